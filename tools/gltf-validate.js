#!/usr/bin/env node
// Runs the Khronos glTF-Validator (npm: gltf-validator) over the glTF/GLB files named on the command
// line and prints one JSON line per file: {"file", "errors", "first", "codes"} (first: the first
// error's code and message; codes: the distinct error codes). External buffers and images are read
// from the file's folder. Used by the tests that cross-check Rayster's loader against the validator
// (tests/unit/test_gltf_validator.cpp, tests/unit/test_gltf_mutations.cpp).
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require(process.env.GLTF_VALIDATOR_MODULE || 'gltf-validator');

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const dir = path.dirname(file);
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const p = path.resolve(dir, decodeURIComponent(uri));
        fs.readFile(p, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
      }),
  });
  const errors = report.issues.numErrors;
  const errorMessages = report.issues.messages.filter((m) => m.severity === 0);
  const first = errorMessages[0];
  return {
    file,
    errors,
    first: first ? `${first.code} ${first.pointer || ''}: ${first.message}` : '',
    codes: [...new Set(errorMessages.map((m) => m.code))],
  };
}

(async () => {
  for (const file of process.argv.slice(2)) {
    try {
      console.log(JSON.stringify(await validate(file)));
    } catch (e) {
      console.log(JSON.stringify({file, errors: -1, first: String(e).split('\n')[0]}));
    }
  }
})();

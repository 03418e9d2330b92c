#!/usr/bin/env node
// Converts the public-domain meshes of the npm packages `teapot` and `bunny` (each exporting
// {positions, cells}) into Rayster's .mesh files (format: assets/meshes/README.md).
//
// Usage: node tools/convert-npm-meshes.js NODE_MODULES_DIR OUT_DIR
//
// Both packages ship coarse meshes (teapot 992, bunny 3,674 triangles) whose facets show in a
// chrome or glass silhouette, so each gets one level of Loop subdivision (our own code below).
// The output is deterministic: the same packages give byte-identical files.
'use strict';
const fs = require('fs');
const path = require('path');

// Levels of Loop subdivision per mesh: one level quadruples the triangles (teapot ~4k, bunny ~15k),
// enough for smooth silhouettes while keeping the embedded data well under 1 MB.
const kMeshes = [
  { pkg: 'teapot', out: 'teapot.mesh', levels: 1 },
  { pkg: 'bunny', out: 'bunny.mesh', levels: 1 },
];

// The teapot's Bezier patches were tessellated separately, so seam vertices are duplicated;
// merging exact duplicates makes the surface one connected piece (smooth normals, no cracks).
function weld(positions, cells) {
  const index = new Map();
  const welded = [];
  const remap = positions.map((p) => {
    const key = p.join(',');
    if (!index.has(key)) {
      index.set(key, welded.length);
      welded.push([p[0], p[1], p[2]]);
    }
    return index.get(key);
  });
  const tris = [];
  for (const c of cells) {
    if (c.length !== 3) throw new Error(`cell with ${c.length} corners; triangles expected`);
    const t = c.map((i) => remap[i]);
    if (t[0] !== t[1] && t[1] !== t[2] && t[0] !== t[2]) tris.push(t);  // drop collapsed ones
  }
  return { positions: welded, cells: tris };
}

const add = (a, b, s) => [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s];

// One level of Loop subdivision (Loop 1987) with the usual boundary rules: boundary edges split
// at their midpoint, boundary vertices follow the cubic B-spline of the boundary curve.
function loopSubdivide({ positions, cells }) {
  const edgeKey = (a, b) => (a < b ? `${a}_${b}` : `${b}_${a}`);
  const edges = new Map();  // key -> {a, b, opposite: [], vertex}
  const neighbours = positions.map(() => new Set());
  for (const t of cells) {
    for (let e = 0; e < 3; e++) {
      const a = t[e], b = t[(e + 1) % 3], c = t[(e + 2) % 3];
      const key = edgeKey(a, b);
      if (!edges.has(key)) edges.set(key, { a, b, opposite: [] });
      edges.get(key).opposite.push(c);
      neighbours[a].add(b);
      neighbours[b].add(a);
    }
  }
  const boundaryNeighbours = positions.map(() => []);
  for (const e of edges.values()) {
    if (e.opposite.length === 1) {
      boundaryNeighbours[e.a].push(e.b);
      boundaryNeighbours[e.b].push(e.a);
    }
  }

  const out = positions.map((p, v) => {
    const bn = boundaryNeighbours[v];
    if (bn.length === 2) return add(add(p.map((x) => x * 0.75), positions[bn[0]], 0.125), positions[bn[1]], 0.125);
    if (bn.length > 0) return p.slice();  // non-manifold corner: keep it where it is
    const n = neighbours[v].size;
    const beta = n === 3 ? 3 / 16 : 3 / (8 * n);
    let q = p.map((x) => x * (1 - n * beta));
    for (const w of neighbours[v]) q = add(q, positions[w], beta);
    return q;
  });
  for (const e of edges.values()) {
    const pa = positions[e.a], pb = positions[e.b];
    let q;
    if (e.opposite.length === 2) {
      q = add(add(pa.map((x) => x * 0.375), pb, 0.375), positions[e.opposite[0]], 0.125);
      q = add(q, positions[e.opposite[1]], 0.125);
    } else {
      q = add(pa.map((x) => x * 0.5), pb, 0.5);
    }
    e.vertex = out.length;
    out.push(q);
  }
  const tris = [];
  for (const [a, b, c] of cells) {
    const ab = edges.get(edgeKey(a, b)).vertex;
    const bc = edges.get(edgeKey(b, c)).vertex;
    const ca = edges.get(edgeKey(c, a)).vertex;
    tris.push([a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]);
  }
  return { positions: out, cells: tris };
}

// "RMSH", uint32 version 1, uint32 vertexCount, uint32 triangleCount, float32 xyz * n,
// uint32 indices * 3t; little-endian.
function encode({ positions, cells }) {
  const buf = Buffer.alloc(16 + positions.length * 12 + cells.length * 12);
  buf.write('RMSH', 0, 'ascii');
  buf.writeUInt32LE(1, 4);
  buf.writeUInt32LE(positions.length, 8);
  buf.writeUInt32LE(cells.length, 12);
  let o = 16;
  for (const p of positions) for (const x of p) { buf.writeFloatLE(x, o); o += 4; }
  for (const t of cells) for (const i of t) { buf.writeUInt32LE(i, o); o += 4; }
  return buf;
}

function main() {
  const [modules, outDir] = process.argv.slice(2);
  if (!modules || !outDir) {
    console.error('usage: convert-npm-meshes.js NODE_MODULES_DIR OUT_DIR');
    process.exit(2);
  }
  fs.mkdirSync(outDir, { recursive: true });
  for (const { pkg, out, levels } of kMeshes) {
    const dir = path.join(modules, pkg);
    const { version, license } = JSON.parse(fs.readFileSync(path.join(dir, 'package.json'), 'utf8'));
    const src = require(path.resolve(dir));
    let mesh = weld(src.positions, src.cells);
    for (let i = 0; i < levels; i++) mesh = loopSubdivide(mesh);
    const bytes = encode(mesh);
    fs.writeFileSync(path.join(outDir, out), bytes);
    console.log(`${out}: ${pkg}@${version} (${license}), ${src.positions.length} -> ${mesh.positions.length} ` +
                `vertices, ${src.cells.length} -> ${mesh.cells.length} triangles, ${bytes.length} bytes`);
  }
}

main();

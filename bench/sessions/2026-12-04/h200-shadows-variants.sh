#!/bin/bash
# The --effects shadows frame on bench/scenes/effects-shadows.json and three variants (no analytic
# spheres, a hard sun, both) with the raw-rate twins: where the 0.70 ms go (issue 16 item 2).
set -u
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
R=dist/rayster-gpu/run.sh
S=bench/scenes/effects-shadows.json
python3 - <<'PY'
import json,re
s=open('bench/scenes/effects-shadows.json').read()
j=json.loads(s)
j2=dict(j); j2['models']=[m for m in j['models'] if 'sphere' not in m['path']]
json.dump(j2,open('/tmp/nosph.json','w'))
j3=json.loads(s); j3['lights'][0]['angularRadius']=0; json.dump(j3,open('/tmp/hard.json','w'))
j4=dict(j2); j4['lights']=j3['lights']; json.dump(j4,open('/tmp/nosph-hard.json','w'))
PY
$R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 | grep frame
for f in $S /tmp/nosph.json /tmp/hard.json /tmp/nosph-hard.json; do
  echo "== $f"
  $R bench $f --size 1920x1080 --warmup 64 --frames 256 --effects shadows --raw-rays --json /tmp/v.json 2>&1 | grep -E " frame|rror"
  python3 -c "
import json; j=json.load(open('/tmp/v.json'))
for c in j['configs']:
  print('  tris', c['scene_stats'])
  for p in c['passes']: print('  ', p['name'], round(p.get('median_ms',0),4), 'raw', round(p.get('raw_ms',0) or 0,4))
"
done

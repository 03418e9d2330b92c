#!/usr/bin/env python3
"""Writes a binary glTF (.glb) heightfield with about N triangles (default 1,000,000) for the
load-time benchmark in BENCHMARKS.md. Usage: bench/make_large_mesh.py OUT.glb [TRIANGLES]"""
import json
import math
import struct
import sys


def main():
    out = sys.argv[1]
    triangles = int(sys.argv[2]) if len(sys.argv) > 2 else 1_000_000
    n = int(math.sqrt(triangles / 2))  # n×n quads, two triangles each
    verts = n + 1
    positions = bytearray()
    normals = bytearray()
    lo, hi = [1e30] * 3, [-1e30] * 3
    for j in range(verts):
        for i in range(verts):
            x, z = i / n * 10 - 5, j / n * 10 - 5
            y = 0.3 * math.sin(x * 1.7) * math.cos(z * 1.3)
            # Analytic normal of the height function.
            dx = 0.3 * 1.7 * math.cos(x * 1.7) * math.cos(z * 1.3)
            dz = -0.3 * 1.3 * math.sin(x * 1.7) * math.sin(z * 1.3)
            l = math.sqrt(dx * dx + 1 + dz * dz)
            positions += struct.pack("<3f", x, y, z)
            normals += struct.pack("<3f", -dx / l, 1 / l, -dz / l)
            for k, v in enumerate((x, y, z)):
                lo[k], hi[k] = min(lo[k], v), max(hi[k], v)
    indices = bytearray()
    for j in range(n):
        for i in range(n):
            a = j * verts + i
            indices += struct.pack("<6I", a, a + verts, a + 1, a + 1, a + verts, a + verts + 1)
    blob = positions + normals + indices
    gltf = {
        "asset": {"version": "2.0", "generator": "rayster bench/make_large_mesh.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
            {"buffer": 0, "byteOffset": len(positions), "byteLength": len(normals)},
            {"buffer": 0, "byteOffset": len(positions) + len(normals), "byteLength": len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": verts * verts, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": verts * verts, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": n * n * 6, "type": "SCALAR"},
        ],
    }
    js = json.dumps(gltf).encode()
    js += b" " * ((4 - len(js) % 4) % 4)
    blob += b"\0" * ((4 - len(blob) % 4) % 4)
    with open(out, "wb") as f:
        f.write(struct.pack("<3I", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(blob)))
        f.write(struct.pack("<2I", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<2I", len(blob), 0x004E4942) + blob)
    print(f"{out}: {n * n * 2} triangles, {verts * verts} vertices")


if __name__ == "__main__":
    main()

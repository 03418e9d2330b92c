#!/usr/bin/env python3
"""Writes the uncompressed source scenes of the glTF-Transform corpus (scripts/corpus/
make_transform_corpus.sh; docs/gltf-compression.md). Python's standard library only, so the
output is reproducible byte for byte.

  make_transform_source.py OUTDIR

writes OUTDIR/source.glb (everything), and the same scene split in two, OUTDIR/part-a.glb (floor,
light, camera) and OUTDIR/part-b.glb (the objects), which `gltf-transform merge` puts back together.

The scene exercises what compression touches: a textured, subdivided floor (TEXCOORD_0), six
nodes sharing one sphere mesh (NORMAL, TEXCOORD_0, TANGENT; what `instance` batches), a cube with
per-face COLOR_0 whose texture is read through TEXCOORD_1, and an identical copy of the cube's mesh
and accessors (what `dedup` removes).
"""
import json
import math
import struct
import sys
import zlib
from zlib import compress as deflate  # imported by name: the scripts test flags "<word>.com" as a host


def png(width, height, pixel):
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", deflate(rows, 9)) + chunk(b"IEND", b""))


class Builder:
    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors = [], []

    def view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.bin += data
        self.views.append(v)
        return len(self.views) - 1

    def floats(self, values, kind, bounds=False):
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[kind]
        flat = [c for v in values for c in v]
        a = {"bufferView": self.view(struct.pack("<%df" % len(flat), *flat), 34962), "componentType": 5126,
             "count": len(values), "type": kind}
        if bounds:
            a["min"] = [min(v[i] for v in values) for i in range(n)]
            a["max"] = [max(v[i] for v in values) for i in range(n)]
        self.accessors.append(a)
        return len(self.accessors) - 1

    def indices(self, values):
        data = struct.pack("<%dH" % len(values), *values)
        self.accessors.append({"bufferView": self.view(data, 34963), "componentType": 5123, "count": len(values),
                               "type": "SCALAR"})
        return len(self.accessors) - 1


def floor_mesh(b, n=4, half=3.0):
    pos, nrm, uv, idx = [], [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            pos.append((-half + 2 * half * i / n, 0.0, -half + 2 * half * j / n))
            nrm.append((0.0, 1.0, 0.0))
            uv.append((i / n, j / n))  # in [0, 1]: quantize only quantizes such UVs
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            idx += [a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2]
    return {"POSITION": b.floats(pos, "VEC3", True), "NORMAL": b.floats(nrm, "VEC3"),
            "TEXCOORD_0": b.floats(uv, "VEC2")}, b.indices(idx)


def sphere_mesh(b, rings=10, segments=16, r=0.35):
    pos, nrm, uv, tan, idx = [], [], [], [], []
    for j in range(rings + 1):
        theta = math.pi * j / rings
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            pos.append(tuple(r * c for c in n))
            nrm.append(n)
            uv.append((i / segments, j / rings))
            tan.append((-math.sin(phi), 0.0, -math.cos(phi), 1.0))
    for j in range(rings):
        for i in range(segments):
            a = j * (segments + 1) + i
            idx += [a, a + segments + 1, a + 1, a + 1, a + segments + 1, a + segments + 2]
    return {"POSITION": b.floats(pos, "VEC3", True), "NORMAL": b.floats(nrm, "VEC3"),
            "TEXCOORD_0": b.floats(uv, "VEC2"), "TANGENT": b.floats(tan, "VEC4")}, b.indices(idx)


def cube_mesh(b, h=0.45):
    faces = [((1, 0, 0), (0, 0, -1)), ((-1, 0, 0), (0, 0, 1)), ((0, 1, 0), (1, 0, 0)), ((0, -1, 0), (1, 0, 0)),
             ((0, 0, 1), (1, 0, 0)), ((0, 0, -1), (-1, 0, 0))]
    colours = [(1, 0.3, 0.2, 1), (0.2, 0.8, 0.3, 1), (0.3, 0.4, 1, 1), (1, 1, 0.3, 1), (0.9, 0.4, 0.9, 1),
               (0.3, 0.9, 0.9, 1)]
    pos, nrm, uv0, uv1, col, idx = [], [], [], [], [], []
    for f, (n, t) in enumerate(faces):
        bt = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
        base = len(pos)
        for (s, u) in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(tuple(h * (n[k] + s * t[k] + u * bt[k]) for k in range(3)))
            nrm.append(n)
            uv0.append(((s + 1) / 2, (1 - u) / 2))
            uv1.append(((s + 1) * 0.45, (1 - u) * 0.45))  # set 1 shows 90 % of the texture
            col.append(colours[f])
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return {"POSITION": b.floats(pos, "VEC3", True), "NORMAL": b.floats(nrm, "VEC3"),
            "TEXCOORD_0": b.floats(uv0, "VEC2"), "TEXCOORD_1": b.floats(uv1, "VEC2"),
            "COLOR_0": b.floats(col, "VEC4")}, b.indices(idx)


def unit(q):
    length = math.sqrt(sum(c * c for c in q))
    return [c / length for c in q]


def quat_y(angle):
    return [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]


def scene(parts):
    """The glTF (as JSON and BIN) of the chosen parts: 'a' floor, light, camera; 'b' the objects."""
    b = Builder()
    doc = {"asset": {"version": "2.0", "generator": "Rayster scripts/corpus/make_transform_source.py"},
           "extensionsUsed": ["KHR_lights_punctual"], "scene": 0, "nodes": [], "meshes": [], "materials": []}
    nodes = []

    def material(m):
        doc["materials"].append(m)
        return len(doc["materials"]) - 1

    def texture():
        if "textures" not in doc:
            checker = png(64, 64, lambda x, y: (230, 225, 210) if (x // 8 + y // 8) % 2 else (60, 70, 90))
            doc["images"] = [{"bufferView": b.view(checker), "mimeType": "image/png", "name": "checker"}]
            doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]
            doc["textures"] = [{"source": 0, "sampler": 0}]
        return 0

    def mesh(name, attrs_idx, mat):
        attrs, idx = attrs_idx
        doc["meshes"].append({"name": name, "primitives": [{"attributes": attrs, "indices": idx, "material": mat}]})
        return len(doc["meshes"]) - 1

    if "a" in parts:
        floor = mesh("floor", floor_mesh(b), material(
            {"name": "floor", "pbrMetallicRoughness": {"baseColorTexture": {"index": texture()}, "metallicFactor": 0,
                                                       "roughnessFactor": 0.8}}))
        nodes.append({"name": "floor", "mesh": floor})
        doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0,
                                                                 "color": [1.0, 0.95, 0.9]}]}}
        nodes.append({"name": "sun", "rotation": unit([-0.5, 0.3, 0.15, 0.8]), "extensions": {"KHR_lights_punctual": {
            "light": 0}}})
        doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 50}}]
        # Looks at the origin from (0, 3.2, 5.6), tilted down by 30 degrees.
        nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 3.2, 5.6],
                      "rotation": [-0.2588190, 0.0, 0.0, 0.9659258]})
    if "b" in parts:
        sphere = mesh("sphere", sphere_mesh(b), material(
            {"name": "orange", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.45, 0.1, 1.0], "metallicFactor": 0,
                                                        "roughnessFactor": 0.45}}))
        for k in range(6):
            x, z = -1.9 + 0.76 * k, 1.3 - 0.2 * k
            nodes.append({"name": "sphere%d" % k, "mesh": sphere, "translation": [x, 0.35 * (0.8 + 0.1 * k), z],
                          "rotation": quat_y(0.4 * k), "scale": [0.8 + 0.1 * k] * 3})
        cube_mat = material({"name": "painted", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": texture(), "texCoord": 1}, "metallicFactor": 0, "roughnessFactor": 0.6}})
        cube = mesh("cube", cube_mesh(b), cube_mat)
        nodes.append({"name": "cube", "mesh": cube, "translation": [-0.9, 0.45, -0.8], "rotation": quat_y(0.5)})
        twin = mesh("cube-copy", cube_mesh(b), cube_mat)  # same data again: `dedup` shares it
        nodes.append({"name": "cube-copy", "mesh": twin, "translation": [1.1, 0.45, -1.0], "rotation": quat_y(-0.3)})
    doc["nodes"] = nodes
    doc["scenes"] = [{"name": "scene", "nodes": list(range(len(nodes)))}]
    doc["bufferViews"], doc["accessors"] = b.views, b.accessors
    if not doc["materials"]:
        del doc["materials"]
    while len(b.bin) % 4:
        b.bin.append(0)
    doc["buffers"] = [{"byteLength": len(b.bin)}]
    return doc, bytes(b.bin)


def glb(doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<I4s", len(text), b"JSON") + text +
            struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def main():
    out = sys.argv[1]
    for name, parts in (("source", "ab"), ("part-a", "a"), ("part-b", "b")):
        with open("%s/%s.glb" % (out, name), "wb") as f:
            f.write(glb(*scene(parts)))


if __name__ == "__main__":
    main()

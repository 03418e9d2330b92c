"""A pure-Lambert variant of a corpus scene, to check light units apart from BRDF differences.

    python3 scripts/corpus/lambert_variant.py IN.glb OUT.glb
        every material becomes a dielectric (metallic 0, no transmission) with KHR_materials_specular
        specularFactor 0: Rayster's BRDF is then exactly base colour / pi (no specular lobe, no
        (1 - F) on the diffuse);
    blender -b IN.blend --python scripts/corpus/lambert_variant.py -- OUT.blend
        every Principled BSDF is replaced by a Diffuse BSDF of roughness 0 (Lambert) of its colour.

Rayster and Cycles then agree on the mean to sampling noise, so any remaining difference on the
real scenes is the materials' (Principled BSDF vs glTF's BRDF), not the units (docs/corpus.md).
"""
import json
import struct
import sys

kGlbMagic, kJsonChunk = 0x46546C67, 0x4E4F534A


def lambert_glb(src, dst):
    data = open(src, "rb").read()
    json_length, chunk_type = struct.unpack("<II", data[12:20])
    if struct.unpack("<I", data[:4])[0] != kGlbMagic or chunk_type != kJsonChunk:
        sys.exit(f"{src}: not a GLB file")
    document = json.loads(data[20:20 + json_length])
    rest = data[20 + json_length:]
    for material in document.get("materials", []):
        material.setdefault("pbrMetallicRoughness", {})["metallicFactor"] = 0.0
        extensions = material.setdefault("extensions", {})
        for name in ("KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior"):
            extensions.pop(name, None)
        extensions["KHR_materials_specular"] = {"specularFactor": 0.0}
    used = document.setdefault("extensionsUsed", [])
    if "KHR_materials_specular" not in used:
        used.append("KHR_materials_specular")
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)  # chunks are 4-byte aligned, JSON padded with spaces
    header = struct.pack("<III", kGlbMagic, 2, 12 + 8 + len(text) + len(rest))
    with open(dst, "wb") as f:
        f.write(header + struct.pack("<II", len(text), kJsonChunk) + text + rest)


def lambert_blend(dst):
    import bpy
    for material in bpy.data.materials:
        nodes = material.node_tree.nodes if material.use_nodes else None
        bsdf = nodes.get("Principled BSDF") if nodes else None
        if bsdf is None:
            continue
        diffuse = nodes.new('ShaderNodeBsdfDiffuse')
        diffuse.inputs["Roughness"].default_value = 0.0
        color = bsdf.inputs["Base Color"]
        if color.links:
            material.node_tree.links.new(color.links[0].from_socket, diffuse.inputs["Color"])
        else:
            diffuse.inputs["Color"].default_value = color.default_value
        surface = diffuse.outputs["BSDF"]
        alpha = bsdf.inputs["Alpha"]
        if alpha.links:  # keep cut-outs: mix with a transparent BSDF by the (thresholded) alpha
            mix = nodes.new('ShaderNodeMixShader')
            clear = nodes.new('ShaderNodeBsdfTransparent')
            material.node_tree.links.new(alpha.links[0].from_socket, mix.inputs["Fac"])
            material.node_tree.links.new(clear.outputs["BSDF"], mix.inputs[1])
            material.node_tree.links.new(surface, mix.inputs[2])
            surface = mix.outputs["Shader"]
        output = next(n for n in nodes if n.type == 'OUTPUT_MATERIAL' and n.is_active_output)
        material.node_tree.links.new(surface, output.inputs["Surface"])
    bpy.ops.wm.save_as_mainfile(filepath=dst, check_existing=False)


if "--" in sys.argv:
    lambert_blend(sys.argv[sys.argv.index("--") + 1])
elif len(sys.argv) == 3:
    lambert_glb(sys.argv[1], sys.argv[2])
else:
    sys.exit(__doc__)

"""Build Rayster's glTF test corpus with Blender's own glTF exporter.

    blender -b --factory-startup --python scripts/corpus/make_corpus.py -- OUTDIR [BLENDDIR]

writes OUTDIR/{room,atrium,product,foliage}.glb, product.json, foliage.json and studio.hdr, and the
same scenes as BLENDDIR/*.blend (default OUTDIR) for Cycles references (scripts/corpus/cycles.sh).
Everything is built procedurally here; see assets/corpus/README.md and docs/corpus.md.
"""
import json
import os
import re
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import corpus_lib  # noqa: E402
import corpus_scenes  # noqa: E402

# The exporter's "Standard" lighting mode writes W x 683 lm/W (point lights / 4 pi sr); Rayster
# takes glTF numbers as radiometric, so its scene files scale the environment by the same factor
# to keep the balance between the lights and the world that the .blend has.
kLumensPerWatt = 683.0


def export_glb(path):
    bpy.ops.export_scene.gltf(filepath=path, export_format='GLB', export_cameras=True, export_lights=True,
                              export_extras=True, export_yup=True, export_apply=True)


def write_scene_file(path, glb, environment):
    text = json.dumps({"name": os.path.splitext(os.path.basename(path))[0], "models": [{"path": glb}],
                       "environment": environment}, indent=2)
    # Arrays of numbers on one line, as in docs/scene-format.md.
    text = re.sub(r"\[\s+([-0-9.,\s]+?)\s+\]", lambda m: "[" + re.sub(r",\s+", ", ", m.group(1)) + "]", text)
    with open(path, "w") as f:
        f.write(text + "\n")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) not in (1, 2):
        sys.exit("usage: blender -b --factory-startup --python make_corpus.py -- OUTDIR [BLENDDIR]")
    out = os.path.abspath(args[0])
    blend_dir = os.path.abspath(args[1]) if len(args) == 2 else out
    os.makedirs(out, exist_ok=True)
    os.makedirs(blend_dir, exist_ok=True)

    studio = os.path.join(out, "studio.hdr")
    corpus_lib.write_radiance_hdr(studio, corpus_scenes.studio_environment())
    builders = (corpus_scenes.build_room, corpus_scenes.build_atrium,
                lambda: corpus_scenes.build_product(studio), corpus_scenes.build_foliage)
    for build in builders:
        corpus_lib.reset_scene()
        scene = build()
        export_glb(os.path.join(out, scene.name + ".glb"))
        scene.prepare_for_cycles()
        bpy.ops.wm.save_as_mainfile(filepath=os.path.join(blend_dir, scene.name + ".blend"), check_existing=False,
                                    compress=True)

    write_scene_file(os.path.join(out, "product.json"), "product.glb",
                     {"map": "studio.hdr", "intensity": kLumensPerWatt, "rotation": 0})
    sky = {"zenith": list(corpus_scenes.kSkyZenith), "horizon": list(corpus_scenes.kSkyHorizon),
           "ground": list(corpus_scenes.kSkyGround)}
    write_scene_file(os.path.join(out, "foliage.json"), "foliage.glb", {"sky": sky, "intensity": kLumensPerWatt})


main()

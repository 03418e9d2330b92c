"""Render the open .blend with Cycles as a reference for Rayster's path tracer.

    blender -b SCENE.blend --python scripts/corpus/cycles_render.py -- OUT.exr [SAMPLES]

Linear full-float OpenEXR at the .blend's size (160x120), CPU, no denoiser, no clamping, view
transform "Standard" at exposure 0, a 1-pixel box filter (Rayster's path tracer box-filters), and
8 bounces: 9 surface vertices, like `rayster render --mode pathtrace --max-depth 9`.
"""
import sys

import bpy

kBounces = 8  # Cycles counts bounces after the first hit; Rayster's --max-depth counts the hits


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) not in (1, 2):
        sys.exit("usage: blender -b SCENE.blend --python cycles_render.py -- OUT.exr [SAMPLES]")
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    cycles = scene.cycles
    cycles.device = 'CPU'
    cycles.samples = int(args[1]) if len(args) == 2 else 256
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.seed = 0
    cycles.sample_clamp_direct = 0.0  # 0 = off (the default clamps indirect light at 10)
    cycles.sample_clamp_indirect = 0.0
    cycles.max_bounces = kBounces
    cycles.diffuse_bounces = cycles.glossy_bounces = cycles.transmission_bounces = kBounces
    cycles.volume_bounces = 0
    cycles.transparent_max_bounces = 64  # alpha-masked leaves: a mask is not a surface vertex
    cycles.caustics_reflective = cycles.caustics_refractive = True
    cycles.blur_glossy = 0.0
    cycles.pixel_filter_type = 'BOX'
    cycles.filter_width = 1.0
    cycles.film_exposure = 1.0
    scene.render.film_transparent = False
    scene.view_settings.view_transform = 'Standard'
    scene.view_settings.look = 'None'
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR'
    settings.color_depth = '32'
    settings.color_mode = 'RGBA'
    settings.exr_codec = 'ZIP'
    scene.render.filepath = args[0]
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)


main()

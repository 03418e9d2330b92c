"""The four corpus scenes of make_corpus.py, each built into an empty Blender scene.

Each builder also sets the Cycles world (glTF carries none; it matches what the Rayster scene file
sets) and returns a Scene: the name of its files and any edit of the .blend the exporter must not see.
Light strengths are Blender's (point: W, sun: W/m^2), chosen so that Cycles at exposure 0 with the
"Standard" view looks right; the README explains what the exporter and Rayster make of them.
"""
import math
from dataclasses import dataclass
from typing import Callable

import bpy
import numpy as np

from corpus_lib import (black_world, box, camera, cylinder, kGreen, kRed, kWhite, map_world, masked_texture_material,
                        mesh_object, packed_image, point_light, principled, quads, set_volume_thickness, sky_world,
                        sun_light, threshold_alpha_for_cycles, uv_sphere)

# Rayster's default sky colours (scene/scene.h), used for foliage.json and its Cycles world.
kSkyZenith = (0.25, 0.45, 0.9)
kSkyHorizon = (0.85, 0.9, 1.0)
kSkyGround = (0.3, 0.28, 0.25)


@dataclass
class Scene:
    name: str
    prepare_for_cycles: Callable[[], None] = lambda: None


def shell(name, lo, hi, thickness, materials, hole=None):
    """A closed room of thin boxes around the interior `lo`..`hi` (walls overlap at the corners, so
    no light leaks through a crack). `materials`: floor, ceiling, -x, +x, -y, +y walls. `hole`:
    ((x0, y0), (x1, y1)), an opening in the ceiling."""
    (x0, y0, z0), (x1, y1, z1), t = lo, hi, thickness
    floor, ceiling, west, east, south, north = materials
    box(f"{name}-floor", (x0 - t, y0 - t, z0 - t), (x1 + t, y1 + t, z0), floor)
    box(f"{name}-wall-west", (x0 - t, y0 - t, z0 - t), (x0, y1 + t, z1 + t), west)
    box(f"{name}-wall-east", (x1, y0 - t, z0 - t), (x1 + t, y1 + t, z1 + t), east)
    box(f"{name}-wall-south", (x0 - t, y0 - t, z0 - t), (x1 + t, y0, z1 + t), south)
    box(f"{name}-wall-north", (x0 - t, y1, z0 - t), (x1 + t, y1 + t, z1 + t), north)
    if hole is None:
        box(f"{name}-ceiling", (x0 - t, y0 - t, z1), (x1 + t, y1 + t, z1 + t), ceiling)
        return
    (hx0, hy0), (hx1, hy1) = hole
    box(f"{name}-ceiling-south", (x0 - t, y0 - t, z1), (x1 + t, hy0, z1 + t), ceiling)
    box(f"{name}-ceiling-north", (x0 - t, hy1, z1), (x1 + t, y1 + t, z1 + t), ceiling)
    box(f"{name}-ceiling-west", (x0 - t, hy0, z1), (hx0, hy1, z1 + t), ceiling)
    box(f"{name}-ceiling-east", (hx1, hy0, z1), (x1 + t, hy1, z1 + t), ceiling)


def build_room():
    """A Cornell-like closed room (red west wall, green east wall), two boxes, one point light."""
    white, red, green = (principled(n, c) for n, c in (("white", kWhite), ("red", kRed), ("green", kGreen)))
    shell("room", (-2.0, -2.0, 0.0), (2.0, 2.0, 2.8), 0.1, (white, white, red, green, white, white))
    box("tall-box", (-1.2, 0.0, 0.0), (-0.4, 0.8, 1.6), white, rotation_z=math.radians(20))
    box("short-box", (0.3, -0.9, 0.0), (1.1, -0.1, 0.8), white, rotation_z=math.radians(-18))
    point_light("ceiling-light", (0.0, 0.2, 2.55), watts=50.0, radius=0.05)
    camera("camera", (0.0, -1.9, 1.4), (0.0, 1.0, 1.2), yfov_degrees=62)
    black_world()
    return Scene("room")


def build_atrium():
    """A hall lit only by a sun through an opening in its roof: a bright patch, the rest indirect."""
    plaster = principled("plaster", (0.75, 0.72, 0.66))
    stone = principled("stone", (0.45, 0.43, 0.4))
    blue = principled("blue-wall", (0.25, 0.35, 0.6))
    shell("atrium", (-3.0, -3.0, 0.0), (3.0, 3.0, 4.0), 0.15, (stone, plaster, plaster, blue, plaster, plaster),
          hole=((-1.2, -1.8), (1.2, 0.0)))
    box("pillar-west", (-2.0, 1.2, 0.0), (-1.6, 1.6, 4.0), plaster)
    box("pillar-east", (1.6, 1.2, 0.0), (2.0, 1.6, 4.0), plaster)
    box("bench", (-0.9, 1.9, 0.0), (0.9, 2.4, 0.45), stone)
    # Elevation 58 degrees, travelling north (+y) and a little east: the patch lands on the floor
    # in front of the pillars and climbs the bench.
    elevation, azimuth = math.radians(58), math.radians(12)
    travel = (math.sin(azimuth) * math.cos(elevation), math.cos(azimuth) * math.cos(elevation), -math.sin(elevation))
    sun_light("sun", travel, strength=20.0)
    camera("camera", (0.4, -2.8, 1.5), (-0.1, 1.5, 0.9), yfov_degrees=60)
    black_world()
    return Scene("atrium")


def cyclorama(name, mat, width=10.0, depth=6.0, radius=1.5, height=5.0, steps=8):
    """A photo studio's backdrop: a floor curving up into a back wall (smooth across the curve)."""
    profile = [(-depth / 2, 0.0)]
    for k in range(steps + 1):
        a = -math.pi / 2 + (math.pi / 2) * k / steps
        profile.append((depth / 2 + radius * math.cos(a), radius + radius * math.sin(a)))
    profile.append((depth / 2 + radius, height))
    verts = [(x, y, z) for y, z in profile for x in (-width / 2, width / 2)]
    faces = [(2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2) for k in range(len(profile) - 1)]
    return mesh_object(name, verts, faces, mat, smooth=True)


def build_product(studio_hdr):
    """Gold, glass and plastic on a studio backdrop; the environment comes from product.json
    (`studio_hdr` at 1 W/(m^2 sr) per unit in Cycles, x683 in Rayster)."""
    cyclorama("backdrop", principled("backdrop", (0.5, 0.5, 0.5), roughness=0.7))
    uv_sphere("gold-sphere", 0.45, 32, 16, principled("gold", (1.0, 0.77, 0.34), roughness=0.15, metallic=1.0),
              location=(-1.0, 0.3, 0.45))
    glass = principled("glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5)
    set_volume_thickness(glass, 0.7)  # the cylinder's diameter
    cylinder("glass-cylinder", 0.35, 0.8, 32, glass, location=(0.05, 0.8, 0.0))
    bpy.ops.mesh.primitive_monkey_add(size=0.9, location=(1.0, 0.1, 0.45))
    plastic = bpy.context.object
    plastic.name = "plastic-monkey"
    plastic.rotation_euler = (0.0, 0.0, math.radians(-15))
    plastic.data.materials.append(principled("red-plastic", (0.8, 0.08, 0.04), roughness=0.4))
    plastic.data.polygons.foreach_set("use_smooth", [True] * len(plastic.data.polygons))
    # The environment does most of the work; a weak key light exercises the exporter's units.
    point_light("key", (-2.0, -2.5, 3.0), watts=30.0, radius=0.15)
    camera("camera", (0.0, -4.2, 1.5), (0.0, 0.4, 0.45), yfov_degrees=30)
    image = bpy.data.images.load(studio_hdr)
    image.pack()
    map_world(image, strength=1.0)
    return Scene("product")


def leaf_texture(size=128, leaves=36, seed=7):
    """A cluster of leaves (alpha 1) on nothing (alpha 0), sRGB-encoded RGBA, top row first.
    Transparent texels keep a leaf colour so filtering does not darken the edges."""
    rng = np.random.default_rng(seed)
    v, u = np.mgrid[0:size, 0:size] / (size - 1.0)
    rgba = np.zeros((size, size, 4))
    rgba[..., :3] = (0.25, 0.45, 0.12)
    for _ in range(leaves):
        r, a = 0.36 * math.sqrt(rng.random()), rng.random() * 2 * math.pi
        cu, cv = 0.5 + r * math.cos(a), 0.5 + r * math.sin(a)
        turn = rng.random() * math.pi
        du, dv = u - cu, v - cv
        along = du * math.cos(turn) + dv * math.sin(turn)
        across = -du * math.sin(turn) + dv * math.cos(turn)
        inside = (along / 0.075) ** 2 + (across / 0.03) ** 2 <= 1.0
        shade = np.array((0.18, 0.42, 0.08)) * (0.7 + 0.6 * rng.random())
        rib = np.abs(across) < 0.004
        rgba[inside, :3] = shade
        rgba[inside & rib, :3] = shade * 1.4
        rgba[inside, 3] = 1.0
    return np.clip(rgba, 0.0, 1.0)


def build_foliage():
    """Trees and bushes of alpha-masked quads on a meadow, under a sun; sky from foliage.json."""
    mesh_object("ground", [(-15, -15, 0), (15, -15, 0), (15, 15, 0), (-15, 15, 0)], [(0, 1, 2, 3)],
                principled("meadow", (0.22, 0.3, 0.12)))
    leaves = masked_texture_material("leaves", packed_image("leaves", leaf_texture()))
    bark = principled("bark", (0.25, 0.16, 0.09), roughness=0.9)
    for k, (x, y, height) in enumerate(((-2.2, 1.5, 2.6), (1.8, 3.0, 3.2), (0.2, 6.0, 2.8))):
        cylinder(f"trunk{k}", 0.12, height, 8, bark, location=(x, y, 0.0))
        crown = [((x, y, height + 0.5), 2.6, 2.6, math.radians(a + 20 * k), 0.0) for a in (0, 60, 120)]
        crown += [((x, y, height + 0.6), 2.2, 2.2, math.radians(35 * k), math.pi / 2)]
        quads(f"crown{k}", crown, leaves)
    for k, (x, y) in enumerate(((-0.6, -0.8), (0.9, 0.2), (3.2, 1.0), (-3.4, 3.6))):
        bush = [((x, y, 0.45), 1.1, 0.9, math.radians(a + 25 * k), 0.0) for a in (0, 90)]
        quads(f"bush{k}", bush, leaves)
    # Elevation 40 degrees, from behind the camera's right: side-lit crowns, long shadows.
    elevation, azimuth = math.radians(40), math.radians(-50)
    travel = (math.sin(azimuth) * math.cos(elevation), math.cos(azimuth) * math.cos(elevation), -math.sin(elevation))
    sun_light("sun", travel, strength=4.0, color=(1.0, 0.96, 0.9))
    camera("camera", (0.3, -7.0, 1.6), (0.0, 2.0, 1.9), yfov_degrees=45)
    sky_world(kSkyZenith, kSkyHorizon, kSkyGround, strength=1.0)
    return Scene("foliage", prepare_for_cycles=lambda: threshold_alpha_for_cycles(leaves))


def studio_environment(width=128, height=64):
    """A studio: dim grey walls and three round softboxes with soft edges, as equirectangular
    radiance in Rayster's layout (top row +Y; u = 0.5 towards glTF -Z = Blender +Y, growing
    towards +X). Directions below are Blender's (z up) pointing at each softbox."""
    v, u = (np.mgrid[0:height, 0:width] + 0.5) / np.array((height, width))[:, None, None]
    theta, alpha = v * math.pi, (u - 0.5) * 2 * math.pi
    d = np.stack((np.sin(theta) * np.sin(alpha), np.sin(theta) * np.cos(alpha), np.cos(theta)), axis=-1)
    up = np.clip(d[..., 2], 0.0, 1.0)[..., None]
    rgb = np.where(d[..., 2:] >= 0.0, 0.08 + 0.07 * up, 0.04) * np.array((1.0, 0.98, 0.95))
    softboxes = (((-1.2, -1.0, 1.1), 18.0, 6.0),  # key: front left, above
                 ((1.3, -0.6, 0.5), 22.0, 2.0),  # fill: right
                 ((0.0, 0.3, 1.0), 15.0, 3.0))  # top
    for towards, radius_degrees, radiance in softboxes:
        c = np.array(towards) / np.linalg.norm(towards)
        angle = np.degrees(np.arccos(np.clip(d @ c, -1.0, 1.0)))
        edge = np.clip((radius_degrees - angle) / 4.0, 0.0, 1.0)  # 4 degree soft edge
        rgb += (radiance * edge * edge * (3 - 2 * edge))[..., None]
    return rgb

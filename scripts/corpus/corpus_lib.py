"""Helpers for make_corpus.py: meshes, materials, lights, cameras, worlds and images built with bpy.

Everything is procedural (no external assets). Coordinates are Blender's (Z up); the glTF exporter
converts to glTF's Y up (Blender (x, y, z) -> glTF (x, z, -y)).
"""
import math

import bpy
import numpy as np
from mathutils import Vector

# One place for the render size: the exported camera's aspect ratio and the Cycles references.
kWidth, kHeight = 160, 120

# Cornell-box-like albedos (linear).
kWhite = (0.73, 0.73, 0.73)
kRed = (0.63, 0.065, 0.05)
kGreen = (0.14, 0.45, 0.09)


def reset_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    scene.render.resolution_x, scene.render.resolution_y = kWidth, kHeight
    scene.render.resolution_percentage = 100
    return scene


def link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


# ---- materials -------------------------------------------------------------------------------

def principled(name, color, roughness=1.0, metallic=0.0, transmission=0.0, ior=1.5):
    """A Principled BSDF material with only the inputs glTF's metallic-roughness model carries."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior
    return mat


def set_volume_thickness(mat, thickness):
    """Add the exporter's 'glTF Material Output' group with a Thickness, so KHR_materials_volume is
    written: without it a transmissive glTF material is thin-walled, while Cycles refracts solids."""
    group = bpy.data.node_groups.get("glTF Material Output")
    if group is None:
        group = bpy.data.node_groups.new("glTF Material Output", 'ShaderNodeTree')
        group.inputs.new('NodeSocketFloat', "Thickness")
    node = mat.node_tree.nodes.new('ShaderNodeGroup')
    node.node_tree = group
    node.inputs["Thickness"].default_value = thickness


def masked_texture_material(name, image, cutoff=0.5):
    """Base colour and alpha from `image`, alpha-tested (blend mode CLIP: glTF alphaMode MASK)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 0.7
    tex = nodes.new('ShaderNodeTexImage')
    tex.image = image
    links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    mat.blend_method = 'CLIP'
    mat.shadow_method = 'CLIP'
    mat.alpha_threshold = cutoff
    return mat


def threshold_alpha_for_cycles(mat):
    """Cycles ignores blend_method and treats alpha as coverage; a step at alpha_threshold makes it
    the same binary test as glTF's MASK (done after export: the exporter wants a direct link)."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    source = bsdf.inputs["Alpha"].links[0].from_socket
    step = nodes.new('ShaderNodeMath')
    step.operation = 'GREATER_THAN'
    step.inputs[1].default_value = mat.alpha_threshold
    links.new(source, step.inputs[0])
    links.new(step.outputs[0], bsdf.inputs["Alpha"])


# ---- meshes ----------------------------------------------------------------------------------

def mesh_object(name, verts, faces, mat, smooth=False, uvs=None, location=(0, 0, 0), rotation_z=0.0):
    """A mesh from vertices and faces (counter-clockwise seen from the front); `uvs` gives one
    (u, v) per face corner, in face order."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in verts], [], [tuple(f) for f in faces])
    if uvs is not None:
        layer = mesh.uv_layers.new(name="UVMap")
        for loop, uv in zip(layer.data, uvs):
            loop.uv = uv
    mesh.polygons.foreach_set("use_smooth", [smooth] * len(mesh.polygons))
    mesh.materials.append(mat)
    mesh.validate()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    obj.rotation_euler = (0.0, 0.0, rotation_z)
    return link(obj)


# Outward-facing quads of a box whose corner i has x = bit 0, y = bit 1, z = bit 2 of i.
kBoxFaces = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]


def box(name, lo, hi, mat, rotation_z=0.0):
    """An axis-aligned box from corner `lo` to `hi`, optionally turned about its vertical axis."""
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    half = [(b - a) / 2 for a, b in zip(lo, hi)]
    verts = [[(half[k] if (i >> k) & 1 else -half[k]) for k in range(3)] for i in range(8)]
    return mesh_object(name, verts, kBoxFaces, mat, location=centre, rotation_z=rotation_z)


def cylinder(name, radius, height, segments, mat, location, smooth=True):
    """A closed cylinder standing on z = 0 of its local frame."""
    ring = [(radius * math.cos(2 * math.pi * k / segments), radius * math.sin(2 * math.pi * k / segments))
            for k in range(segments)]
    verts = [(x, y, 0.0) for x, y in ring] + [(x, y, height) for x, y in ring]
    sides = [(k, (k + 1) % segments, segments + (k + 1) % segments, segments + k) for k in range(segments)]
    caps = [tuple(reversed(range(segments))), tuple(range(segments, 2 * segments))]
    obj = mesh_object(name, verts, sides + caps, mat, location=location)
    # Smooth sides, flat caps: mark only the side faces smooth.
    obj.data.polygons.foreach_set("use_smooth", [smooth] * segments + [False, False])
    return obj


def uv_sphere(name, radius, segments, rings, mat, location):
    verts = [(0.0, 0.0, -radius)]
    for r in range(1, rings):
        theta = math.pi * r / rings - math.pi / 2
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            verts.append((radius * math.cos(theta) * math.cos(phi), radius * math.cos(theta) * math.sin(phi),
                          radius * math.sin(theta)))
    verts.append((0.0, 0.0, radius))
    top = len(verts) - 1

    def at(r, s):  # ring r in 1..rings-1
        return 1 + (r - 1) * segments + s % segments

    faces = [(0, at(1, s + 1), at(1, s)) for s in range(segments)]
    faces += [(at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)) for r in range(1, rings - 1)
              for s in range(segments)]
    faces += [(at(rings - 1, s), at(rings - 1, s + 1), top) for s in range(segments)]
    return mesh_object(name, verts, faces, mat, smooth=True, location=location)


def quads(name, specs, mat):
    """Textured quads, each spec (centre, width, height, angle about z, tilt): a quad of the full
    texture, vertical (tilt 0) or tilted back about its own horizontal axis (tilt pi/2 = flat)."""
    verts, faces, uvs = [], [], []
    for centre, width, height, angle, tilt in specs:
        right = Vector((math.cos(angle), math.sin(angle), 0.0)) * (width / 2)
        up = Vector((-math.sin(angle) * math.sin(tilt), math.cos(angle) * math.sin(tilt), math.cos(tilt)))
        base = Vector(centre) - up * (height / 2)
        first = len(verts)
        verts += [base - right, base + right, base + right + up * height, base - right + up * height]
        faces.append((first, first + 1, first + 2, first + 3))
        uvs += [(0, 0), (1, 0), (1, 1), (0, 1)]
    return mesh_object(name, verts, faces, mat, uvs=uvs)


# ---- lights and cameras ----------------------------------------------------------------------

def look_rotation(position, target):
    return (Vector(target) - Vector(position)).to_track_quat('-Z', 'Y').to_euler()


def camera(name, position, target, yfov_degrees):
    data = bpy.data.cameras.new(name)
    data.sensor_fit = 'VERTICAL'
    data.angle_y = math.radians(yfov_degrees)
    data.clip_start, data.clip_end = 0.05, 100.0
    obj = link(bpy.data.objects.new(name, data))
    obj.location = position
    obj.rotation_euler = look_rotation(position, target)
    bpy.context.scene.camera = obj
    return obj


def point_light(name, position, watts, radius, color=(1.0, 1.0, 1.0)):
    """A Blender point light of `watts` (Cycles: radiant intensity watts / 4 pi W/sr). Its radius
    goes to the glTF light's extras, where Rayster reads sphere-light sizes."""
    data = bpy.data.lights.new(name, 'POINT')
    data.energy = watts
    data.color = color
    data.shadow_soft_size = radius
    data["radius"] = radius
    obj = link(bpy.data.objects.new(name, data))
    obj.location = position
    return obj


def sun_light(name, travel, strength, angle_degrees=0.53, color=(1.0, 1.0, 1.0)):
    """A sun of `strength` W/m^2 (irradiance on a surface facing it) whose light travels along
    `travel`; the angular diameter goes to extras as Rayster's angularRadius (radians)."""
    data = bpy.data.lights.new(name, 'SUN')
    data.energy = strength
    data.color = color
    data.angle = math.radians(angle_degrees)
    data["angularRadius"] = data.angle / 2
    obj = link(bpy.data.objects.new(name, data))
    obj.location = (0.0, 0.0, 10.0)
    obj.rotation_euler = Vector(travel).to_track_quat('-Z', 'Y').to_euler()
    return obj


# ---- worlds (Cycles only: glTF carries no world) ---------------------------------------------

def black_world():
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    bpy.context.scene.world = world


def map_world(image, strength):
    """An equirectangular map looked up as Rayster does. Rayster's u is 0.5 towards glTF -Z
    (Blender +Y) and grows towards +X; Cycles' is 0.5 towards Blender +X. Turning the lookup
    direction by -90 degrees about Z makes the two agree (checked with a marked test map)."""
    world = bpy.data.worlds.new("map")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    coords = nodes.new('ShaderNodeTexCoord')
    turn = nodes.new('ShaderNodeMapping')
    turn.vector_type = 'POINT'
    turn.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(-90.0))
    tex = nodes.new('ShaderNodeTexEnvironment')
    tex.image = image
    links.new(coords.outputs["Generated"], turn.inputs["Vector"])
    links.new(turn.outputs["Vector"], tex.inputs["Vector"])
    links.new(tex.outputs["Color"], nodes["Background"].inputs["Color"])
    nodes["Background"].inputs["Strength"].default_value = strength
    bpy.context.scene.world = world


def sky_world(zenith, horizon, ground, strength):
    """Rayster's procedural sky (skyRadiance() in shaders/lib/environment.glsl), with y up = z:
    above the horizon mix(horizon, zenith, sqrt(z)), below it mix(horizon, ground, sqrt(min(-4z, 1)))."""
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    coords = nodes.new('ShaderNodeTexCoord')
    split = nodes.new('ShaderNodeSeparateXYZ')
    links.new(coords.outputs["Generated"], split.inputs["Vector"])

    def math_node(operation, a, b=None):
        node = nodes.new('ShaderNodeMath')
        node.operation = operation
        for socket, value in ((node.inputs[0], a), (node.inputs[1], b)):
            if isinstance(value, bpy.types.NodeSocket):
                links.new(value, socket)
            elif value is not None:
                socket.default_value = value
        return node.outputs[0]

    z = split.outputs["Z"]
    up = math_node('SQRT', math_node('MAXIMUM', z, 0.0))
    down = math_node('SQRT', math_node('MINIMUM', math_node('MAXIMUM', math_node('MULTIPLY', z, -4.0), 0.0), 1.0))
    upper = nodes.new('ShaderNodeMixRGB')
    links.new(up, upper.inputs["Fac"])
    upper.inputs["Color1"].default_value = (*horizon, 1.0)
    upper.inputs["Color2"].default_value = (*zenith, 1.0)
    lower = nodes.new('ShaderNodeMixRGB')
    links.new(down, lower.inputs["Fac"])
    links.new(upper.outputs["Color"], lower.inputs["Color1"])
    lower.inputs["Color2"].default_value = (*ground, 1.0)
    links.new(lower.outputs["Color"], nodes["Background"].inputs["Color"])
    nodes["Background"].inputs["Strength"].default_value = strength
    bpy.context.scene.world = world


# ---- images ----------------------------------------------------------------------------------

def write_radiance_hdr(path, rgb):
    """A flat (not run-length encoded) RGBE Radiance file; `rgb` is height x width x 3, top row first."""
    height, width, _ = rgb.shape
    peak = rgb.max(axis=2)
    exponent = np.floor(np.log2(np.maximum(peak, 1e-30))) + 1  # peak / 2^exponent in [0.5, 1)
    exponent += np.round(peak * np.exp2(8 - exponent)) >= 256  # rounding up to 256: next exponent
    scale = np.where(peak > 1e-30, np.exp2(8 - exponent), 0.0)
    rgbe = np.zeros((height, width, 4), np.uint8)
    rgbe[..., :3] = np.clip(np.round(rgb * scale[..., None]), 0, 255)
    rgbe[..., 3] = np.where(peak > 1e-30, exponent + 128, 0)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\n# generated by Rayster's scripts/corpus/make_corpus.py\n")
        f.write(b"FORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
        f.write(rgbe.tobytes())


def packed_image(name, rgba):
    """A Blender image from `rgba` (height x width x 4, top row first, colour sRGB-encoded), packed
    as PNG so both the .glb and the .blend carry it."""
    height, width, _ = rgba.shape
    image = bpy.data.images.new(name, width, height, alpha=True)
    image.pixels.foreach_set(np.ascontiguousarray(rgba[::-1]).astype(np.float32).ravel())
    image.pack()
    return image

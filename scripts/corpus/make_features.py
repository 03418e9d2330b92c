"""Build the Blender feature corpus: skins, shape keys, vertex colours and material extensions,
each exported by Blender's own glTF exporter.

    blender -b --factory-startup --python scripts/corpus/make_features.py -- OUTDIR

writes OUTDIR/{skinned,shapekeys,vertex_colors,materials}.glb and OUTDIR/extensions.json (what
each file's JSON actually declares in extensionsUsed, read back from the export). Everything is
built procedurally here; see assets/corpus/README.md ("Feature files") and docs/corpus.md.
"""
import json
import math
import os
import struct
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import corpus_lib as lib  # noqa: E402

kFps = 24
kLastFrame = 48  # 2 s at 24 fps: frame 1 is t = 0, frame 48 is t = 47/24 s


def export_glb(path, animations):
    bpy.ops.export_scene.gltf(filepath=path, export_format='GLB', export_cameras=True, export_lights=True,
                              export_extras=True, export_yup=True, export_apply=False,
                              export_animations=animations, export_skins=True, export_morph=True,
                              export_colors=True)


def glb_json(path):
    """The JSON chunk of a GLB file."""
    with open(path, "rb") as f:
        data = f.read()
    length, kind = struct.unpack_from("<II", data, 12)
    assert kind == 0x4E4F534A, "first chunk is JSON"
    return json.loads(data[20:20 + length])


def set_timeline(scene):
    scene.render.fps = kFps
    scene.frame_start, scene.frame_end = 1, kLastFrame


def floor(name, size, color):
    half = size / 2
    return lib.mesh_object(name, [(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)],
                           [(0, 1, 2, 3)], lib.principled(name, color, roughness=0.8))


# Light power for Rayster at the goldens' unit exposure (--exposure 0): the exporter writes
# W / 4 pi x 683 cd, so 1.5 W is 82 cd, about 3.5 lux on the subject 4.9 m away (white Lambert
# radiance about 1). Cycles would need exposure +9.4 to show these files as bright.
kKeyWatts = 1.5


def key_light():
    lib.point_light("Key", (2.5, -3.0, 4.0), kKeyWatts, 0.1)


# ---- skinned.glb -----------------------------------------------------------------------------

def build_skinned():
    """A segmented cylinder on three bones; the action bends each bone 35 degrees about X."""
    scene = lib.reset_scene()
    set_timeline(scene)
    floor("Floor", 6.0, lib.kWhite)
    segments, rings, radius, height = 16, 18, 0.22, 2.1
    verts = [(radius * math.cos(2 * math.pi * s / segments), radius * math.sin(2 * math.pi * s / segments),
              height * r / rings) for r in range(rings + 1) for s in range(segments)]
    faces = [(r * segments + s, r * segments + (s + 1) % segments, (r + 1) * segments + (s + 1) % segments,
              (r + 1) * segments + s) for r in range(rings) for s in range(segments)]
    top = [rings * segments + s for s in range(segments)]
    faces.append(tuple(top))
    limb = lib.mesh_object("Limb", verts, faces, lib.principled("Limb", (0.8, 0.35, 0.1), roughness=0.5),
                           smooth=True)

    armature = bpy.data.armatures.new("Rig")
    rig = lib.link(bpy.data.objects.new("Rig", armature))
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode='EDIT')
    bone_length = height / 3
    parent = None
    for i in range(3):
        bone = armature.edit_bones.new("Bone%d" % i)
        bone.head = (0.0, 0.0, i * bone_length)
        bone.tail = (0.0, 0.0, (i + 1) * bone_length)
        if parent is not None:
            bone.parent, bone.use_connect = parent, True
        parent = bone
    bpy.ops.object.mode_set(mode='OBJECT')

    # Scripted weights: each ring is shared by the two bones nearest its height, linearly.
    groups = [limb.vertex_groups.new(name="Bone%d" % i) for i in range(3)]
    for index, v in enumerate(verts):
        x = min(max(v[2] / bone_length - 0.5, 0.0), 2.0)  # 0 at bone 0's middle, 2 at bone 2's
        lower = min(int(x), 1)
        w = x - lower
        groups[lower].add([index], 1.0 - w, 'REPLACE')
        groups[lower + 1].add([index], w, 'REPLACE')
    limb.parent = rig
    modifier = limb.modifiers.new("Armature", 'ARMATURE')
    modifier.object = rig

    bpy.ops.object.mode_set(mode='POSE')
    for pose_bone in rig.pose.bones:
        pose_bone.rotation_mode = 'QUATERNION'
        for frame, degrees in ((1, 0.0), (kLastFrame, 35.0)):
            angle = math.radians(degrees) / 2
            pose_bone.rotation_quaternion = (math.cos(angle), math.sin(angle), 0.0, 0.0)
            pose_bone.keyframe_insert("rotation_quaternion", frame=frame)
    bpy.ops.object.mode_set(mode='OBJECT')
    rig.animation_data.action.name = "Bend"

    # Seen from +X: the limb bends towards -Y, across the picture.
    lib.camera("Camera", (4.8, 0.0, 1.4), (0.0, -0.45, 1.0), 40.0)
    key_light()
    scene.name = "skinned"
    return scene


# ---- shapekeys.glb ---------------------------------------------------------------------------

def build_shapekeys():
    """A sphere with two shape keys (squash, and a bulge to +X); their values are animated."""
    scene = lib.reset_scene()
    set_timeline(scene)
    floor("Floor", 6.0, lib.kWhite)
    ball = lib.uv_sphere("Ball", 0.7, 24, 12, lib.principled("Ball", (0.1, 0.35, 0.8), roughness=0.4), (0, 0, 0.8))
    ball.shape_key_add(name="Basis")
    squash = ball.shape_key_add(name="Squash")
    bulge = ball.shape_key_add(name="Bulge")
    for i, v in enumerate(ball.data.vertices):
        x, y, z = v.co
        squash.data[i].co = (x * 1.3, y * 1.3, (z + 0.7) * 0.55 - 0.7)  # squashed onto its bottom
        push = max(x, 0.0) / 0.7
        bulge.data[i].co = (x + 0.6 * push * push, y, z)
    for key, frames in ((squash, ((1, 0.0), (kLastFrame, 1.0))), (bulge, ((1, 0.0), (24, 1.0), (kLastFrame, 0.0)))):
        for frame, value in frames:
            key.value = value
            key.keyframe_insert("value", frame=frame)
    ball.data.shape_keys.animation_data.action.name = "Morph"
    lib.camera("Camera", (0.0, -6.0, 1.6), (0.3, 0.0, 0.7), 40.0)
    key_light()
    scene.name = "shapekeys"
    return scene


# ---- vertex_colors.glb -----------------------------------------------------------------------

def build_vertex_colors():
    """A 4 x 4 grid of quads facing the camera, each face corner coloured (byte colour attribute on
    face corners, flat per cell); the material multiplies it into a white base colour."""
    scene = lib.reset_scene()
    floor("Floor", 6.0, (0.3, 0.3, 0.3))
    cells = 4
    size = 2.0
    palette = [(1.0, 0.05, 0.05), (0.05, 1.0, 0.05), (0.05, 0.05, 1.0), (1.0, 1.0, 0.05)]
    verts, faces, colors = [], [], []
    for row in range(cells):
        for col in range(cells):
            x0, z0 = -size / 2 + col * size / cells, 0.2 + row * size / cells
            step = size / cells
            first = len(verts)
            verts += [(x0, 0, z0), (x0 + step, 0, z0), (x0 + step, 0, z0 + step), (x0, 0, z0 + step)]
            # Counter-clockwise seen from -Y (the camera).
            faces.append((first, first + 1, first + 2, first + 3))
            colors += [palette[(row + col) % 4] if (row, col) != (0, 0) else (1.0, 1.0, 1.0)] * 4
    mat = bpy.data.materials.new("VertexColour")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 0.9
    attribute = nodes.new('ShaderNodeVertexColor')
    attribute.layer_name = "Col"
    links.new(attribute.outputs["Color"], bsdf.inputs["Base Color"])
    panel = lib.mesh_object("Panel", verts, faces, mat)
    layer = panel.data.color_attributes.new("Col", 'BYTE_COLOR', 'CORNER')
    for loop, c in zip(layer.data, colors):
        loop.color_srgb = (*c, 1.0)
    panel.data.color_attributes.render_color_index = 0
    panel.data.color_attributes.active_color_index = 0
    lib.camera("Camera", (0.0, -5.0, 1.3), (0.0, 0.0, 1.15), 40.0)
    lib.point_light("Key", (0.5, -4.0, 3.0), kKeyWatts, 0.1)
    scene.name = "vertex_colors"
    return scene


# ---- materials.glb ---------------------------------------------------------------------------

def stripes_image(name, size=64, bands=4):
    """Vertical black and white stripes (grey values linear: the image is non-colour data)."""
    u = (np.arange(size) * bands // size) % 2
    rgba = np.ones((size, size, 4))
    rgba[..., :3] = u[None, :, None].astype(float)
    image = lib.packed_image(name, rgba)
    image.colorspace_settings.name = 'Non-Color'
    return image


def checker_image(name, size=64, cells=8):
    idx = np.arange(size) * cells // size
    grey = np.where((idx[:, None] + idx[None, :]) % 2 == 0, 0.9, 0.15)
    rgba = np.ones((size, size, 4))
    rgba[..., :3] = grey[..., None]
    return lib.packed_image(name, rgba)


def textured_input(mat, socket_name, image):
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    tex = nodes.new('ShaderNodeTexImage')
    tex.image = image
    links.new(tex.outputs["Color"], nodes["Principled BSDF"].inputs[socket_name])


def uv_sphere_with_uvs(name, radius, location, mat, segments=24, rings=12):
    obj = lib.uv_sphere(name, radius, segments, rings, mat, location)
    # Cylindrical UVs (u around, v up) so a texture-driven slot shows stripes.
    layer = obj.data.uv_layers.new(name="UVMap")
    for poly in obj.data.polygons:
        us = []
        for li in poly.loop_indices:
            co = obj.data.vertices[obj.data.loops[li].vertex_index].co
            us.append(((math.atan2(co.y, co.x) / (2 * math.pi)) % 1.0, co.z / (2 * radius) + 0.5))
        # Keep a face from wrapping around u = 0.
        if max(u for u, _ in us) - min(u for u, _ in us) > 0.5:
            us = [(u + 1.0 if u < 0.5 else u, v) for u, v in us]
        for li, uv in zip(poly.loop_indices, us):
            layer.data[li].uv = uv
    return obj


kBase = (0.6, 0.08, 0.05)  # the plain, coated and textured-coat spheres share this red


def material_specs(stripes):
    """(name, builder) per sphere, in grid order: row 0 left to right, then row 1."""

    def plain(m):
        pass

    def coat(m):
        bsdf = m.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Clearcoat"].default_value = 1.0
        bsdf.inputs["Clearcoat Roughness"].default_value = 0.05

    def coat_texture(m):
        coat(m)
        textured_input(m, "Clearcoat", stripes)

    def glass(m):
        bsdf = m.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        bsdf.inputs["Roughness"].default_value = 0.0
        bsdf.inputs["Transmission"].default_value = 1.0
        bsdf.inputs["IOR"].default_value = 1.5

    def glass_volume(m):
        glass(m)
        m.node_tree.nodes["Principled BSDF"].inputs["IOR"].default_value = 1.33
        lib.set_volume_thickness(m, 0.8)  # the diameter
        nodes, links = m.node_tree.nodes, m.node_tree.links
        absorb = nodes.new('ShaderNodeVolumeAbsorption')
        absorb.inputs["Color"].default_value = (0.2, 0.9, 0.3, 1.0)
        absorb.inputs["Density"].default_value = 1.0
        links.new(absorb.outputs["Volume"], nodes["Material Output"].inputs["Volume"])

    def glass_texture(m):
        glass(m)
        textured_input(m, "Transmission", stripes)

    def specular(m):
        bsdf = m.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (0.05, 0.05, 0.05, 1.0)
        bsdf.inputs["Roughness"].default_value = 0.2
        bsdf.inputs["Specular"].default_value = 1.0
        bsdf.inputs["Specular Tint"].default_value = 0.0

    def emission(m):
        bsdf = m.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (0.05, 0.05, 0.05, 1.0)
        bsdf.inputs["Emission"].default_value = (1.0, 0.5, 0.1, 1.0)
        bsdf.inputs["Emission Strength"].default_value = 4.0

    def sheen(m):
        nodes, links = m.node_tree.nodes, m.node_tree.links
        bsdf = nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (0.05, 0.05, 0.3, 1.0)
        velvet = nodes.new('ShaderNodeBsdfVelvet')
        velvet.inputs["Color"].default_value = (1.0, 0.9, 0.2, 1.0)
        velvet.inputs["Sigma"].default_value = 0.5
        add = nodes.new('ShaderNodeAddShader')
        links.new(bsdf.outputs["BSDF"], add.inputs[0])
        links.new(velvet.outputs["BSDF"], add.inputs[1])
        links.new(add.outputs["Shader"], nodes["Material Output"].inputs["Surface"])

    return [("Plain", plain), ("Clearcoat", coat), ("ClearcoatTexture", coat_texture), ("Specular", specular),
            ("Glass", glass), ("GlassVolume", glass_volume), ("GlassTexture", glass_texture), ("Emission", emission),
            ("Sheen", sheen)]


def build_materials():
    """Nine spheres in a 3 x 3 grid on a checker floor, one Principled BSDF setting each."""
    scene = lib.reset_scene()
    floor_mat = bpy.data.materials.new("Checker")
    floor_mat.use_nodes = True
    floor_mat.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 0.9
    textured_input(floor_mat, "Base Color", checker_image("checker"))
    half = 3.0
    lib.mesh_object("Floor", [(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [(0, 1, 2, 3)],
                    floor_mat, uvs=[(0, 0), (1, 0), (1, 1), (0, 1)])
    stripes = stripes_image("stripes")
    for i, (name, build) in enumerate(material_specs(stripes)):
        mat = lib.principled(name, kBase, roughness=0.4)
        build(mat)
        row, col = divmod(i, 3)
        uv_sphere_with_uvs(name, 0.4, ((col - 1) * 1.05, (1 - row) * 1.05, 0.4), mat)
    lib.camera("Camera", (0.0, -5.2, 3.6), (0.0, 0.0, 0.25), 40.0)
    lib.point_light("Key", (2.0, -2.5, 4.0), kKeyWatts, 0.1)
    lib.sun_light("Sun", (0.3, 0.5, -1.0), 0.002)  # 1.4 lux: fills the shadows a little
    scene.name = "materials"
    return scene


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 1:
        sys.exit("usage: blender -b --factory-startup --python make_features.py -- OUTDIR")
    out = os.path.abspath(args[0])
    os.makedirs(out, exist_ok=True)
    report = {}
    for build, animated in ((build_skinned, True), (build_shapekeys, True), (build_vertex_colors, False),
                            (build_materials, False)):
        scene = build()
        path = os.path.join(out, scene.name + ".glb")
        export_glb(path, animated)
        doc = glb_json(path)
        per_material = {m.get("name", "?"): sorted(m.get("extensions", {})) for m in doc.get("materials", [])}
        report[scene.name + ".glb"] = {"extensionsUsed": sorted(doc.get("extensionsUsed", [])),
                                       "materials": per_material,
                                       "skins": len(doc.get("skins", [])),
                                       "animations": len(doc.get("animations", [])),
                                       "bytes": os.path.getsize(path)}
        print("%s: %s" % (scene.name, json.dumps(report[scene.name + ".glb"])))
    with open(os.path.join(out, "extensions.json"), "w") as f:
        json.dump(report, f, indent=1, sort_keys=True)
        f.write("\n")


main()

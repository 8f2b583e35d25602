"""Renders a Penumbra scene's camera view with Blender's Cycles path tracer, as an independent
reference for the bake's image (see README.md next to this file).

    blender -b --factory-startup --python-exit-code 1 -P scripts/reference/render_cycles.py -- \
        SCENE.json OUT.exr --spp N --seed S

Supports what the Cornell box uses: OBJ geometry (v / f / o / g / usemtl / mtllib) with MTL
Kd (diffuse reflectance) and Ke (emitted radiance, W/(sr·m²)), material overrides
`reflectance`, `emission` and `emission_two_sided`, and the pinhole camera. Anything else in
the scene fails with a message rather than rendering something else.
"""

import argparse
import json
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

METRES_PER_UNIT = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": 0.3048}
# Keys that do not change what the camera sees (the bake's own settings), and those we render.
IGNORED_KEYS = {"name", "sensors", "mesher", "solver"}
RENDERED_KEYS = {"units", "up", "geometry", "materials", "camera", "image"}
MATERIAL_KEYS = {"reflectance", "emission", "emission_two_sided"}
CAMERA_KEYS = {"type", "eye", "look_at", "up", "fov_deg", "fov_axis"}
IMAGE_KEYS = {"width", "height", "spp", "exposure"}  # spp and exposure: ours, not Cycles'
BOUNCES = 64  # ρ ≤ 0.73 in a closed box: 0.73^64 ≈ 2e-9 of the light is cut off


def fail(message):
    raise SystemExit(f"render_cycles.py: {message}")


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="render_cycles.py")
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("--spp", type=int, required=True)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=2)
    return parser.parse_args(argv)


def check_keys(obj, allowed, where):
    unknown = set(obj) - allowed
    if unknown:
        fail(f"{where}: unsupported key(s) {sorted(unknown)}")


def rgb(value, where):
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    if isinstance(value, list) and len(value) == 3:
        return tuple(float(v) for v in value)
    fail(f"{where}: expected a number or [r, g, b], got {value!r}")


def to_blender(up):
    """Rotation taking the scene's up axis to Blender's +z (right-handed both)."""
    if up == [0, 1, 0]:
        return Matrix(((1, 0, 0), (0, 0, -1), (0, 1, 0)))  # (x, y, z) -> (x, -z, y)
    if up == [0, 0, 1]:
        return Matrix.Identity(3)
    fail(f"up {up}: only [0, 1, 0] and [0, 0, 1] are supported")


def read_mtl(path):
    materials, current = {}, None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            if words[0] == "newmtl":
                current = materials.setdefault(words[1], {"Kd": (0.5,) * 3, "Ke": (0.0,) * 3})
            elif words[0] in ("Kd", "Ke"):
                if len(words) != 4:
                    fail(f"{path}: '{line.strip()}': expected three values")
                current[words[0]] = tuple(float(w) for w in words[1:])
            elif words[0] in ("Ks", "Ka", "Ns", "Ni") and all(float(w) == 0 for w in words[1:]):
                continue  # no specular or ambient term: Lambert only
            elif words[0] == "illum" and words[1] in ("0", "1"):
                continue
            else:
                fail(f"{path}: unsupported MTL statement '{line.strip()}'")
    return materials


def read_obj(path):
    """Polygons as (object name, material name, [vertex positions]) in file units."""
    vertices, polygons, materials = [], [], {}
    name, material = os.path.basename(path), None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            key = words[0]
            if key == "v":
                vertices.append(tuple(float(w) for w in words[1:4]))
            elif key == "f":
                indices = [int(w.split("/")[0]) for w in words[1:]]
                corners = [vertices[i - 1 if i > 0 else len(vertices) + i] for i in indices]
                polygons.append((name, material, corners))
            elif key in ("o", "g"):
                name = " ".join(words[1:])
            elif key == "usemtl":
                material = words[1]
            elif key == "mtllib":
                materials.update(read_mtl(os.path.join(os.path.dirname(path), words[1])))
            elif key == "s":
                continue  # flat shading either way: Lambert faces, no normals
            else:
                fail(f"{path}: unsupported OBJ statement '{line.strip()}'")
    return polygons, materials


def load_scene(path):
    with open(path) as f:
        scene = json.load(f)
    check_keys(scene, IGNORED_KEYS | RENDERED_KEYS, path)
    if "camera" not in scene:
        fail(f"{path}: no camera")
    units = scene.get("units", "m")
    if units not in METRES_PER_UNIT:
        fail(f"{path}: unknown units '{units}'")
    geometry = scene.get("geometry", [])
    geometry = [geometry] if isinstance(geometry, str) else geometry
    polygons, materials = [], {}
    for file in geometry:
        full = os.path.join(os.path.dirname(os.path.abspath(path)), file)
        if not full.lower().endswith(".obj"):
            fail(f"{file}: only OBJ geometry is supported")
        p, m = read_obj(full)
        polygons += p
        materials.update(m)
    for name, override in scene.get("materials", {}).items():
        check_keys(override, MATERIAL_KEYS, f"materials.{name}")
        material = materials.setdefault(name, {"Kd": (0.5,) * 3, "Ke": (0.0,) * 3})
        if "reflectance" in override:
            material["Kd"] = rgb(override["reflectance"], f"materials.{name}.reflectance")
        if "emission" in override:
            material["Ke"] = rgb(override["emission"], f"materials.{name}.emission")
        material["two_sided_emission"] = bool(override.get("emission_two_sided", False))
    return scene, polygons, materials, METRES_PER_UNIT[units]


def make_material(name, spec):
    """Lambert (Diffuse BSDF, roughness 0) plus, for an emitter, an Emission shader whose
    strength 1 makes a directly seen pixel its radiance; one-sided unless asked otherwise."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*spec["Kd"], 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    surface = diffuse.outputs["BSDF"]
    if any(spec["Ke"]):
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (*spec["Ke"], 1.0)
        emission.inputs["Strength"].default_value = 1.0
        if not spec.get("two_sided_emission", False):
            geometry = nodes.new("ShaderNodeNewGeometry")
            front = nodes.new("ShaderNodeMath")
            front.operation = "SUBTRACT"
            front.inputs[0].default_value = 1.0
            links.new(geometry.outputs["Backfacing"], front.inputs[1])
            links.new(front.outputs["Value"], emission.inputs["Strength"])
        add = nodes.new("ShaderNodeAddShader")
        links.new(surface, add.inputs[0])
        links.new(emission.outputs["Emission"], add.inputs[1])
        surface = add.outputs["Shader"]
    links.new(surface, output.inputs["Surface"])
    return material


def build_geometry(polygons, materials, rotation, scale):
    names = sorted({m for _, m, _ in polygons})
    for m in names:
        if m not in materials:
            fail(f"material '{m}' is used but not defined")
    blender_materials = [make_material(n, materials[n]) for n in names]
    vertices, faces, face_materials = [], [], []
    for _, m, corners in polygons:
        start = len(vertices)
        vertices += [tuple(rotation @ Vector(c) * scale) for c in corners]
        faces.append(list(range(start, len(vertices))))
        face_materials.append(names.index(m))
    mesh = bpy.data.meshes.new("scene")
    mesh.from_pydata(vertices, [], faces)
    for m in blender_materials:
        mesh.materials.append(m)
    for polygon, index in zip(mesh.polygons, face_materials):
        polygon.material_index = index
        polygon.use_smooth = False
    mesh.validate()
    bpy.context.scene.collection.objects.link(bpy.data.objects.new("scene", mesh))


def build_camera(camera, image, scene_up, rotation, scale):
    check_keys(camera, CAMERA_KEYS, "camera")
    check_keys(image, IMAGE_KEYS, "image")
    if camera.get("type", "pinhole") != "pinhole":
        fail("camera: only 'pinhole' is supported")
    eye = rotation @ Vector(camera["eye"]) * scale
    look_at = rotation @ Vector(camera["look_at"]) * scale
    up = rotation @ Vector(camera.get("up", scene_up))
    forward = (look_at - eye).normalized()
    right = forward.cross(up).normalized()  # as raytrace/src/render.cpp builds its frame
    true_up = right.cross(forward)
    # Blender's camera looks along its -z with +y up and +x right.
    frame = Matrix((right, true_up, -forward)).transposed().to_4x4()
    frame.translation = eye
    data = bpy.data.cameras.new("camera")
    data.type = "PERSP"
    data.sensor_fit = "HORIZONTAL" if camera.get("fov_axis", "x") == "x" else "VERTICAL"
    data.angle = math.radians(camera.get("fov_deg", 45.0))
    data.clip_start, data.clip_end = 1e-4, 1e4
    obj = bpy.data.objects.new("camera", data)
    obj.matrix_world = frame
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    render = bpy.context.scene.render
    render.resolution_x = image.get("width", 512)
    render.resolution_y = image.get("height", 512)
    render.resolution_percentage = 100
    render.pixel_aspect_x = render.pixel_aspect_y = 1.0


def set_up_cycles(spp, seed, threads):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    c.samples = spp
    c.seed = seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = BOUNCES
    c.transmission_bounces = c.transparent_max_bounces = c.volume_bounces = BOUNCES
    scene.render.film_transparent = False
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scene.world = world
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"


def main():
    args = parse_args()
    scene, polygons, materials, scale = load_scene(args.scene)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene_up = scene.get("up", [0, 0, 1])
    rotation = to_blender(scene_up)
    build_geometry(polygons, materials, rotation, scale)
    build_camera(scene["camera"], scene.get("image", {}), scene_up, rotation, scale)
    set_up_cycles(args.spp, args.seed, args.threads)
    bpy.context.scene.render.filepath = os.path.abspath(args.out)
    bpy.ops.render.render(write_still=True)


main()

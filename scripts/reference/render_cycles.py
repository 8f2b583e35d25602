"""Renders a Penumbra scene's camera view with Blender's Cycles path tracer, as an independent
reference for the bake's image (see README.md next to this file).

    blender -b --factory-startup --python-exit-code 1 -P scripts/reference/render_cycles.py -- \
        SCENE.json OUT.exr --spp N --seed S

Supports OBJ geometry (v / vn / f / o / g / usemtl / mtllib / s) with MTL materials read as
core/src/imported_material.cpp reads them, the scene's material overrides of the types
diffuse, ggx (no Fresnel), mirror and glass, `smooth_objects`, a black `background`, and the
pinhole or thin-lens camera. Anything that Cycles cannot render exactly as Penumbra defines it
fails with a message rather than rendering something else; README.md lists each mapping.
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
# `cameras` adds views; this script renders `camera`. `lightmap`: baked textures, not the view.
IGNORED_KEYS = {"name", "sensors", "mesher", "solver", "lightmap", "cameras"}
RENDERED_KEYS = {"units", "up", "geometry", "materials", "camera", "image", "render",
                 "background", "emission_two_sided", "smooth_objects"}
EMISSION_KEYS = {"emission", "emission_two_sided"}
# The keys each material `type` takes (docs/scene-format.md), besides the emission keys.
TYPE_KEYS = {"diffuse": {"reflectance"}, "ggx": {"alpha", "specular", "fresnel", "ior"},
             "mirror": {"specular"}, "glass": {"ior", "solid", "transmittance"}}
CAMERA_KEYS = {"type", "eye", "look_at", "up", "fov_deg", "fov_axis", "aperture_radius",
               "focus_distance"}
IMAGE_KEYS = {"width", "height", "spp", "exposure"}  # spp and exposure: ours, not Cycles'
# spp, max_bounces and the photon settings are how Penumbra estimates the image, not the image.
RENDER_KEYS = {"spp", "max_bounces", "pixel_filter", "filter_width_px", "caustic_photons",
               "caustic_radius"}
BOUNCES = 64  # ρ ≤ 0.73 in a closed box: 0.73^64 ≈ 2e-9 of the light is cut off
MIN_IMPORTED_ALPHA = 1e-3  # imported_material.cpp's k_min_imported_alpha


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
    """MTL statements per material, as numbers (the lobe is chosen later, in mtl_material)."""
    statements, current = {}, None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            if words[0] == "newmtl":
                current = statements.setdefault(words[1], {})
            elif words[0] in ("Kd", "Ke", "Ks", "Ka", "Tf"):
                if len(words) != 4:
                    fail(f"{path}: '{line.strip()}': expected three values")
                current[words[0]] = tuple(float(w) for w in words[1:])
            elif words[0] in ("Ns", "Ni", "Pr", "d", "Tr", "illum") and len(words) == 2:
                current[words[0]] = float(words[1])
            else:
                fail(f"{path}: unsupported MTL statement '{line.strip()}'")
    return {name: mtl_material(name, st, path) for name, st in statements.items()}


def mtl_material(name, st, path):
    """The rules of core/src/imported_material.cpp (mtl_lobe), first that applies: illum 6/7
    glass, d < 1 thin glass, illum 3 with Ks mirror / ggx metal / plastic, else diffuse Kd.
    Ka is ignored there too."""
    where = f"{path}: {name}"
    if "Kd" not in st:
        fail(f"{where}: no Kd (Penumbra would take assimp's default)")
    kd, ks = st.get("Kd", (0.0,) * 3), st.get("Ks", (0.0,) * 3)
    material = {"Kd": kd, "Ke": st.get("Ke", (0.0,) * 3), "lobe": None}
    illum = int(st.get("illum", 0))
    opacity = 1.0 - st["Tr"] if "Tr" in st and "d" not in st else st.get("d", 1.0)
    if illum in (6, 7):
        material["lobe"] = {"type": "glass", "ior": st.get("Ni", 1.0),
                            "transmittance": st.get("Tf", (1.0,) * 3), "solid": True}
    elif opacity < 1:
        fail(f"{where}: d < 1 is thin glass, which Cycles has no exact counterpart of")
    elif illum == 3 and any(ks):
        if "Pr" in st:
            alpha = st["Pr"] ** 2 if st["Pr"] > 0 else None
        else:
            alpha = math.sqrt(2 / (st["Ns"] + 2)) if st.get("Ns", 0) > 0 else None
        if any(kd):
            fail(f"{where}: illum 3 with Kd and Ks is a plastic (a GGX coat over a Lambertian "
                 "base that gets what the coat leaves), which no Cycles shader is exactly")
        if alpha is None:
            material["lobe"] = {"type": "mirror", "specular": ks}
        else:
            material["lobe"] = {"type": "ggx", "alpha": max(alpha, MIN_IMPORTED_ALPHA),
                                "specular": ks, "fresnel": "none"}
    if material["lobe"] is not None:
        material["Kd"] = (0.0,) * 3  # a metal, a mirror and glass have no diffuse part
        check_lobe(material["lobe"], where)
    return material


def read_obj(path):
    """Polygons as (object name, material name, [vertex positions], [vertex normals] or None)
    in file units."""
    vertices, normals, polygons, materials = [], [], [], {}
    name, material = os.path.basename(path), None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            key = words[0]
            if key == "v":
                vertices.append(tuple(float(w) for w in words[1:4]))
            elif key == "vn":
                normals.append(tuple(float(w) for w in words[1:4]))
            elif key == "f":
                refs = [w.split("/") for w in words[1:]]
                corners = [vertices[index(r[0], len(vertices))] for r in refs]
                corner_normals = None
                if all(len(r) == 3 and r[2] for r in refs):
                    corner_normals = [normals[index(r[2], len(normals))] for r in refs]
                polygons.append((name, material, corners, corner_normals))
            elif key in ("o", "g"):
                name = " ".join(words[1:])
            elif key == "usemtl":
                material = words[1]
            elif key == "mtllib":
                materials.update(read_mtl(os.path.join(os.path.dirname(path), words[1])))
            elif key == "s":
                continue  # Penumbra shades by `vn` and `smooth_objects`, not by smoothing groups
            else:
                fail(f"{path}: unsupported OBJ statement '{line.strip()}'")
    return polygons, materials


def index(word, count):
    i = int(word)
    return i - 1 if i > 0 else count + i


def unit_normals(normals):
    """Normalised vertex normals, or None when one is zero or not finite (the polygon is then
    flat, as docs/scene-format.md says of geometry files)."""
    if normals is None:
        return None
    out = []
    for n in normals:
        length = math.sqrt(sum(c * c for c in n))
        if not (length > 0 and math.isfinite(length)):
            return None
        out.append(tuple(c / length for c in n))
    return out


def load_scene(path):
    with open(path) as f:
        scene = json.load(f)
    check_keys(scene, IGNORED_KEYS | RENDERED_KEYS, path)
    if "camera" not in scene:
        fail(f"{path}: no camera")
    if any(rgb(scene.get("background", 0), "background")):
        fail(f"{path}: background: Penumbra's background lights nothing, Cycles' world lights "
             "the scene; only a black one maps exactly")
    check_render(scene.get("render", {}))
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
        for name, material in m.items():
            materials.setdefault(name, material)  # the first file's definition wins
    default_two_sided = bool(scene.get("emission_two_sided", False))
    for material in materials.values():
        material["two_sided_emission"] = default_two_sided
    for name, override in scene.get("materials", {}).items():
        apply_override(materials.setdefault(name, diffuse_material()), override, name)
    polygons = apply_smooth_objects(polygons, scene.get("smooth_objects"))
    return scene, polygons, materials, METRES_PER_UNIT[units]


def check_render(render):
    check_keys(render, RENDER_KEYS, "render")
    if render.get("pixel_filter", "box") != "box":
        fail("render.pixel_filter: only 'box' is the same filter in Cycles")
    if render.get("filter_width_px", 1.0) != 1.0:
        fail("render.filter_width_px: only 1 (the pixel itself) is supported")


def diffuse_material():
    return {"Kd": (0.5,) * 3, "Ke": (0.0,) * 3, "lobe": None, "two_sided_emission": False}


def apply_override(material, override, name):
    """The scene's `materials` entry: a `type` replaces the lobe (its omitted keys take their
    defaults), without one the entry overrides only the keys it gives."""
    where = f"materials.{name}"
    kind = override.get("type")
    if kind is not None and kind not in TYPE_KEYS:
        fail(f"{where}.type: '{kind}' has no exact Cycles counterpart here")
    lobe_type = kind or (material["lobe"] or {}).get("type", "diffuse")
    check_keys(override, {"type"} | EMISSION_KEYS | TYPE_KEYS[lobe_type], where)
    if "emission" in override:
        material["Ke"] = rgb(override["emission"], f"{where}.emission")
    if "emission_two_sided" in override:
        material["two_sided_emission"] = bool(override["emission_two_sided"])
    if kind == "diffuse":
        if material["lobe"] is not None and "reflectance" not in override:
            fail(f"{where}: a diffuse type over the file's {material['lobe']['type']} needs "
                 "its own reflectance (which one Penumbra keeps is not checked here)")
        material["lobe"] = None
    elif kind is not None:
        material["lobe"] = {"type": kind}
        material["Kd"] = (0.0,) * 3
    if lobe_type == "diffuse":
        if "reflectance" in override:
            material["Kd"] = rgb(override["reflectance"], f"{where}.reflectance")
        return
    lobe = material["lobe"]
    for key in TYPE_KEYS[lobe_type] & set(override):
        value = override[key]
        lobe[key] = rgb(value, f"{where}.{key}") if key in ("specular", "transmittance") else value
    check_lobe(lobe, where)


def check_lobe(lobe, where):
    """What Cycles 3.4's Glossy and Glass BSDFs reproduce exactly, with the defaults of
    docs/scene-format.md."""
    kind = lobe["type"]
    if kind == "ggx":
        lobe.setdefault("alpha", 0.1)
        lobe.setdefault("specular", (1.0,) * 3)
        if lobe.setdefault("fresnel", "none") != "none":
            fail(f"{where}.fresnel: only 'none' (Cycles' Fresnel node takes the shading normal, "
                 "not the microfacet normal)")
        if not 0 < lobe["alpha"] <= 1:
            fail(f"{where}.alpha: must be in (0, 1]")
    elif kind == "mirror":
        lobe.setdefault("specular", (1.0,) * 3)
    elif kind == "glass":
        lobe.setdefault("ior", 1.5)
        if not lobe.setdefault("solid", True):
            fail(f"{where}.solid: only a solid body (Cycles' Glass BSDF flips the index by side)")
        if lobe.setdefault("transmittance", (1.0,) * 3) != (1.0,) * 3:
            fail(f"{where}.transmittance: only 1 (Cycles' Glass colour tints the reflection too)")


def apply_smooth_objects(polygons, names):
    """Vertex normals kept for the listed objects only (all objects without the key)."""
    if names is not None:
        found = {n for n, _, _, normals in polygons if normals is not None}
        for name in names:
            if name not in found:
                fail(f"smooth_objects: '{name}' has no polygons with vertex normals")
    return [(n, m, corners, unit_normals(normals) if names is None or n in names else None)
            for n, m, corners, normals in polygons]


def make_material(name, spec):
    """The material's surface shader (surface_bsdf) plus, for an emitter, an Emission shader
    whose strength 1 makes a directly seen pixel its radiance; one-sided unless asked."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    surface = surface_bsdf(nodes, spec)
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


def surface_bsdf(nodes, spec):
    """Diffuse: Diffuse BSDF of roughness 0 (Lambert). ggx without Fresnel: Glossy BSDF, GGX,
    roughness √α (Cycles squares it), colour `specular`. mirror: Glossy BSDF, Sharp. glass:
    Glass BSDF, Sharp, of the index (Fresnel reflection, refraction and total internal
    reflection; it takes 1/n on back faces, as Penumbra's solid dielectric does inside)."""
    lobe = spec["lobe"]
    if lobe is None:
        node = nodes.new("ShaderNodeBsdfDiffuse")
        node.inputs["Color"].default_value = (*spec["Kd"], 1.0)
        node.inputs["Roughness"].default_value = 0.0
    elif lobe["type"] in ("ggx", "mirror"):
        node = nodes.new("ShaderNodeBsdfGlossy")
        node.distribution = "GGX" if lobe["type"] == "ggx" else "SHARP"
        node.inputs["Color"].default_value = (*lobe["specular"], 1.0)
        node.inputs["Roughness"].default_value = (
            math.sqrt(lobe["alpha"]) if lobe["type"] == "ggx" else 0.0)
    else:
        node = nodes.new("ShaderNodeBsdfGlass")
        node.distribution = "SHARP"
        node.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        node.inputs["Roughness"].default_value = 0.0
        node.inputs["IOR"].default_value = lobe["ior"]
    return node.outputs["BSDF"]


def build_geometry(polygons, materials, rotation, scale):
    """Two meshes: flat polygons, and those with vertex normals (custom split normals, which
    Cycles interpolates over Blender's triangles (0, 1, 2), (0, 2, 3) of a quad: the fan that
    raytrace/src/path_geometry.cpp interpolates over too)."""
    names = sorted({m for _, m, _, _ in polygons})
    for m in names:
        if m not in materials:
            fail(f"material '{m}' is used but not defined")
    blender_materials = [make_material(n, materials[n]) for n in names]
    flat = [p for p in polygons if p[3] is None]
    smooth = [p for p in polygons if p[3] is not None]
    for label, group in (("flat", flat), ("smooth", smooth)):
        if group:
            build_mesh(label, group, names, blender_materials, rotation, scale)


def build_mesh(label, polygons, names, blender_materials, rotation, scale):
    vertices, faces, face_materials, loop_normals = [], [], [], []
    for _, m, corners, normals in polygons:
        start = len(vertices)
        vertices += [tuple(rotation @ Vector(c) * scale) for c in corners]
        faces.append(list(range(start, len(vertices))))
        face_materials.append(names.index(m))
        if normals is not None:
            loop_normals += [tuple(rotation @ Vector(n)) for n in normals]
    mesh = bpy.data.meshes.new(label)
    mesh.from_pydata(vertices, [], faces)
    for m in blender_materials:
        mesh.materials.append(m)
    smooth = bool(loop_normals)
    for polygon, index in zip(mesh.polygons, face_materials):
        polygon.material_index = index
        polygon.use_smooth = smooth
    mesh.validate()
    if smooth:
        mesh.use_auto_smooth = True  # Blender 3.4 keeps custom normals only with it
        mesh.auto_smooth_angle = math.pi
        mesh.normals_split_custom_set(loop_normals)
    bpy.context.scene.collection.objects.link(bpy.data.objects.new(label, mesh))


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
    set_thin_lens(data, camera, eye, look_at, forward, scale)
    obj = bpy.data.objects.new("camera", data)
    obj.matrix_world = frame
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    render = bpy.context.scene.render
    render.resolution_x = image.get("width", 512)
    render.resolution_y = image.get("height", 512)
    render.resolution_percentage = 100
    render.pixel_aspect_x = render.pixel_aspect_y = 1.0


def set_thin_lens(data, camera, eye, look_at, forward, scale):
    """Cycles' thin lens: a uniform disc of radius lens / (2 f-stop) (lens in mm, radius in m),
    round (no blades), focused on the plane perpendicular to the view axis at the distance,
    as Penumbra's ThinLensCamera."""
    radius = camera.get("aperture_radius", 0.0) * scale
    if radius < 0:
        fail("camera.aperture_radius: must be >= 0")
    if radius == 0:
        return
    focus = camera.get("focus_distance")
    focus = focus * scale if focus is not None else (look_at - eye).dot(forward)
    if not focus > 0:
        fail("camera.focus_distance: must be > 0")
    data.dof.use_dof = True
    data.dof.focus_distance = focus
    data.dof.aperture_blades = 0
    data.dof.aperture_ratio = 1.0
    data.dof.aperture_fstop = data.lens * 1e-3 / (2.0 * radius)


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

# Builds and renders a GOR-IS style scene with Blender Cycles from a scene description written by
# `goris synth` (scene.json). Run as:  blender -b --factory-startup --python render_scene.py -- scene.json OUTDIR
#
# Per training view:  train/r_XXX.png (with the target, RGBA), train/mask_XXX.png (target),
#                     train/gloss_XXX.png (glossy surfaces),
#                     train/gt/{diffcol,glosscol,normal,depth,f0,roughness}_XXX.exr
#                     (their encoding is written next to them: train/gt/encoding.json, from GT_ENCODING below)
# Per test view:      test/full_XXX.png (with the target), test/r_XXX.png (target hidden: its reflections and
#                     shadows go too), test/mask_XXX.png, test/gt/gloss_XXX.png (glossy surfaces)
# Masks come from a second, cheap render per view: every object emits its mask channel (R = target,
# G = glossy) through a view-layer material override, no bounces, raw colour transform, on an opaque black
# background. Its edges are anti-aliased by the same pixel filter as the beauty render (a mask pixel is
# the covered fraction of the pixel), and occlusion is exact.
# With a third argument `train-after` it renders only the training views with the target hidden, into
# OUTDIR/train_after/r_XXX.png (`goris synth --train-after`; what `goris remove --fill-truth` reads).
# With `test-only` it renders only the test views (tools/reference_noise.py renders them again at more
# samples per pixel to measure what the references' own noise costs the metrics).
# After each view the script prints "GORIS_FRAME <done> <total>" so the caller can show progress.
import json
import math
import os
import sys

import bpy
from mathutils import Vector

TARGET_INDEX = 1  # object pass_index of the target
GLOSSY_INDEX = 2  # object pass_index of glossy surfaces

# (file prefix, Render Layers output) of the training views' ground-truth maps.
GT_MAPS = (("diffcol_", "DiffCol"), ("glosscol_", "GlossCol"), ("normal_", "Normal"), ("depth_", "Depth"),
           ("f0_", "f0"), ("roughness_", "roughness"))
GT_ENCODING = {
    "format": "goris-synth-gt",
    "version": 1,
    "files": "train/gt/<map>_XXX.exr, one per training view: OpenEXR, 32-bit float RGB, linear values "
             "(no colour management), same size and pixel grid as train/r_XXX.png",
    "maps": {
        "diffcol": "Cycles Diffuse Color pass: diffuse albedo, linear RGB",
        "glosscol": "Cycles Glossy Color pass: the colour weight of glossy closures, linear RGB; for the "
                    "Principled BSDF of these scenes it is white wherever there is a specular layer (the "
                    "Fresnel colour is inside the closure): use f0 for the reflectance",
        "f0": "shader AOV: reflectance at normal incidence, linear RGB: 0.08 * Specular for dielectrics, "
              "the base colour for metals, mixed by Metallic",
        "roughness": "shader AOV: the Principled BSDF roughness in [0, 1], the same value in R, G and B",
        "normal": "Cycles Normal pass: world-space shading normal in Blender axes (Z up) as raw components "
                  "in [-1, 1]",
        "depth": "Cycles Z pass: distance along the camera's optical axis (not along the ray) in scene "
                 "units (metres); the same value in R, G and B",
    },
    "units": "metres",
    "background": "pixels that see no surface hold 0 (depth: 1e10)",
    "antialiasing": "diffcol, glosscol, normal, f0 and roughness are means over a pixel's samples, "
                    "background samples counting as 0: at silhouettes against the background divide by the "
                    "alpha of train/r_XXX.png to get the surface value; normals are not renormalised. depth "
                    "comes from the pixel's first sample only (Cycles): a silhouette pixel holds either one "
                    "surface's depth or 1e10",
}


def args():
    """(scene description, OUTDIR, mode): mode is "all", "train-after" or "test-only"."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] not in ("train-after", "test-only")):
        raise SystemExit("usage: blender -b --python render_scene.py -- scene.json OUTDIR [train-after|test-only]")
    with open(argv[0]) as f:
        return json.load(f), argv[1], argv[2] if len(argv) == 3 else "all"


def render_train_after(cam, target, r, world, train, out_dir, progress):
    """The training views once more with the target hidden (its reflections and shadows go too), into
    OUTDIR/train_after/r_XXX.png: what a perfect removal would show in the views it learns from. Outside the
    target's imprint they equal the training photos (same samples and seed)."""
    after_dir = os.path.join(out_dir, "train_after")
    os.makedirs(after_dir, exist_ok=True)
    beauty_mode(r, world)
    target.hide_render = True
    for i, view in enumerate(train):
        aim_camera(cam, view)
        render_to(os.path.join(after_dir, "r_%03d.png" % i))
        progress()
    target.hide_render = False


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o, do_unlink=True)
    for m in list(bpy.data.materials):
        bpy.data.materials.remove(m)


# ---------------------------------------------------------------- materials
def texture_node(nodes, links, tex):
    """Returns the output socket giving the base colour of a procedural texture description."""
    coord = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    links.new(coord.outputs["Object"], mapping.inputs["Vector"])
    kind = tex["kind"]
    if kind == "checker":
        t = nodes.new("ShaderNodeTexChecker")
        t.inputs["Color1"].default_value = (*tex["color1"], 1)
        t.inputs["Color2"].default_value = (*tex["color2"], 1)
        t.inputs["Scale"].default_value = tex["scale"]
        links.new(mapping.outputs["Vector"], t.inputs["Vector"])
        return t.outputs["Color"]
    if kind == "brick":
        t = nodes.new("ShaderNodeTexBrick")
        t.inputs["Color1"].default_value = (*tex["color1"], 1)
        t.inputs["Color2"].default_value = (*tex["color2"], 1)
        t.inputs["Mortar"].default_value = (0.8, 0.8, 0.78, 1)
        t.inputs["Scale"].default_value = tex["scale"]
        links.new(mapping.outputs["Vector"], t.inputs["Vector"])
        return t.outputs["Color"]
    # noise and marble: a scalar pattern mapped between two colours by a ramp
    if kind == "noise":
        t = nodes.new("ShaderNodeTexNoise")
        t.inputs["Scale"].default_value = tex["scale"]
        t.inputs["Detail"].default_value = 4.0
        fac = t.outputs["Fac"]
    elif kind == "marble":
        t = nodes.new("ShaderNodeTexWave")
        t.inputs["Scale"].default_value = tex["scale"]
        t.inputs["Distortion"].default_value = 8.0
        t.inputs["Detail"].default_value = 4.0
        fac = t.outputs["Fac"]
    else:
        raise SystemExit("unknown texture kind " + kind)
    links.new(mapping.outputs["Vector"], t.inputs["Vector"])
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].color = (*tex["color1"], 1)
    ramp.color_ramp.elements[1].color = (*tex["color2"], 1)
    links.new(fac, ramp.inputs["Fac"])
    return ramp.outputs["Color"]


def make_material(name, desc):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*desc["color"], 1)
    bsdf.inputs["Metallic"].default_value = desc["metallic"]
    bsdf.inputs["Roughness"].default_value = desc["roughness"]
    bsdf.inputs["Specular"].default_value = desc["specular"]
    base = texture_node(nodes, links, desc["texture"]) if desc.get("texture") else None
    if base is not None:
        links.new(base, bsdf.inputs["Base Color"])
    # Ground-truth material AOVs for the decomposition (train/gt/f0_, roughness_): Principled's normal-
    # incidence reflectance is 0.08 * Specular for dielectrics and the base colour for metals.
    f0 = nodes.new("ShaderNodeMixRGB")
    f0.inputs["Fac"].default_value = desc["metallic"]
    f0.inputs["Color1"].default_value = (*[0.08 * desc["specular"]] * 3, 1)
    f0.inputs["Color2"].default_value = (*desc["color"], 1)
    if base is not None:
        links.new(base, f0.inputs["Color2"])
    links.new(f0.outputs["Color"], aov_output(nodes, "f0").inputs["Color"])
    aov_output(nodes, "roughness").inputs["Value"].default_value = desc["roughness"]
    return mat


def aov_output(nodes, name):
    node = nodes.new("ShaderNodeOutputAOV")
    setattr(node, "aov_name" if hasattr(node, "aov_name") else "name", name)  # renamed in later Blenders
    return node


def mask_override_material():
    """Emits (is target, is glossy, 0) from each object's pass_index: one render gives both masks."""
    mat = bpy.data.materials.new("goris_mask_override")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    info = nodes.new("ShaderNodeObjectInfo")
    rgb = nodes.new("ShaderNodeCombineColor")
    for channel, index in (("Red", TARGET_INDEX), ("Green", GLOSSY_INDEX)):
        cmp = nodes.new("ShaderNodeMath")
        cmp.operation = "COMPARE"
        cmp.inputs[1].default_value = index
        cmp.inputs[2].default_value = 0.25
        links.new(info.outputs["Object Index"], cmp.inputs[0])
        links.new(cmp.outputs[0], rgb.inputs[channel])
    emit = nodes.new("ShaderNodeEmission")
    links.new(rgb.outputs["Color"], emit.inputs["Color"])
    out = nodes.new("ShaderNodeOutputMaterial")
    links.new(emit.outputs["Emission"], out.inputs["Surface"])
    return mat


# ---------------------------------------------------------------- scene
SHAPES = {
    "cube": lambda: bpy.ops.mesh.primitive_cube_add(size=2.0),
    "sphere": lambda: bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=48, ring_count=24),
    "ico_sphere": lambda: bpy.ops.mesh.primitive_ico_sphere_add(radius=1.0, subdivisions=2),
    "cylinder": lambda: bpy.ops.mesh.primitive_cylinder_add(radius=1.0, depth=2.0, vertices=64),
    "cone": lambda: bpy.ops.mesh.primitive_cone_add(radius1=1.0, depth=2.0, vertices=64),
    "torus": lambda: bpy.ops.mesh.primitive_torus_add(major_radius=0.7, minor_radius=0.3),
    "monkey": lambda: bpy.ops.mesh.primitive_monkey_add(size=2.0),
    "plane": lambda: bpy.ops.mesh.primitive_plane_add(size=2.0),
}
SMOOTH = {"sphere", "cylinder", "cone", "torus", "monkey"}


def add_object(desc):
    if desc["shape"] not in SHAPES:
        raise SystemExit("unknown shape " + desc["shape"])
    SHAPES[desc["shape"]]()
    obj = bpy.context.active_object
    obj.name = desc["name"]
    obj.location = desc["location"]
    obj.rotation_euler = desc["rotation"]
    obj.scale = desc["scale"]
    if desc["shape"] in SMOOTH:
        bpy.ops.object.shade_smooth()
    obj.data.materials.append(make_material(desc["name"], desc["material"]))
    obj.pass_index = TARGET_INDEX if desc["target"] else (GLOSSY_INDEX if desc["glossy"] else 0)
    return obj


def black_world():
    world = bpy.data.worlds.new("goris_black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    return world


def add_world(desc):
    world = bpy.data.worlds.new("goris_world")
    bpy.context.scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    bg = nodes["Background"]
    bg.inputs["Strength"].default_value = desc["strength"]
    if desc["kind"] == "sky":
        sky = nodes.new("ShaderNodeTexSky")
        sky.sky_type = "HOSEK_WILKIE"
        sky.sun_direction = Vector(desc["sun_direction"]).normalized()
        sky.turbidity = desc["turbidity"]
        links.new(sky.outputs["Color"], bg.inputs["Color"])
    elif desc["kind"] == "gradient":
        coord = nodes.new("ShaderNodeTexCoord")
        sep = nodes.new("ShaderNodeSeparateXYZ")
        ramp = nodes.new("ShaderNodeValToRGB")
        links.new(coord.outputs["Generated"], sep.inputs["Vector"])  # world "Generated" = view direction
        links.new(sep.outputs["Z"], ramp.inputs["Fac"])
        ramp.color_ramp.elements[0].position = 0.0
        ramp.color_ramp.elements[0].color = (*desc["horizon"], 1)
        ramp.color_ramp.elements[1].position = 0.8
        ramp.color_ramp.elements[1].color = (*desc["zenith"], 1)
        links.new(ramp.outputs["Color"], bg.inputs["Color"])
    else:
        raise SystemExit("unknown world kind " + desc["kind"])
    return world


def add_area_light(desc):
    data = bpy.data.lights.new("goris_area", type="AREA")
    data.energy = desc["energy"]
    data.size = desc["size"]
    data.color = desc["color"]
    light = bpy.data.objects.new("goris_area", data)
    bpy.context.scene.collection.objects.link(light)
    light.location = desc["location"]
    aim = Vector(desc["look_at"]) - Vector(desc["location"])
    light.rotation_euler = aim.to_track_quat("-Z", "Y").to_euler()


def add_camera(angle_x):
    data = bpy.data.cameras.new("goris_camera")
    data.sensor_fit = "HORIZONTAL"
    data.angle = angle_x
    data.clip_start = 0.05
    data.clip_end = 100.0
    cam = bpy.data.objects.new("goris_camera", data)
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam
    return cam


def aim_camera(cam, view):
    cam.location = view["location"]
    aim = Vector(view["look_at"]) - Vector(view["location"])
    cam.rotation_euler = aim.to_track_quat("-Z", "Y").to_euler()
    bpy.context.view_layer.update()
    return [list(row) for row in cam.matrix_world]


# ---------------------------------------------------------------- render settings
def setup_render(r):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = r["threads"]
    scene.cycles.use_auto_tile = True
    scene.cycles.tile_size = r["tile"]
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = r["seed"]
    scene.render.resolution_x = r["res"]
    scene.render.resolution_y = r["res"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.color_depth = "8"
    scene.render.image_settings.compression = 90
    scene.render.dither_intensity = 0.0  # no noise added when quantising: mask backgrounds stay exactly 0
    scene.render.use_persistent_data = True  # keep the BVH between the many renders of one scene
    for prop in dir(scene.render):  # no date, frame, camera ... metadata in the images
        if prop.startswith("use_stamp"):
            setattr(scene.render, prop, False)


def beauty_mode(r, world):
    scene = bpy.context.scene
    scene.world = world
    scene.render.film_transparent = True
    scene.cycles.samples = r["spp"]
    scene.cycles.max_bounces = 6
    scene.cycles.sample_clamp_indirect = 10.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    bpy.context.view_layer.material_override = None


def mask_mode(r, override, mask_world):
    # An opaque black background rather than a transparent one: PNG stores straight (un-premultiplied)
    # colour, which would turn a silhouette against the background into a hard 1. On black, the colour of
    # an edge pixel is exactly the object's coverage.
    scene = bpy.context.scene
    scene.world = mask_world
    scene.render.film_transparent = False
    scene.cycles.samples = r["mask_spp"]
    scene.cycles.max_bounces = 0
    scene.view_settings.view_transform = "Raw"  # the mask values are written as they are, no sRGB curve
    bpy.context.view_layer.material_override = override


def setup_gt_output(gt_dir):
    """Compositor File Output writing the training views' intrinsic passes as float EXR."""
    scene = bpy.context.scene
    layer = bpy.context.view_layer
    layer.use_pass_diffuse_color = True
    layer.use_pass_glossy_color = True
    layer.use_pass_normal = True
    layer.use_pass_z = True
    for name, kind in (("f0", "COLOR"), ("roughness", "VALUE")):
        aov = layer.aovs.add()
        aov.name, aov.type = name, kind
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    rl = tree.nodes.new("CompositorNodeRLayers")
    comp = tree.nodes.new("CompositorNodeComposite")
    comp.use_alpha = True
    tree.links.new(rl.outputs["Image"], comp.inputs["Image"])
    tree.links.new(rl.outputs["Alpha"], comp.inputs["Alpha"])
    out = tree.nodes.new("CompositorNodeOutputFile")
    out.base_path = gt_dir
    out.format.file_format = "OPEN_EXR"
    out.format.color_depth = "32"
    out.format.exr_codec = "ZIP"
    out.format.color_mode = "RGB"
    out.file_slots.clear()
    for slot, socket in GT_MAPS:
        out.file_slots.new(slot)
        tree.links.new(rl.outputs[socket], out.inputs[slot])
    return out


def strip_png_text(path):
    """Drops a PNG's text chunks: Cycles always stamps render times there, and without them the same scene
    and seed give byte-identical files (a regenerated data set shows no spurious changes)."""
    with open(path, "rb") as f:
        data = f.read()
    out, pos = [data[:8]], 8
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        end = pos + 12 + length  # length, type, data, CRC
        if data[pos + 4:pos + 8] not in (b"tEXt", b"zTXt", b"iTXt", b"tIME"):
            out.append(data[pos:end])
        pos = end
    with open(path, "wb") as f:
        f.write(b"".join(out))


def render_to(path):
    """Renders the current camera into path through a temporary name, so no half file keeps the final name."""
    tmp = path + ".part.png"
    bpy.context.scene.render.filepath = tmp
    bpy.ops.render.render(write_still=True)
    strip_png_text(tmp)
    os.replace(tmp, path)


def split_mask(rgb_path, outputs):
    """Splits the mask render (R = target, G = glossy) into 8-bit grey PNGs (values written as they are)."""
    img = bpy.data.images.load(rgb_path)
    w, h = img.size
    px = list(img.pixels)
    bpy.data.images.remove(img)
    settings = bpy.context.scene.render.image_settings
    settings.color_mode = "BW"
    for channel, path in outputs:
        mask = bpy.data.images.new("goris_mask", w, h, alpha=False, float_buffer=True)
        mask.colorspace_settings.name = "Non-Color"
        vals = []
        for i in range(w * h):
            v = px[4 * i + channel]
            vals.extend((v, v, v, 1.0))
        mask.pixels = vals
        mask.save_render(path + ".part.png", scene=bpy.context.scene)
        strip_png_text(path + ".part.png")
        bpy.data.images.remove(mask)
        os.replace(path + ".part.png", path)
    settings.color_mode = "RGBA"
    os.remove(rgb_path)


def write_json(path, data):
    tmp = path + ".part"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1)
    os.replace(tmp, path)


def write_transforms(path, angle_x, frames):
    write_json(path, {"camera_angle_x": angle_x, "frames": frames})


def main():
    desc, out_dir, mode = args()
    train_after = mode == "train-after"
    r = desc["render"]
    clear_scene()
    setup_render(r)
    world = add_world(desc["world"])
    mask_world = black_world()
    for light in desc["lights"]:
        add_area_light(light)
    objects = [add_object(o) for o in desc["objects"]]
    target = [o for o, d in zip(objects, desc["objects"]) if d["target"]][0]
    cam = add_camera(desc["camera_angle_x"])
    override = mask_override_material()

    train, test = desc["cameras"]["train"], desc["cameras"]["test"]
    if mode == "test-only":
        train = []
    total, done = len(train) + (0 if train_after else len(test)), 0

    def progress():
        nonlocal done
        done += 1
        print("GORIS_FRAME %d %d" % (done, total), flush=True)

    if train_after:  # only the training views without the target, beside an existing data set
        render_train_after(cam, target, r, world, train, out_dir, progress)
        print("GORIS_DONE", flush=True)
        return

    train_dir, test_dir = os.path.join(out_dir, "train"), os.path.join(out_dir, "test")
    gt_dir = os.path.join(train_dir, "gt")
    test_gt_dir = os.path.join(test_dir, "gt")  # test glossy masks: not part of the GOR-IS layout
    os.makedirs(test_gt_dir, exist_ok=True)
    os.makedirs(train_dir, exist_ok=True)
    write_gt = desc["ground_truth_maps"]
    gt_out = None
    if write_gt:
        os.makedirs(gt_dir, exist_ok=True)
        gt_out = setup_gt_output(gt_dir)
        write_json(os.path.join(gt_dir, "encoding.json"), GT_ENCODING)

    scene = bpy.context.scene
    frames = []
    for i, view in enumerate(train):
        name = "%03d" % i
        frames.append({"file_path": "./train/r_" + name, "transform_matrix": aim_camera(cam, view)})
        beauty_mode(r, world)
        if gt_out:
            gt_out.mute = False
            scene.frame_current = i
        render_to(os.path.join(train_dir, "r_" + name + ".png"))
        if gt_out:
            gt_out.mute = True
            for slot, _ in GT_MAPS:
                os.replace(os.path.join(gt_dir, "%s%04d.exr" % (slot, i)), os.path.join(gt_dir, slot + name + ".exr"))
        mask_mode(r, override, mask_world)
        tmp = os.path.join(train_dir, "masks_" + name + ".tmp.png")
        render_to(tmp)
        split_mask(tmp, [(0, os.path.join(train_dir, "mask_" + name + ".png")),
                         (1, os.path.join(train_dir, "gloss_" + name + ".png"))])
        progress()
    if mode != "test-only":
        write_transforms(os.path.join(out_dir, "transforms_train.json"), desc["camera_angle_x"], frames)

    frames = []
    for i, view in enumerate(test):
        name = "%03d" % i
        frames.append({"file_path": "./test/r_" + name, "transform_matrix": aim_camera(cam, view)})
        beauty_mode(r, world)
        target.hide_render = False
        render_to(os.path.join(test_dir, "full_" + name + ".png"))
        target.hide_render = True
        render_to(os.path.join(test_dir, "r_" + name + ".png"))
        target.hide_render = False
        mask_mode(r, override, mask_world)
        tmp = os.path.join(test_dir, "masks_" + name + ".tmp.png")
        render_to(tmp)
        split_mask(tmp, [(0, os.path.join(test_dir, "mask_" + name + ".png")),
                         (1, os.path.join(test_gt_dir, "gloss_" + name + ".png"))])
        progress()
    write_transforms(os.path.join(out_dir, "transforms_test.json"), desc["camera_angle_x"], frames)
    print("GORIS_DONE", flush=True)


main()

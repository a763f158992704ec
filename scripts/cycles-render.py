# Renders a glTF model with Blender's Cycles as tripath renders it, for the comparison in
# docs/gltf-samples.md ("tripath against Cycles").
#
# Blender is a measuring instrument here, never a dependency of the build or the tests: install it
# by hand (Debian: apt-get install blender; the numbers in the document are from Blender 3.4.1)
# and run
#
#     blender -b --factory-startup -P scripts/cycles-render.py -- --scene M.gltf --out M.exr \
#             [--width 256 --height 256 --spp 512 --seed 1 --threads 2] [options below]
#
# scripts/cycles-compare.sh runs it, tripath and the comparison together.
#
# What it sets up, to match `tripath render --scene M.gltf --environment 1,1,1 --integrator pt`:
# - the model through Blender's own glTF importer (io_import_scene_gltf2); its cameras and lights
#   are deleted;
# - tripath's automatic framing (frameBounds in src/geometry/scene.cpp): the box around every
#   triangle in glTF world space, the camera 1.05 × radius / sin(yfov / 2) from its centre along
#   +Z, looking along −Z with +Y up, vertical field 0.6911 rad. glTF is +Y up, Blender +Z up: the
#   importer maps glTF (x, y, z) to Blender (x, −z, y);
# - a constant white sky (World background 1, 1, 1, strength 1) and no other light;
# - Cycles path tracing, no denoiser, no adaptive sampling, no clamping, no glossy blur, a 1-pixel
#   box filter (tripath samples each pixel uniformly), and at most 14 bounces: tripath's default
#   --max-depth 16 counts segments (camera to sky through 15 surfaces is 16; Cycles' bounce count
#   is the surface count − 1);
# - a transparent film, so that the EXR's alpha is what the model covers; its RGB misses only the
#   sky seen directly, which is (1 − alpha) × (1, 1, 1): cycles-compare.py adds it back.
#   EXR, 32-bit float, linear; view transform Standard.
# Options that change both renderers alike, each to isolate one difference (cycles-compare.py
# writes the matching glTF copy for tripath):
#   --lambert   every material becomes Cycles' Diffuse BSDF (Lambertian) of its base colour
#               (texture included), normal map and emission kept;
#   --flat      normal maps dropped (tripath: normalTexture removed).
# and some that change Cycles alone:
#   --no-specular  Principled BSDF's Specular 0: its diffuse lobe alone on non-metals;
#   --no-terminator-offset  every object's shadow_terminator_geometry_offset 0 (default 0.1:
#               shadow rays of smooth-shaded triangles start moved toward the smooth surface);
#   --linear-textures  every 8-bit sRGB image is decoded to linear float before rendering, so that
#               Cycles interpolates decoded texels as tripath does (Cycles 3.4 keeps such images as
#               bytes and decodes after interpolating).
import argparse
import math
import sys

import bpy
import numpy
from mathutils import Vector

# Debian's Blender 3.4 importer still says numpy.bool, which numpy 1.24 removed.
if "bool" not in numpy.__dict__:
    numpy.bool = bool

YFOV = 0.6911  # tripath's automatic framing: a 35 mm lens's vertical field


def parse():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles-render.py")
    p.add_argument("--scene", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--width", type=int, default=256)
    p.add_argument("--height", type=int, default=256)
    p.add_argument("--spp", type=int, default=512)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--lambert", action="store_true")
    p.add_argument("--flat", action="store_true")
    p.add_argument("--no-specular", action="store_true")
    p.add_argument("--no-terminator-offset", action="store_true")
    p.add_argument("--linear-textures", action="store_true")
    return p.parse_args(argv)


def world_bounds_gltf():
    """The box around every mesh vertex, in glTF world coordinates."""
    lo = Vector((math.inf,) * 3)
    hi = Vector((-math.inf,) * 3)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    for ob in bpy.context.scene.objects:
        if ob.type != "MESH":
            continue
        ev = ob.evaluated_get(depsgraph)
        mw = ev.matrix_world
        for v in ev.data.vertices:
            b = mw @ v.co
            g = Vector((b.x, b.z, -b.y))  # Blender (x, y, z) is glTF (x, −z, y)
            lo = Vector(map(min, lo, g))
            hi = Vector(map(max, hi, g))
    return lo, hi


def place_camera(width, height):
    lo, hi = world_bounds_gltf()
    centre = (lo + hi) * 0.5
    radius = 0.5 * (hi - lo).length
    g = centre + Vector((0, 0, radius / math.sin(0.5 * YFOV) * 1.05))
    data = bpy.data.cameras.new("tripath-frame")
    data.sensor_fit = "VERTICAL"
    data.angle_y = YFOV
    data.clip_start = radius * 1e-4
    data.clip_end = radius * 1e3
    cam = bpy.data.objects.new("tripath-frame", data)
    cam.location = (g.x, -g.z, g.y)
    cam.rotation_euler = (math.pi / 2, 0, 0)  # Blender cameras look along local −Z: now +Y, up +Z
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam
    print(f"cycles-render: bounds glTF {tuple(lo)} .. {tuple(hi)}; camera glTF {tuple(g)}, "
          f"yfov {data.angle_y:.6f}, {width}x{height}")


def make_lambert(mat):
    nt = mat.node_tree
    out = next(n for n in nt.nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output)
    pr = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if pr is None:
        print(f"cycles-render: material {mat.name} has no Principled BSDF; left as it is")
        return
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0  # Oren-Nayar at 0 is Lambertian
    for name in ("Color", "Normal"):
        src = pr.inputs["Base Color" if name == "Color" else name]
        if src.is_linked:
            nt.links.new(src.links[0].from_socket, diffuse.inputs[name])
        elif name == "Color":
            diffuse.inputs[name].default_value = src.default_value
    surface = diffuse.outputs["BSDF"]
    em, strength = pr.inputs["Emission"], pr.inputs["Emission Strength"].default_value
    if em.is_linked or any(c > 0 for c in em.default_value[:3]):
        emission = nt.nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = strength
        if em.is_linked:
            nt.links.new(em.links[0].from_socket, emission.inputs["Color"])
        else:
            emission.inputs["Color"].default_value = em.default_value
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(surface, add.inputs[0])
        nt.links.new(emission.outputs["Emission"], add.inputs[1])
        surface = add.outputs["Shader"]
    nt.links.new(surface, out.inputs["Surface"])


def srgb_decode(v):
    return numpy.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def linear_textures():
    """Replaces every 8-bit sRGB image by a float copy of its decoded texels."""
    for img in list(bpy.data.images):
        if img.is_float or img.colorspace_settings.name != "sRGB":
            continue
        w, h = img.size
        px = numpy.empty(w * h * 4, dtype=numpy.float32)
        img.pixels.foreach_get(px)  # an 8-bit image's stored values / 255, still sRGB-encoded
        px = px.reshape(-1, 4)
        px[:, :3] = srgb_decode(px[:, :3].astype(numpy.float64))
        lin = bpy.data.images.new(img.name + " (linear)", w, h, alpha=True, float_buffer=True)
        lin.colorspace_settings.name = "Linear"
        lin.pixels.foreach_set(px.ravel())
        lin.pack()
        img.user_remap(lin)
        print(f"cycles-render: {img.name}: {w}x{h} sRGB bytes decoded to linear float")


def main():
    a = parse()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=a.scene)
    for ob in list(bpy.context.scene.objects):
        if ob.type in ("CAMERA", "LIGHT"):
            bpy.data.objects.remove(ob, do_unlink=True)
    scene = bpy.context.scene
    place_camera(a.width, a.height)
    if a.no_terminator_offset:
        for ob in scene.objects:
            ob.cycles.shadow_terminator_geometry_offset = 0.0

    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        for n in mat.node_tree.nodes:
            if n.type == "BSDF_PRINCIPLED":
                print(f"cycles-render: material {mat.name}: distribution {n.distribution}, "
                      f"specular {n.inputs['Specular'].default_value:.3f}")
            if a.no_specular and n.type == "BSDF_PRINCIPLED":
                n.inputs["Specular"].default_value = 0.0
            if a.flat and n.type == "BSDF_PRINCIPLED":
                for link in n.inputs["Normal"].links:
                    mat.node_tree.links.remove(link)
        if a.lambert:
            make_lambert(mat)

    if a.linear_textures:
        linear_textures()

    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1, 1, 1, 1)
    bg.inputs["Strength"].default_value = 1.0
    scene.world = world

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = a.width, a.height, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1
    r.film_transparent = True
    r.threads_mode, r.threads = "FIXED", a.threads
    r.use_compositing = r.use_sequencer = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGBA"
    r.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0
    scene.view_settings.gamma = 1

    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.seed = a.seed
    c.use_adaptive_sampling = False
    c.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0
    c.blur_glossy = 0
    c.caustics_reflective = c.caustics_refractive = True
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 14
    c.transparent_max_bounces = 14
    c.volume_bounces = 0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.film_exposure = 1.0

    r.filepath = a.out
    bpy.ops.render.render(write_still=True)
    print(f"cycles-render: wrote {a.out}")


main()

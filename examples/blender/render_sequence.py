"""Render a short animated scene with Cycles as a kdop frame sequence.

What it renders: a static camera looking down at an angle on a ground plane
with a high-frequency, grass-like procedural texture (luma and chroma
variation), a saturated red box (the "car") that drives across the frame and a
little away from the camera, four near-black wheels that move with it, and a
sun light. The camera is not jittered: ghosting is measured on jitter-off
sequences.

Why: it is content from outside kdop. kdop's own scenes are drawn by kdop
itself (2-D sprites over textures, and a rasterized 3-D testbed); this one comes
from a path tracer with real perspective, shading and motion vectors, and goes
through the same reader as any renderer's captures (docs/taa.md, "Frame
sequences").

How to run it (Blender 3.4 or later, no .blend file, nothing downloaded):

    blender --background --factory-startup \
        --python examples/blender/render_sequence.py -- \
        --out DIR [--frames N] [--size WxH] [--samples S] [--seed K] [--hdr]

    kdop taa --sequence DIR --warmup 16 --out RESULTS

(--warmup: the frames before measuring; its default, 100, is more than the 48
frames rendered by default.)

Defaults: 48 frames, 160x90, 16 samples, seed 1.

With --hdr the frames are HDR, as a renderer's are before tone mapping: the sun
is 4x stronger (the ground's luminance is about 0.6 to 1), the car has two
emissive headlights (up to 38), the color is not clamped, and sequence.json says
"color": {"range": "hdr"}, so kdop taa measures it in HDR-FLIP.

What it writes under DIR, frames numbered from 0000:

    color/NNNN.exr   the Combined pass, linear RGB, 32-bit float. Without
                     --hdr the compositor clamps it to [0, 1] (a Mix node
                     with Clamp on), the range of an "ldr" sequence, which
                     kdop measures in LDR-FLIP. It is a safeguard: with this
                     lighting the default render peaks near 0.8 and nothing
                     is clamped.
    motion/NNNN.exr  the Vector pass, for every frame but the first. Cycles
                     writes it only with motion blur off. R, G: X, Y, the
                     offset to where the surface was in the previous frame;
                     B: Cycles' Z, about the next frame, which kdop ignores
                     (the 3.4 compositor's vector sockets carry three
                     channels, so W is lost; kdop reads only X and Y).
    depth/NNNN.exr   the Depth (Z) pass, distance from the camera: smaller is
                     nearer, kdop's default.
    sequence.json    format version 1, with the motion settings the Blender
                     row of docs/taa.md ("Motion settings for what engines
                     write") gives: "units": "pixels",
                     "points_to": "previous", "y_axis": "up"; the color
                     range, "ldr" or (--hdr) "hdr"; and "measure":
                     ["ghosting"]: without jitter, only ghosting means
                     anything (kdop taa leaves shimmer out).

Blender writes motion/0000.exr too (motion toward a frame before the first);
the script deletes it so that the folder holds only the files sequence.json
names.
"""

import argparse
import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix

GROUND_SIZE = 60.0
CAR_START = (-5.5, -1.0, 0.55)  # the red box's center on the first frame
CAR_END = (5.5, 2.0, 0.55)      # on the last: right, away, up in the image
CAR_SIZE = (2.0, 1.0, 0.7)
WHEEL_RADIUS = 0.3
SUN_STRENGTH = 3.5
HDR_SUN_STRENGTH = 14.0  # --hdr: the ground's luminance about 0.6 to 1
HEADLIGHT_STRENGTH = 40.0  # --hdr: emission of the car's two headlights
WORLD_STRENGTH = 0.15
PASSES = ("color", "motion", "depth")


def parse_args(argv):
    """Parse the options after Blender's `--` separator."""
    if "--" in argv:
        argv = argv[argv.index("--") + 1:]
    else:
        argv = []
    parser = argparse.ArgumentParser(
        prog="render_sequence.py",
        description="Render a Cycles animation as a kdop frame sequence.")
    parser.add_argument("--out", required=True, help="output folder")
    parser.add_argument("--frames", type=int, default=48,
                        help="number of frames (default 48)")
    parser.add_argument("--size", default="160x90",
                        help="frame size WxH (default 160x90)")
    parser.add_argument("--samples", type=int, default=16,
                        help="Cycles samples per pixel (default 16)")
    parser.add_argument("--seed", type=int, default=1,
                        help="Cycles seed (default 1)")
    parser.add_argument("--hdr", action="store_true",
                        help="HDR frames: a stronger sun, emissive "
                             "headlights, no clamp (default: clamped to "
                             "[0, 1])")
    args = parser.parse_args(argv)
    try:
        width, height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        parser.error(f"--size must be WIDTHxHEIGHT, not {args.size!r}")
    if width < 1 or height < 1 or args.frames < 2 or args.samples < 1:
        parser.error("--size, --frames (at least 2) and --samples must be "
                     "positive")
    args.width, args.height = width, height
    args.out = os.path.abspath(args.out)
    return args


def clear_scene():
    """Start from an empty scene (factory startup still has a cube, a light
    and a camera)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return bpy.context.scene


def configure_render(scene, args):
    """Cycles on the CPU, fixed seed, no denoising, no motion blur, frames
    0 .. N-1."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.samples
    scene.cycles.seed = args.seed
    scene.cycles.use_animated_seed = False
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.render.use_motion_blur = False  # else Cycles has no Vector pass
    scene.render.use_persistent_data = True
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.fps = 24
    scene.frame_start = 0
    scene.frame_end = args.frames - 1
    # Display only: EXR files hold scene-linear values whatever the view.
    scene.view_settings.view_transform = "Standard"
    view_layer = scene.view_layers[0]
    view_layer.use_pass_z = True
    view_layer.use_pass_vector = True


def make_world(scene):
    """A dim grey sky, so shadows are not black."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.6, 0.7, 0.8, 1.0)
    background.inputs["Strength"].default_value = WORLD_STRENGTH
    scene.world = world


def grass_material():
    """Grass-like ground: two noise textures pick the hue (yellow-green to
    dark green to brown) and a fine Voronoi texture the brightness, at about
    a pixel's scale, so the detail aliases."""
    mat = bpy.data.materials.new("Grass")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 0.9
    bsdf.inputs["Specular"].default_value = 0.1

    coords = nodes.new("ShaderNodeTexCoord")

    hue_noise = nodes.new("ShaderNodeTexNoise")
    hue_noise.inputs["Scale"].default_value = 9.0
    hue_noise.inputs["Detail"].default_value = 6.0
    links.new(coords.outputs["Object"], hue_noise.inputs["Vector"])
    hue_ramp = nodes.new("ShaderNodeValToRGB")
    ramp = hue_ramp.color_ramp
    ramp.elements[0].position = 0.35
    ramp.elements[0].color = (0.02, 0.12, 0.015, 1.0)   # dark green
    ramp.elements[1].position = 0.65
    ramp.elements[1].color = (0.22, 0.32, 0.04, 1.0)    # yellow-green
    links.new(hue_noise.outputs["Fac"], hue_ramp.inputs["Fac"])

    soil_noise = nodes.new("ShaderNodeTexNoise")
    soil_noise.inputs["Scale"].default_value = 3.0
    soil_noise.inputs["Detail"].default_value = 4.0
    links.new(coords.outputs["Object"], soil_noise.inputs["Vector"])
    soil_ramp = nodes.new("ShaderNodeValToRGB")
    soil_ramp.color_ramp.elements[0].position = 0.55
    soil_ramp.color_ramp.elements[0].color = (0.0, 0.0, 0.0, 1.0)
    soil_ramp.color_ramp.elements[1].position = 0.7
    soil_ramp.color_ramp.elements[1].color = (0.6, 0.6, 0.6, 1.0)
    links.new(soil_noise.outputs["Fac"], soil_ramp.inputs["Fac"])
    soil_mix = nodes.new("ShaderNodeMixRGB")
    soil_mix.inputs["Color2"].default_value = (0.16, 0.1, 0.04, 1.0)  # brown
    links.new(soil_ramp.outputs["Color"], soil_mix.inputs["Fac"])
    links.new(hue_ramp.outputs["Color"], soil_mix.inputs["Color1"])

    blades = nodes.new("ShaderNodeTexVoronoi")
    blades.inputs["Scale"].default_value = 28.0
    links.new(coords.outputs["Object"], blades.inputs["Vector"])
    blade_ramp = nodes.new("ShaderNodeMapRange")
    blade_ramp.inputs["To Min"].default_value = 0.35
    blade_ramp.inputs["To Max"].default_value = 1.6
    links.new(blades.outputs["Distance"], blade_ramp.inputs["Value"])

    shade = nodes.new("ShaderNodeMixRGB")
    shade.blend_type = "MULTIPLY"
    shade.inputs["Fac"].default_value = 1.0
    links.new(soil_mix.outputs["Color"], shade.inputs["Color1"])
    links.new(blade_ramp.outputs["Result"], shade.inputs["Color2"])
    links.new(shade.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def plain_material(name, color, roughness):
    """A single-color diffuse-ish material."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Specular"].default_value = 0.2
    return mat


def make_ground():
    """The textured ground plane, large enough to fill the view."""
    bpy.ops.mesh.primitive_plane_add(size=GROUND_SIZE, location=(0, 0, 0))
    ground = bpy.context.active_object
    ground.name = "Ground"
    ground.data.materials.append(grass_material())
    return ground


def emissive_material(name, color, strength):
    """A light-emitting surface (the --hdr headlights)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*color, 1.0)
    emission.inputs["Strength"].default_value = strength
    mat.node_tree.links.new(emission.outputs["Emission"],
                            nodes["Material Output"].inputs["Surface"])
    return mat


def make_car(headlights):
    """The saturated red box with four near-black wheels parented to it and,
    with `headlights`, two emissive boxes on its front."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=CAR_START)
    car = bpy.context.active_object
    car.name = "Car"
    car.data.transform(Matrix.Diagonal((*CAR_SIZE, 1.0)))  # scale stays 1
    car.data.materials.append(
        plain_material("Red", (0.8, 0.01, 0.01), roughness=0.6))
    tire = plain_material("Tire", (0.01, 0.01, 0.01), roughness=0.8)
    half_x, half_y = CAR_SIZE[0] * 0.3, CAR_SIZE[1] * 0.5 + 0.06
    wheel_z = WHEEL_RADIUS - CAR_START[2]  # the wheels touch the ground
    for dx in (-half_x, half_x):
        for dy in (-half_y, half_y):
            bpy.ops.mesh.primitive_cylinder_add(
                radius=WHEEL_RADIUS, depth=0.15, vertices=24,
                rotation=(math.pi / 2, 0, 0))
            wheel = bpy.context.active_object
            wheel.name = "Wheel"
            wheel.data.materials.append(tire)
            wheel.parent = car
            wheel.location = (dx, dy, wheel_z)  # in the car's space
    if headlights:
        light = emissive_material("Headlight", (1.0, 0.95, 0.8),
                                  HEADLIGHT_STRENGTH)
        for dy in (-0.3, 0.3):
            bpy.ops.mesh.primitive_cube_add(size=0.18)
            lamp = bpy.context.active_object
            lamp.name = "Headlight"
            lamp.data.materials.append(light)
            lamp.parent = car
            lamp.location = (CAR_SIZE[0] * 0.5 + 0.05, dy, 0.1)
    return car


def animate_car(car, last_frame):
    """Drive the car from CAR_START on frame 0 to CAR_END on the last frame,
    at constant speed."""
    car.location = CAR_START
    car.keyframe_insert("location", frame=0)
    car.location = CAR_END
    car.keyframe_insert("location", frame=last_frame)
    for curve in car.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = "LINEAR"
        curve.extrapolation = "CONSTANT"


def make_camera(scene):
    """A static camera above and in front of the ground, looking down at
    about 35 degrees."""
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = 35.0
    camera = bpy.data.objects.new("Camera", cam_data)
    scene.collection.objects.link(camera)
    camera.location = (0.0, -11.0, 6.5)
    camera.rotation_euler = (math.radians(58.0), 0.0, 0.0)
    scene.camera = camera
    return camera


def make_sun(scene, strength):
    """A sun from the side and above, for shading and shadows."""
    sun_data = bpy.data.lights.new("Sun", type="SUN")
    sun_data.energy = strength
    sun_data.angle = math.radians(2.0)
    sun = bpy.data.objects.new("Sun", sun_data)
    scene.collection.objects.link(sun)
    sun.rotation_euler = (math.radians(40.0), math.radians(25.0),
                          math.radians(30.0))
    return sun


def file_output(tree, out_dir, kind, color_mode):
    """A File Output node writing 32-bit float EXR to out_dir/kind/NNNN.exr.

    Blender appends the frame number to the slot's path; the trailing slash
    makes `kind` a folder (without it, 3.4 writes out_dir/kind0000.exr)."""
    node = tree.nodes.new("CompositorNodeOutputFile")
    node.base_path = out_dir
    node.file_slots[0].path = kind + "/"
    node.format.file_format = "OPEN_EXR"
    node.format.color_depth = "32"
    node.format.color_mode = color_mode
    node.format.exr_codec = "ZIP"
    return node


def build_compositor(scene, out_dir, hdr):
    """Render Layers -> clamp -> color/, Vector -> motion/, Depth -> depth/.

    The clamp (a Mix node with Clamp on, mixing nothing in) keeps the color in
    [0, 1], an "ldr" sequence's range; with `hdr` it mixes without clamping."""
    scene.use_nodes = True
    tree = scene.node_tree
    for node in list(tree.nodes):
        tree.nodes.remove(node)
    layers = tree.nodes.new("CompositorNodeRLayers")

    clamp = tree.nodes.new("CompositorNodeMixRGB")
    clamp.blend_type = "MIX"
    clamp.use_clamp = not hdr
    clamp.inputs["Fac"].default_value = 0.0
    tree.links.new(layers.outputs["Image"], clamp.inputs[1])

    color = file_output(tree, out_dir, "color", "RGB")
    motion = file_output(tree, out_dir, "motion", "RGB")
    depth = file_output(tree, out_dir, "depth", "RGB")
    tree.links.new(clamp.outputs["Image"], color.inputs[0])
    tree.links.new(layers.outputs["Vector"], motion.inputs[0])
    tree.links.new(layers.outputs["Depth"], depth.inputs[0])

    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(clamp.outputs["Image"], composite.inputs["Image"])


def frame_path(kind, index):
    """A frame's file name relative to the sequence folder."""
    return f"{kind}/{index:04d}.exr"


def find_written(out_dir, kind, index):
    """The file Blender wrote for frame `index` of pass `kind`, whatever
    padding it chose; renamed to NNNN.exr if it differs."""
    wanted = os.path.join(out_dir, frame_path(kind, index))
    if os.path.isfile(wanted):
        return wanted
    folder = os.path.join(out_dir, kind)
    for name in os.listdir(folder):
        stem, ext = os.path.splitext(name)
        if ext.lower() == ".exr" and stem.isdigit() and int(stem) == index:
            os.replace(os.path.join(folder, name), wanted)
            return wanted
    raise RuntimeError(f"Blender wrote no {kind} file for frame {index}")


def render_frames(scene, out_dir, frame_count):
    """Render every frame; the File Output nodes write the passes."""
    for index in range(frame_count):
        scene.frame_set(index)
        bpy.ops.render.render(write_still=False)
        for kind in PASSES:
            find_written(out_dir, kind, index)


def drop_first_motion(out_dir):
    """Delete motion/0000.exr: the first frame has no history, and the folder
    should hold only the files sequence.json names."""
    first = os.path.join(out_dir, frame_path("motion", 0))
    if os.path.isfile(first):
        os.remove(first)


def write_sequence_json(out_dir, args):
    """Write sequence.json, format version 1, Blender's motion convention."""
    frames = []
    for index in range(args.frames):
        frame = {"color": frame_path("color", index)}
        if index > 0:
            frame["motion"] = frame_path("motion", index)
        frame["depth"] = frame_path("depth", index)
        frames.append(frame)
    sequence = {
        "kdop_sequence": 1,
        "width": args.width,
        "height": args.height,
        "color": {"range": "hdr" if args.hdr else "ldr"},
        # A moving camera-still capture without jitter: it has ghosting to
        # measure, and its shimmer would be the motion's, not the clip's.
        "measure": ["ghosting"],
        "motion": {"units": "pixels", "points_to": "previous",
                   "y_axis": "up"},
        "frames": frames,
    }
    with open(os.path.join(out_dir, "sequence.json"), "w",
              encoding="utf-8") as f:
        json.dump(sequence, f, indent=1)
        f.write("\n")


def main():
    args = parse_args(sys.argv)
    for kind in PASSES:
        os.makedirs(os.path.join(args.out, kind), exist_ok=True)
    scene = clear_scene()
    configure_render(scene, args)
    make_world(scene)
    make_ground()
    animate_car(make_car(args.hdr), args.frames - 1)
    make_camera(scene)
    make_sun(scene, HDR_SUN_STRENGTH if args.hdr else SUN_STRENGTH)
    build_compositor(scene, args.out, args.hdr)

    start = time.monotonic()
    render_frames(scene, args.out, args.frames)
    seconds = time.monotonic() - start
    drop_first_motion(args.out)
    write_sequence_json(args.out, args)
    print(f"render_sequence.py: {args.frames} frames, {args.width}x"
          f"{args.height}, {args.samples} samples"
          f"{', HDR' if args.hdr else ''}, in {seconds:.1f} s: "
          f"{args.out}/sequence.json")


if __name__ == "__main__":
    main()

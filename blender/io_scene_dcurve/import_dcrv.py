"""File > Import > dcurve (.dcrv): a mesh object animated by one shape key per frame."""

import os

import bpy
import numpy as np
from bpy.props import BoolProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ImportHelper
from mathutils import Matrix

from . import mesh_build, module


def add_frame_keys(obj, frames, frame_start):
    """Shape key f holds frame f; at scene frame frame_start + f only key f has weight 1
    (constant keys), so the evaluated mesh is frame f, and the last frame holds after."""
    obj.shape_key_add(name="Basis", from_mix=False)
    keys = obj.data.shape_keys
    keys.use_relative = True
    action = bpy.data.actions.new(obj.name + "_frames")
    keys.animation_data_create().action = action
    last = len(frames) - 1
    for f in range(1, len(frames)):
        key = obj.shape_key_add(name="frame_%05d" % f, from_mix=False)
        key.data.foreach_set("co", np.ascontiguousarray(frames[f], np.float32).ravel())
        curve = action.fcurves.new('key_blocks["%s"].value' % key.name)
        points = [(frame_start + f - 1, 0.0), (frame_start + f, 1.0)]
        if f < last:
            points.append((frame_start + f + 1, 0.0))
        curve.keyframe_points.add(len(points))
        curve.keyframe_points.foreach_set("co", [x for p in points for x in p])
        for point in curve.keyframe_points:
            point.interpolation = "CONSTANT"


def set_scene_timing(scene, dec, frame_start):
    if dec.frame_rate > 0:
        fps = max(1, round(dec.frame_rate))
        scene.render.fps = fps
        scene.render.fps_base = fps / dec.frame_rate
    scene.frame_start = frame_start
    scene.frame_end = frame_start + dec.frame_count - 1
    scene.frame_set(frame_start)


def start_frame(dec, use_file_start, frame_start):
    """The scene frame of the file's frame 0: its start time at its rate when it records one."""
    if use_file_start and dec.start_time != 0 and dec.frame_rate > 0:
        return round(dec.start_time * dec.frame_rate)
    return frame_start


def import_file(context, path, use_file_start, frame_start):
    dcurve = module.load()
    dec = dcurve.Decoder(path)
    frames = dec.frames()
    name = dec.node_name or os.path.splitext(os.path.basename(path))[0]
    mesh = mesh_build.build_mesh(dec.mesh_name or name, dec, frames[0])
    obj = bpy.data.objects.new(name, mesh)
    context.collection.objects.link(obj)
    if dec.world_matrix is not None:
        obj.matrix_world = Matrix(dec.world_matrix.tolist())
    first = start_frame(dec, use_file_start, frame_start)
    if len(frames) > 1:
        add_frame_keys(obj, frames, first)
    for other in context.selected_objects:
        other.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj
    set_scene_timing(context.scene, dec, first)
    return obj, dec


class ImportDcurve(bpy.types.Operator, ImportHelper):
    """Import a dcurve file as a mesh object animated by shape keys"""

    bl_idname = "import_scene.dcurve"
    bl_label = "Import dcurve"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".dcrv"
    filter_glob: StringProperty(default="*.dcrv", options={"HIDDEN"})
    use_file_start: BoolProperty(name="Start From File", default=True,
                                 description="Start at the file's recorded start time when it has one")
    frame_start: IntProperty(name="Start Frame", default=1, description="Scene frame of the file's first frame")

    def execute(self, context):
        try:
            obj, dec = import_file(context, self.filepath, self.use_file_start, self.frame_start)
        except (module.ModuleMissing, ValueError, OSError) as e:
            self.report({"ERROR"}, "dcurve import: %s" % e)
            return {"CANCELLED"}
        self.report({"INFO"}, "dcurve import: %s: %d vertices x %d frames" % (obj.name, dec.vertex_count,
                                                                           dec.frame_count))
        return {"FINISHED"}

"""File > Export > dcurve (.dcrv): the active mesh object over a frame range."""

import os

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty
from bpy_extras.io_utils import ExportHelper

from . import encoding, module, sampling


def write_atomically(path, data):
    """A finished file or none: a failed write leaves no partial .dcrv behind."""
    temporary = path + ".partial"
    with open(temporary, "wb") as f:
        f.write(data)
    os.replace(temporary, path)


class ExportDcurve(bpy.types.Operator, ExportHelper):
    """Export the active mesh object's animation (modifiers and simulations applied) as a dcurve file"""

    bl_idname = "export_scene.dcurve"
    bl_label = "Export dcurve"
    bl_options = {"PRESET"}

    filename_ext = ".dcrv"
    filter_glob: bpy.props.StringProperty(default="*.dcrv", options={"HIDDEN"})
    tolerance: FloatProperty(name="Tolerance", description="Max error, fraction of the rest pose's bounding-box diagonal",
                             default=1e-3, min=1e-6, max=0.5, precision=5)
    frame_start: IntProperty(name="Start Frame", description="First frame exported (default: the scene's)")
    frame_end: IntProperty(name="End Frame", description="Last frame exported (default: the scene's)")
    space: EnumProperty(name="Space", default="WORLD", items=(
        ("WORLD", "World", "Positions in world space, object transforms and their animation included"),
        ("LOCAL", "Local", "Positions in the object's space; the file records the object's transform at the start")))

    def invoke(self, context, event):
        self._default_frames(context)
        return ExportHelper.invoke(self, context, event)

    def _default_frames(self, context):
        if not self.properties.is_property_set("frame_start"):
            self.frame_start = context.scene.frame_start
        if not self.properties.is_property_set("frame_end"):
            self.frame_end = context.scene.frame_end

    def execute(self, context):
        self._default_frames(context)
        obj = context.active_object
        if obj is None or obj.type != "MESH":
            self.report({"ERROR"}, "dcurve export: select a mesh object (the active object is exported)")
            return {"CANCELLED"}
        if self.frame_end < self.frame_start:
            self.report({"ERROR"}, "dcurve export: the end frame is before the start frame")
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0.0, 1.0)
        try:
            data, frame_count, vertex_count = self._encode(context, obj, wm)
            write_atomically(self.filepath, data)
        except (module.ModuleMissing, sampling.SamplingError, ValueError, OSError) as e:
            self.report({"ERROR"}, "dcurve export: %s" % e)
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        self.report({"INFO"}, "dcurve export: %s: %d bytes, %d vertices x %d frames" % (
            self.filepath, len(data), vertex_count, frame_count))
        return {"FINISHED"}

    def _encode(self, context, obj, wm):
        dcurve = module.load()
        world = self.space == "WORLD"
        # Sampling takes the first half of the bar, the encode the second.
        topology, frames = sampling.sample(context, obj, self.frame_start, self.frame_end, world,
                                           lambda i, n: wm.progress_update(0.5 * i / n))
        scene = context.scene
        fps = scene.render.fps / scene.render.fps_base
        keywords = dict(tolerance=self.tolerance, fps=fps, start_time=self.frame_start / fps,
                        mesh_name=obj.data.name, node_name=obj.name)
        if not world:
            keywords["matrix"] = [list(row) for row in obj.matrix_world]
        faces = topology.faces if len(topology.faces) else None
        if faces is not None and topology.uvs is not None:
            keywords["uvs"] = topology.uvs
        keywords.update(sampling.material_keywords(obj, topology))
        job = encoding.BackgroundEncode(dcurve, frames, faces, keywords)
        data = job.run(lambda fraction: wm.progress_update(0.5 + 0.5 * fraction))
        return data, len(frames), topology.vertex_count

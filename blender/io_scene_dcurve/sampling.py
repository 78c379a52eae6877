"""The active object's evaluated mesh over a frame range, as the arrays dcurve.encode takes:
positions per frame (modifiers, shape keys, cloth and soft-body caches applied), triangles,
per-corner UVs and a face group per material slot."""

import numpy as np


class SamplingError(ValueError):
    pass


def loop_vertices(mesh):
    out = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", out)
    return out


class Topology:
    """What frame 0 fixes: the polygons, their triangles (Blender triangulates a deforming quad
    along its shorter diagonal, which may change from frame to frame: frame 0's is kept), the
    corners' UVs and the material slots."""

    def __init__(self, mesh):
        self.polygon_corners = loop_vertices(mesh)
        mesh.calc_loop_triangles()
        count = len(mesh.loop_triangles)
        self.vertex_count = len(mesh.vertices)
        self.faces = np.empty(count * 3, np.int32)
        mesh.loop_triangles.foreach_get("vertices", self.faces)
        self.faces = self.faces.reshape(count, 3)
        loops = np.empty(count * 3, np.int32)
        mesh.loop_triangles.foreach_get("loops", loops)
        self.materials = np.empty(count, np.int32)
        mesh.loop_triangles.foreach_get("material_index", self.materials)
        self.uvs = corner_uvs(mesh, loops.reshape(count, 3))

    def same_as(self, mesh):
        return len(mesh.vertices) == self.vertex_count and np.array_equal(loop_vertices(mesh), self.polygon_corners)


def corner_uvs(mesh, loops):
    """The active UV layer per triangle corner, v flipped to dcurve's (glTF's) convention."""
    layer = mesh.uv_layers.active
    if layer is None:
        return None
    uv = np.empty(len(mesh.loops) * 2, np.float32)
    layer.data.foreach_get("uv", uv)
    uv = uv.reshape(-1, 2)[loops]
    uv[..., 1] = 1.0 - uv[..., 1]
    return uv


def positions(mesh, matrix):
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    if matrix is None:
        return co
    m = np.array(matrix, np.float64)
    return (co @ m[:3, :3].T + m[:3, 3]).astype(np.float32)


def sample(context, obj, frame_start, frame_end, world_space, step=None):
    """(topology, frames (F, V, 3)); `step(i, count)` after each frame. Raises SamplingError
    when the mesh's vertices or triangles change between frames."""
    scene = context.scene
    current = scene.frame_current
    count = frame_end - frame_start + 1
    topology, frames = None, []
    try:
        for i, frame in enumerate(range(frame_start, frame_end + 1)):
            scene.frame_set(frame)
            evaluated = obj.evaluated_get(context.evaluated_depsgraph_get())
            mesh = evaluated.to_mesh()
            try:
                if topology is None:
                    topology = Topology(mesh)
                elif not topology.same_as(mesh):
                    raise SamplingError(
                        "%s: the vertex count or the faces change at frame %d (%d vertices, frame %d has %d): "
                        "dcurve needs fixed connectivity" % (obj.name, frame, len(mesh.vertices), frame_start,
                                                            topology.vertex_count))
                frames.append(positions(mesh, evaluated.matrix_world if world_space else None))
            finally:
                evaluated.to_mesh_clear()
            if step:
                step(i + 1, count)
    finally:
        scene.frame_set(current)
    return topology, np.stack(frames)


def material_keywords(obj, topology):
    """face_groups, group_names and materials for the object's material slots."""
    slots = obj.material_slots
    if not slots or len(topology.faces) == 0:
        return {}
    materials = []
    for slot in slots:
        m = slot.material
        entry = {"name": m.name if m else slot.name}
        if m:
            entry["pbrMetallicRoughness"] = {"baseColorFactor": [float(c) for c in m.diffuse_color]}
        materials.append(entry)
    return {
        "face_groups": np.clip(topology.materials, 0, len(slots) - 1),
        "group_names": [e["name"] for e in materials],
        "materials": {"materials": materials},
    }

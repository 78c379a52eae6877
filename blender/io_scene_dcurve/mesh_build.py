"""A Blender mesh from a decoded file: its triangles, UVs and one material per face group."""

import bpy
import numpy as np


def render_triangles(dec):
    """The triangles as render vertex ids (grouped by material when the file has groups) and
    the vertex each render vertex shows."""
    triangles = dec.group_faces
    if triangles is None:
        triangles = dec.render_faces
    if triangles is None:
        triangles = dec.faces
    source = dec.render_source
    if source is None:
        source = np.arange(dec.vertex_count, dtype=np.uint32)
    return triangles, source


def material_for(dec, group, index):
    """A material for face group `group`: the file's material of that name, or a new one with
    the file's base colour."""
    materials = (dec.materials or {}).get("materials", [])
    entry = materials[group["material"]] if 0 <= group["material"] < len(materials) else {}
    name = group["name"] or entry.get("name") or "dcurve_group_%d" % index
    material = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    color = entry.get("pbrMetallicRoughness", {}).get("baseColorFactor")
    if color and len(color) == 4:
        material.diffuse_color = color
    return material


def add_uvs(mesh, dec, corners):
    uvs = dec.uvs
    if uvs is None or len(corners) == 0:
        return
    uv = uvs[corners].astype(np.float32)
    uv[:, 1] = 1.0 - uv[:, 1]  # dcurve (glTF) runs v down the image, Blender up
    layer = mesh.uv_layers.new(name="UVMap")
    layer.data.foreach_set("uv", uv.ravel())


def add_groups(mesh, dec):
    groups = dec.groups
    if not groups:
        return
    index = np.zeros(len(mesh.polygons), np.int32)
    for g, group in enumerate(groups):
        mesh.materials.append(material_for(dec, group, g))
        index[group["first_face"]:group["first_face"] + group["face_count"]] = g
    mesh.polygons.foreach_set("material_index", index)


def build_mesh(name, dec, rest):
    """A mesh of the file's vertices at positions `rest` (V, 3)."""
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(dec.vertex_count)
    mesh.vertices.foreach_set("co", np.ascontiguousarray(rest, np.float32).ravel())
    if dec.face_count:
        triangles, source = render_triangles(dec)
        corners = triangles.ravel().astype(np.int64)
        count = len(triangles)
        mesh.loops.add(3 * count)
        mesh.loops.foreach_set("vertex_index", source[corners].astype(np.int32))
        mesh.polygons.add(count)
        mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * count, 3, dtype=np.int32))
        mesh.polygons.foreach_set("loop_total", np.full(count, 3, np.int32))
        add_uvs(mesh, dec, corners)
        add_groups(mesh, dec)
    mesh.update(calc_edges=True)
    return mesh

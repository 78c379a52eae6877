"""The add-on's test, run headless:
blender -b --factory-startup --python-exit-code 1 --python test_addon.py -- \
    --addon-dir DIR --cli DCURVE [--corpus CORPUS_EXT]
DIR holds io_scene_dcurve (with the compiled module, as cmake --install ships it).

1. A cloth sheet falling onto a sphere, baked, exported with export_scene.dcurve and imported
   back with import_scene.dcurve: at scene frame frame_start + f the imported object's
   evaluated mesh is frame f within the tolerance (max |x_hat - x| / L, L the rest pose's
   bounding-box diagonal); faces, UVs, materials, frame range and rate come back.
   A Wave modifier's grid exported in local space comes back with its object transform.
2. A mesh whose vertex count changes over time (a Build modifier) is refused with a message.
3. A .dcrv from `dcurve encode` of a corpus-ext clip imports as its decode, frame by frame.
4. A damaged file is refused with a message; Blender goes on.
"""

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import bpy
import numpy as np


def arguments():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-dir", required=True)
    parser.add_argument("--cli", required=True)
    parser.add_argument("--corpus", default="")
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:])


def evaluated_positions(obj, frame):
    scene = bpy.context.scene
    scene.frame_set(frame)
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    evaluated.to_mesh_clear()
    m = np.array(evaluated.matrix_world)
    return co.reshape(-1, 3).astype(np.float64) @ m[:3, :3].T + m[:3, 3]


def max_relative_error(got, want):
    rest = want[0]
    diagonal = np.linalg.norm(rest.max(axis=0) - rest.min(axis=0))
    return max(np.linalg.norm(g - w, axis=1).max() for g, w in zip(got, want)) / diagonal


def imported_frames(obj, first, count):
    return [evaluated_positions(obj, first + f) for f in range(count)]


def triangles(obj):
    mesh = obj.data
    mesh.calc_loop_triangles()
    out = np.empty(len(mesh.loop_triangles) * 3, np.int32)
    mesh.loop_triangles.foreach_get("vertices", out)
    return {tuple(np.roll(t, -int(np.argmin(t)))) for t in out.reshape(-1, 3).tolist()}


def loop_uvs(mesh):
    """Per loop: its vertex and its UV."""
    uv = np.empty(len(mesh.loops) * 2, np.float32)
    mesh.uv_layers.active.data.foreach_get("uv", uv)
    vertex = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", vertex)
    return vertex, uv.reshape(-1, 2)


def uvs_match(original, imported, step=1e-4):
    """Each imported corner's UV is within `step` of a UV the original has at that vertex."""
    by_vertex = {}
    for v, uv in zip(*loop_uvs(original)):
        by_vertex.setdefault(int(v), []).append(uv)
    return all(min(np.abs(uv - known).max() for known in by_vertex[int(v)]) <= step
               for v, uv in zip(*loop_uvs(imported)))


def cloth_scene():
    """A 13 x 13 sheet with a UV map and a material, 30 frames of cloth falling onto a sphere, baked."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 30
    scene.render.fps = 24
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, location=(0, 0, 0), segments=16, ring_count=8)
    bpy.context.active_object.modifiers.new("Collision", "COLLISION")
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=13, y_subdivisions=13, size=2, location=(0.2, 0, 1.0),
                                    calc_uvs=True)
    sheet = bpy.context.active_object
    sheet.name = "Sheet"
    material = bpy.data.materials.new("SheetRed")
    material.diffuse_color = (0.8, 0.1, 0.1, 1.0)
    sheet.data.materials.append(material)
    cloth = sheet.modifiers.new("Cloth", "CLOTH")
    cloth.point_cache.frame_start, cloth.point_cache.frame_end = 1, 30
    with bpy.context.temp_override(scene=scene, active_object=sheet, point_cache=cloth.point_cache):
        bpy.ops.ptcache.bake(bake=True)
    assert cloth.point_cache.is_baked, "the cloth did not bake"
    return sheet


def test_cloth_round_trip(tmp):
    sheet = cloth_scene()
    original = imported_frames(sheet, 1, 30)
    moved = max_relative_error(original, [original[0]] * 30)
    assert moved > 0.05, "the cloth hardly moved (%g of L)" % moved
    path = str(tmp / "cloth.dcrv")
    tolerance = 1e-3
    assert bpy.ops.export_scene.dcurve(filepath=path, tolerance=tolerance, frame_start=1, frame_end=30) == {"FINISHED"}
    original_triangles = triangles(sheet)
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = 100, 101
    bpy.context.scene.render.fps = 60
    assert bpy.ops.import_scene.dcurve(filepath=path) == {"FINISHED"}
    imported = bpy.context.active_object
    assert imported is not sheet and imported.name.startswith("Sheet")
    scene = bpy.context.scene
    assert (scene.frame_start, scene.frame_end, scene.render.fps) == (1, 30, 24), "scene range and rate not set"
    error = max_relative_error(imported_frames(imported, 1, 30), original)
    print("cloth round trip: max error %.9g of L (tolerance %g), motion %.3g of L" % (error, tolerance, moved))
    assert error <= tolerance, "imported frames off by %g of L" % error
    # World-space positions in world space: the sheet's vertices in world coordinates.
    assert len(imported.data.vertices) == len(sheet.data.vertices)
    assert triangles(imported) == original_triangles
    assert [m.name for m in imported.data.materials] == ["SheetRed"]
    assert imported.data.uv_layers.active is not None
    assert uvs_match(sheet.data, imported.data)

def test_local_space_keeps_the_object_transform(tmp):
    """A Wave modifier on a rotated, moved grid, exported in the object's space: the import
    puts the recorded transform back, so the world positions match."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 8
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=8, y_subdivisions=8, location=(3, -1, 2), rotation=(0.4, 0, 1.1))
    grid = bpy.context.active_object
    grid.modifiers.new("Wave", "WAVE").height = 0.3
    original = imported_frames(grid, 1, 8)
    path = tmp / "local.dcrv"
    assert bpy.ops.export_scene.dcurve(filepath=str(path), space="LOCAL") == {"FINISHED"}
    assert bpy.ops.import_scene.dcurve(filepath=str(path)) == {"FINISHED"}
    imported = bpy.context.active_object
    assert np.allclose(np.array(imported.matrix_world), np.array(grid.matrix_world), atol=1e-6)
    error = max_relative_error(imported_frames(imported, 1, 8), original)
    assert error <= 1e-3, "local-space frames off by %g of L" % error
    assert max_relative_error(original, [original[0]] * 8) > 0.01, "the wave did not move the grid"


def test_changing_vertex_count_is_refused(tmp):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, 10
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=6, y_subdivisions=6)
    build = bpy.context.active_object.modifiers.new("Build", "BUILD")
    build.frame_start, build.frame_duration = 1, 8
    path = tmp / "build.dcrv"
    try:
        bpy.ops.export_scene.dcurve(filepath=str(path), frame_start=1, frame_end=10)
    except RuntimeError as e:
        assert "vertex count or the faces change" in str(e), str(e)
    else:
        raise AssertionError("a mesh with a changing vertex count was exported")
    assert not path.exists()


def test_cli_file_imports_as_its_decode(tmp, cli, corpus):
    source = pathlib.Path(corpus) / "cloth-sphere"
    if not source.is_dir():
        print("no corpus-ext cloth-sphere: skipped the CLI file import")
        return
    clip = tmp / "clip"
    clip.mkdir()
    for i in range(6):
        (clip / ("frame_%05d.obj" % i)).symlink_to(source / ("frame_%05d.obj" % (40 + i)))
    path = tmp / "clip.dcrv"
    subprocess.run([cli, "encode", str(clip), "-o", str(path), "-q"], check=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    assert bpy.ops.import_scene.dcurve(filepath=str(path)) == {"FINISHED"}
    obj = bpy.context.active_object
    from io_scene_dcurve import module
    dec = module.load().Decoder(path)
    decoded = dec.frames().astype(np.float64)
    first = bpy.context.scene.frame_start
    assert bpy.context.scene.frame_end == first + 5
    error = max_relative_error(imported_frames(obj, first, 6), decoded)
    print("CLI file import: max difference from its decode %.3g of L" % error)
    assert error <= 1e-6, "imported frames differ from the decode by %g of L" % error
    assert triangles(obj) == {tuple(np.roll(t, -int(np.argmin(t)))) for t in dec.faces.tolist()}


def test_damaged_file_is_refused(tmp):
    path = tmp / "damaged.dcrv"
    path.write_bytes(b"DCRV" + bytes(60))
    try:
        bpy.ops.import_scene.dcurve(filepath=str(path))
    except RuntimeError as e:
        assert "dcurve import:" in str(e), str(e)
    else:
        raise AssertionError("a damaged file was imported")


def main():
    args = arguments()
    sys.path.insert(0, args.addon_dir)
    import io_scene_dcurve
    io_scene_dcurve.register()
    with tempfile.TemporaryDirectory() as scratch:
        tmp = pathlib.Path(scratch)
        for test in (test_cloth_round_trip, test_local_space_keeps_the_object_transform,
                     test_changing_vertex_count_is_refused, test_damaged_file_is_refused):
            start = time.monotonic()
            test(tmp)
            print("%s passed (%.1f s)" % (test.__name__, time.monotonic() - start))
        start = time.monotonic()
        test_cli_file_imports_as_its_decode(tmp, args.cli, args.corpus)
        print("test_cli_file_imports_as_its_decode passed (%.1f s)" % (time.monotonic() - start))
    print("blender add-on tests passed")


main()

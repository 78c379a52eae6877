"""UVs, face groups, materials and placement given to encode come back from the Decoder."""

import numpy as np
import pytest

import dcurve
from conftest import grid_wave


def seamed_uvs(faces, vertex_count):
    """Per-corner UVs: u from the vertex id, except triangle 0 whose corners get u + 0.5 (a seam)."""
    uv = np.stack([np.arange(vertex_count) / vertex_count, np.full(vertex_count, 0.25)], axis=1)[faces]
    uv[0, :, 0] += 0.5
    return uv.astype(np.float32)


def test_per_corner_uvs_split_vertices_at_seams():
    frames, faces = grid_wave(frames=4, n=5)
    uvs = seamed_uvs(faces, 25)
    dec = dcurve.Decoder(dcurve.encode(frames, faces, uvs=uvs))
    assert dec.render_vertex_count == 25 + 3  # the three corners of triangle 0 are copies
    rfaces, source = dec.render_faces, dec.render_source
    assert np.array_equal(source[rfaces], dec.faces)
    # uvs quantized to 14 bits over their range
    step = (uvs.max(axis=(0, 1)) - uvs.min(axis=(0, 1))) / 16383
    decoded = dec.uvs[rfaces]
    order = {tuple(t): i for i, t in enumerate(dec.faces.tolist())}
    for t, tri in enumerate(faces.tolist()):
        for r in range(3):
            rot = tri[r:] + tri[:r]
            if tuple(rot) in order:
                got = decoded[order[tuple(rot)]]
                want = np.roll(uvs[t], -r, axis=0)
                assert np.all(np.abs(got - want) <= step + 1e-7)
                break
        else:
            pytest.fail("triangle %d missing" % t)


def test_groups_materials_and_placement_round_trip():
    frames, faces = grid_wave(frames=4, n=5)
    groups = (np.arange(len(faces)) % 2).astype(np.int32)
    materials = {"materials": [{"name": "Red", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}},
                               {"name": "Blue"}]}
    matrix = np.array([[1, 0, 0, 2], [0, 0, -1, 3], [0, 1, 0, 4], [0, 0, 0, 1]], np.float64)
    dec = dcurve.Decoder(dcurve.encode(frames, faces, face_groups=groups, group_names=["Red", "Blue"],
                                       materials=materials, matrix=matrix, start_time=1.5,
                                       mesh_name="Sheet", node_name="SheetObject"))
    assert [(g["name"], g["material"], g["face_count"]) for g in dec.groups] == [("Red", 0, 16), ("Blue", 1, 16)]
    assert dec.materials["materials"][0]["name"] == "Red"
    assert dec.group_faces.shape == (32, 3)
    np.testing.assert_array_equal(dec.world_matrix, matrix)
    assert (dec.start_time, dec.mesh_name, dec.node_name) == (1.5, "Sheet", "SheetObject")


def test_without_render_data_the_render_vertices_are_the_vertices():
    frames, faces = grid_wave(frames=4, n=5)
    dec = dcurve.Decoder(dcurve.encode(frames, faces))
    assert dec.render_source is None and dec.uvs is None and dec.groups == [] and dec.world_matrix is None
    assert dec.render_vertex_count == 25

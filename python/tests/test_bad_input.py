"""Bad arrays, options and files are refused with dcurve.Error (a ValueError) and a message
that names the problem."""

import numpy as np
import pytest

import dcurve
from conftest import grid_wave


@pytest.fixture
def wave():
    return grid_wave(frames=4, n=5)


@pytest.mark.parametrize("shape", [(4, 25, 2), (25, 3), (0, 25, 3), (4, 0, 3)])
def test_wrong_frame_shapes(wave, shape):
    with pytest.raises(dcurve.Error, match=r"frames: shape \(frames, vertices, 3\) expected"):
        dcurve.encode(np.zeros(shape, np.float32), None)


def test_integer_frames(wave):
    frames, faces = wave
    with pytest.raises(dcurve.Error, match="frames: float32 or float64 values expected"):
        dcurve.encode(frames.astype(np.int32), faces)


@pytest.mark.parametrize("bad", [np.nan, np.inf, 1e30])
def test_non_finite_or_huge_coordinates(wave, bad):
    frames, faces = wave
    frames = frames.astype(np.float64)
    frames[2, 7, 1] = bad
    with pytest.raises(dcurve.Error, match="frame 2, vertex 7: a coordinate is not finite"):
        dcurve.encode(frames, faces)


@pytest.mark.parametrize("value", [25, -1])
def test_faces_out_of_range(wave, value):
    frames, faces = wave
    faces = faces.copy()
    faces[3, 2] = value
    with pytest.raises(dcurve.Error, match=r"faces\[3, 2\] = %d is out of range for 25 vertices" % value):
        dcurve.encode(frames, faces)


def test_faces_shape_and_type(wave):
    frames, faces = wave
    with pytest.raises(dcurve.Error, match=r"faces: shape \(triangles, 3\) expected"):
        dcurve.encode(frames, faces[:, :2])
    with pytest.raises(dcurve.Error, match="faces: integer vertex ids expected"):
        dcurve.encode(frames, faces.astype(np.float32))


def test_degenerate_triangle_has_the_encoder_message(wave):
    frames, faces = wave
    faces = faces.copy()
    faces[5] = (1, 1, 2)
    with pytest.raises(dcurve.Error, match="triangle 5 uses a vertex twice"):
        dcurve.encode(frames, faces)


@pytest.mark.parametrize("options, message", [
    ({"tolerance": 0.9}, "tolerance must be a number in"),
    ({"tolerance": float("nan")}, "tolerance must be a number in"),
    ({"model": "pde16"}, "model must be one of"),
    ({"low_rank": 65}, r"low_rank must be an integer in \[1, 64\]"),
    ({"effort": 4}, "effort must be an integer in"),
    ({"chunk_frames": 0}, "chunk_frames must be an integer in"),
    ({"keep_face_order": 1}, "keep_face_order must be True or False"),
    ({"uvs": np.zeros((24, 2), np.float32)}, r"uvs: shape \(vertices, C\) or \(triangles, 3, C\) expected"),
    ({"face_groups": np.zeros(31, np.int32)}, r"face_groups: shape \(32,\) expected"),
    ({"face_groups": np.full(32, 2), "group_names": ["a", "b"]}, r"face_groups\[0\] = 2 is out of range for 2 groups"),
])
def test_bad_options(wave, options, message):
    frames, faces = wave
    with pytest.raises(dcurve.Error, match=message):
        dcurve.encode(frames, faces, **options)


def test_unknown_keyword_is_a_type_error(wave):
    frames, faces = wave
    with pytest.raises(TypeError, match="unexpected keyword argument 'tolerence'"):
        dcurve.encode(frames, faces, tolerence=1e-3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'mesh'"):
        dcurve.encode(frames, faces, mesh="rest.obj")


def test_bad_files_do_not_open(wave, tmp_path):
    frames, faces = wave
    data = dcurve.encode(frames, faces)
    for bad in (b"", b"not a dcurve file", data[: len(data) // 2]):
        with pytest.raises(dcurve.Error):
            dcurve.Decoder(bad)
    with pytest.raises(dcurve.Error, match="missing.dcrv"):
        dcurve.Decoder(tmp_path / "missing.dcrv")
    with pytest.raises(TypeError):
        dcurve.Decoder(12)
    with pytest.raises(dcurve.Error, match="finite"):
        dcurve.Decoder(data).evaluate(float("nan"))


def test_error_is_a_value_error():
    assert issubclass(dcurve.Error, ValueError)

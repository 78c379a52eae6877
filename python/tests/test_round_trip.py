"""Encode and decode: every frame within the tolerance, the faces and counts kept."""

import numpy as np
import pytest

import dcurve
from conftest import grid_wave, max_relative_error


def triangle_set(faces):
    """Triangles with their corners rotated to start at the smallest id (winding kept)."""
    out = set()
    for t in np.asarray(faces).tolist():
        k = t.index(min(t))
        out.add(tuple(t[k:] + t[:k]))
    return out


@pytest.mark.parametrize("tolerance", [1e-3, 4e-3])
def test_corpus_clip_round_trip_within_tolerance(corpus_arrays, tolerance):
    frames, faces = corpus_arrays
    dec = dcurve.Decoder(dcurve.encode(frames, faces, tolerance=tolerance))
    assert (dec.vertex_count, dec.frame_count, dec.face_count) == (frames.shape[1], len(frames), len(faces))
    assert dec.tolerance == pytest.approx(tolerance)
    assert dec.frame_rate == 30.0
    decoded = dec.frames()
    assert decoded.dtype == np.float32 and decoded.shape == frames.shape
    assert max_relative_error(decoded, frames) <= tolerance
    assert dec.faces.dtype == np.uint32 and triangle_set(dec.faces) == triangle_set(faces)


def test_frame_evaluate_and_frames_agree():
    frames, faces = grid_wave()
    dec = dcurve.Decoder(dcurve.encode(frames.astype(np.float64), faces, fps=24.0))
    assert dec.frame_rate == 24.0
    all_frames = dec.frames()
    for f in range(dec.frame_count):
        np.testing.assert_array_equal(dec.frame(f), all_frames[f])
        np.testing.assert_array_equal(dec.evaluate(f / (dec.frame_count - 1)), all_frames[f])
    np.testing.assert_array_equal(dec.frame(-1), all_frames[-1])
    between = dec.evaluate(0.5 / (dec.frame_count - 1))
    assert not np.array_equal(between, all_frames[0]) and not np.array_equal(between, all_frames[1])
    with pytest.raises(IndexError):
        dec.frame(dec.frame_count)


def test_decoder_opens_bytes_bytearray_memoryview_and_paths(tmp_path):
    frames, faces = grid_wave(frames=4)
    data = dcurve.encode(frames, faces)
    path = tmp_path / "wave.dcrv"
    path.write_bytes(data)
    reference = dcurve.Decoder(data).frames()
    for source in (bytearray(data), memoryview(data), str(path), path):
        np.testing.assert_array_equal(dcurve.Decoder(source).frames(), reference)


def test_without_faces_there_is_no_connectivity():
    frames, _ = grid_wave(frames=4)
    dec = dcurve.Decoder(dcurve.encode(frames))
    assert dec.faces is None and dec.face_count == 0
    assert dec.normals(dec.frame(0)) is None
    assert max_relative_error(dec.frames(), frames) <= 1e-3

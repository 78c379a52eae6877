"""Shared inputs of the module's tests: a small synthetic animation, a short corpus-ext
sequence (a few frames, linked into a scratch folder) and the dcurve CLI of the same build."""

import os
import pathlib

import numpy as np
import pytest


def grid_wave(frames=8, n=9):
    """An n x n sheet with a travelling wave: (F, V, 3) float32 frames and (T, 3) faces."""
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    out = []
    for f in range(frames):
        z = 0.1 * np.sin(2 * np.pi * (u + f / frames)) * v
        out.append(np.stack([u, v, z], axis=-1).reshape(-1, 3))
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            a, b, c, d = i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1
            faces += [(a, b, c), (a, c, d)]
    return np.array(out, np.float32), np.array(faces, np.int64)


def read_obj(path):
    xyz, faces = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        parts = line.split()
        if parts and parts[0] == "v":
            xyz.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            faces.append([int(x.split("/")[0]) - 1 for x in parts[1:4]])
    return np.array(xyz, np.float32), np.array(faces, np.int64)


def rest_diagonal(frames):
    rest = np.asarray(frames[0], np.float64)
    return float(np.linalg.norm(rest.max(axis=0) - rest.min(axis=0)))


def max_relative_error(decoded, frames):
    """max over frames and vertices of |x_hat - x| / L, L the rest pose's bounding-box diagonal."""
    diff = np.linalg.norm(np.asarray(decoded, np.float64) - np.asarray(frames, np.float64), axis=-1)
    return float(diff.max()) / rest_diagonal(frames)


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("DCURVE_CLI")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("DCURVE_CLI names no dcurve program (ctest sets it)")
    return path


@pytest.fixture(scope="session")
def corpus_clip(tmp_path_factory):
    """The first 4 frames of corpus-ext's cloth-sphere (2,500 vertices), linked into a folder."""
    source = pathlib.Path(os.environ.get("DCURVE_CORPUS_EXT", "/work/shared/corpus-ext")) / "cloth-sphere"
    if not source.is_dir():
        pytest.skip("no corpus-ext cloth-sphere (set DCURVE_CORPUS_EXT)")
    folder = tmp_path_factory.mktemp("cloth-sphere-4")
    for i in range(4):
        name = "frame_%05d.obj" % (20 + i)
        (folder / name).symlink_to(source / name)
    return folder


@pytest.fixture(scope="session")
def corpus_arrays(corpus_clip):
    meshes = [read_obj(p) for p in sorted(corpus_clip.glob("*.obj"))]
    return np.stack([m[0] for m in meshes]), meshes[0][1]

"""The module writes what the CLI writes: the same bytes for the same input and options, the
same --json summary, the same error message."""

import json
import subprocess

import numpy as np
import pytest

import dcurve

OPTIONS = {"tolerance": 2e-3, "low_rank": "off", "chunk_frames": 2}
FLAGS = ["--tolerance", "2e-3", "--low-rank", "off", "--chunk-frames", "2"]


def cli_encode(cli, folder, out, flags):
    return subprocess.run([cli, "encode", str(folder), "-o", str(out), "--json", "-q"] + flags,
                          capture_output=True, text=True)


def without_time(summary):
    return {k: v for k, v in summary.items() if k != "encode_seconds"}


def test_same_bytes_and_summary_as_the_cli(cli, corpus_clip, corpus_arrays, tmp_path):
    by_cli = tmp_path / "cli.dcrv"
    run = cli_encode(cli, corpus_clip, by_cli, FLAGS)
    assert run.returncode == 0, run.stderr
    by_file = tmp_path / "module.dcrv"
    summary = dcurve.encode_file(corpus_clip, by_file, **OPTIONS)
    assert by_file.read_bytes() == by_cli.read_bytes()
    cli_summary = json.loads(run.stdout)
    cli_summary["output"] = str(by_file)
    assert without_time(summary) == without_time(cli_summary)
    frames, faces = corpus_arrays
    assert dcurve.encode(frames, faces, **OPTIONS) == by_cli.read_bytes()


def test_options_change_the_bytes_as_they_do_in_the_cli(cli, corpus_clip, corpus_arrays, tmp_path):
    frames, faces = corpus_arrays
    out = tmp_path / "fast.dcrv"
    assert cli_encode(cli, corpus_clip, out, ["--profile", "fast", "--keep-face-order"]).returncode == 0
    assert dcurve.encode(frames, faces, profile="fast", keep_face_order=True) == out.read_bytes()
    assert dcurve.encode(frames, faces) != out.read_bytes()


def test_error_is_the_cli_message(cli, corpus_clip, tmp_path):
    bad = tmp_path / "bad"
    bad.mkdir()
    for obj in sorted(corpus_clip.glob("*.obj"))[:2]:
        (bad / obj.name).symlink_to(obj.resolve())
    last = sorted(bad.glob("*.obj"))[-1]
    last.unlink()
    last.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    run = cli_encode(cli, bad, tmp_path / "bad.dcrv", [])
    assert run.returncode == 1
    with pytest.raises(dcurve.Error) as error:
        dcurve.encode_file(bad, tmp_path / "bad.dcrv")
    assert isinstance(error.value, ValueError)
    assert run.stderr.strip() == "dcurve encode: " + str(error.value)
    assert not (tmp_path / "bad.dcrv").exists()


def test_existing_output_needs_force(corpus_clip, tmp_path):
    out = tmp_path / "x.dcrv"
    out.write_bytes(b"keep")
    with pytest.raises(dcurve.Error, match="--force"):
        dcurve.encode_file(corpus_clip, out, tolerance=4e-3)
    assert out.read_bytes() == b"keep"
    dcurve.encode_file(corpus_clip, out, tolerance=4e-3, force=True)
    assert dcurve.Decoder(out).frame_count == 4

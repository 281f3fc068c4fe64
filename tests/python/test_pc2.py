"""The add-on's .pc2 writer and reader (python_addon/gauss_stylization/bake/pc2.py), without Blender."""

import importlib.util
import os
import struct

import numpy as np
import pytest

from conftest import REPO

_SPEC = importlib.util.spec_from_file_location("pc2", REPO / "python_addon" / "gauss_stylization" / "bake" / "pc2.py")
pc2 = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(pc2)


def _frames(samples=3, points=5, seed=1):
    return np.random.default_rng(seed).normal(size=(samples, points, 3)).astype(np.float32)


def _write(path, frames, start=1.0, rate=1.0):
    writer = pc2.Writer(str(path), frames.shape[1], frames.shape[0], start=start, rate=rate)
    for frame in frames:
        writer.add(frame)
    writer.commit()


def test_round_trip_and_the_exact_layout(tmp_path):
    frames = _frames()
    path = tmp_path / "a.pc2"
    _write(path, frames, start=12.0, rate=0.5)
    data = path.read_bytes()
    # The PC2 header as Blender's Mesh Cache modifier reads it, then float32 xyz little-endian.
    assert data[:32] == b"POINTCACHE2\0" + struct.pack("<iiffi", 1, 5, 12.0, 0.5, 3)
    assert data[32:] == frames.astype("<f4").tobytes() and len(data) == pc2.file_size(5, 3)
    cache = pc2.read(str(path))
    assert (cache.start, cache.rate) == (12.0, 0.5) and np.array_equal(cache.frames, frames)
    assert os.listdir(tmp_path) == ["a.pc2"]


def test_the_file_gets_the_permissions_of_any_new_file(tmp_path):
    # Not the owner-only mode of a temporary file: other users (render nodes) must read a cache.
    _write(tmp_path / "a.pc2", _frames())
    (tmp_path / "plain").write_bytes(b"")
    assert os.stat(tmp_path / "a.pc2").st_mode == os.stat(tmp_path / "plain").st_mode


def test_the_file_appears_only_at_commit_and_discard_keeps_the_old_one(tmp_path):
    path = tmp_path / "a.pc2"
    _write(path, _frames(seed=1))
    old = path.read_bytes()
    writer = pc2.Writer(str(path), 5, 3)
    writer.add(_frames(seed=2)[0])
    assert path.read_bytes() == old and len(os.listdir(tmp_path)) == 2
    writer.discard()
    assert path.read_bytes() == old and os.listdir(tmp_path) == ["a.pc2"]
    writer = pc2.Writer(str(path), 5, 1)
    with pytest.raises(ValueError, match="0 of 1 samples"):
        writer.commit()  # unfinished: refused, nothing replaced
    writer.discard()
    assert path.read_bytes() == old


@pytest.mark.parametrize("frame, message", [
    (np.zeros((4, 3), np.float32), "shape"), (np.zeros((5, 2), np.float32), "shape"),
    (np.full((5, 3), np.nan, np.float32), "NaN"), (np.full((5, 3), np.inf), "NaN"),
])
def test_bad_frames_are_refused(tmp_path, frame, message):
    writer = pc2.Writer(str(tmp_path / "a.pc2"), 5, 2)
    with pytest.raises(ValueError, match=message):
        writer.add(frame)
    writer.discard()


@pytest.mark.parametrize("points, samples, start, rate", [
    (0, 1, 0.0, 1.0), (5, 0, 0.0, 1.0), (-1, 1, 0.0, 1.0), (5, 1, float("nan"), 1.0), (5, 1, 0.0, 0.0),
    (5.0, 1, 0.0, 1.0),
])
def test_nonsense_counts_are_refused(tmp_path, points, samples, start, rate):
    with pytest.raises(ValueError):
        pc2.Writer(str(tmp_path / "a.pc2"), points, samples, start, rate)
    assert os.listdir(tmp_path) == []


def test_too_many_samples_are_refused(tmp_path):
    writer = pc2.Writer(str(tmp_path / "a.pc2"), 5, 1)
    writer.add(_frames()[0])
    with pytest.raises(ValueError, match="already"):
        writer.add(_frames()[1])
    writer.discard()


def test_a_cache_larger_than_the_free_disk_is_refused_before_writing(tmp_path):
    with pytest.raises(OSError, match="MB free"):
        pc2.Writer(str(tmp_path / "a.pc2"), 10 ** 9, 10 ** 6)
    assert os.listdir(tmp_path) == []


def test_a_missing_folder_is_made_and_an_impossible_one_refused(tmp_path):
    writer = pc2.Writer(str(tmp_path / "cache" / "shot" / "a.pc2"), 5, 1)
    writer.discard()
    assert os.listdir(tmp_path / "cache" / "shot") == []
    (tmp_path / "file").write_text("")
    with pytest.raises(OSError, match="cannot make the folder"):
        pc2.Writer(str(tmp_path / "file" / "a.pc2"), 5, 1)


@pytest.mark.parametrize("mangle, message", [
    (lambda b: b[:20], "too short"), (lambda b: b"POINTCACHE3\0" + b[12:], "not a version 1"),
    (lambda b: b[:-4], "truncated"), (lambda b: b + b"\0", "trailing"),
    (lambda b: b[:16] + struct.pack("<i", -5) + b[20:], "points"),
])
def test_broken_files_are_refused(tmp_path, mangle, message):
    path = tmp_path / "a.pc2"
    _write(path, _frames())
    path.write_bytes(mangle(path.read_bytes()))
    with pytest.raises(ValueError, match=message):
        pc2.read(str(path))


def _chunks(tmp_path, frames, ranges, start=1):
    """Write frames[a:b] of each (a, b) in ``ranges`` as its own cache starting at frame start + a."""
    paths = []
    for a, b in ranges:
        path = tmp_path / ("chunk_%d.pc2" % a)
        _write(path, frames[a:b], start=float(start + a))
        paths.append(str(path))
    return paths


def test_merged_chunks_are_byte_identical_to_one_cache_in_any_order(tmp_path):
    frames = _frames(samples=12, points=7)
    _write(tmp_path / "whole.pc2", frames, start=5.0)
    # chunk_10 sorts before chunk_2 by name: the merge goes by the frames, not the names.
    paths = _chunks(tmp_path, frames, [(0, 2), (2, 10), (10, 12)], start=5)
    assert pc2.merge(list(reversed(paths)), str(tmp_path / "merged.pc2")) == (5.0, 12)
    assert (tmp_path / "merged.pc2").read_bytes() == (tmp_path / "whole.pc2").read_bytes()


@pytest.mark.parametrize("ranges, points, message", [
    ([(0, 3), (4, 6)], None, "a gap"),
    ([(0, 4), (3, 6)], None, "an overlap"),
    ([(0, 3), (3, 6)], 4, "not chunks of one bake"),
])
def test_chunks_that_do_not_join_are_refused_and_write_nothing(tmp_path, ranges, points, message):
    frames = _frames(samples=6, points=5)
    paths = _chunks(tmp_path, frames, ranges)
    if points:
        _write(tmp_path / "other.pc2", _frames(samples=3, points=points), start=4.0)
        paths[1] = str(tmp_path / "other.pc2")
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(ValueError, match=message):
        pc2.merge(paths, str(tmp_path / "merged.pc2"))
    assert sorted(os.listdir(tmp_path)) == before
    with pytest.raises(ValueError, match="no chunks"):
        pc2.merge([], str(tmp_path / "merged.pc2"))

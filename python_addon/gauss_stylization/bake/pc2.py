"""Point caches in the PC2 format, which Blender's Mesh Cache modifier plays back.

A .pc2 file is a 32-byte little-endian header followed by the frames, each
``points`` float32 (x, y, z) triples in object space:

    char[12] "POINTCACHE2\\0"; int32 version (1); int32 points;
    float32 start frame; float32 sample rate (frames per sample); int32 samples

Writer writes into a temporary file next to the destination and renames it
over the destination only in commit(), so a cancelled or failed bake leaves
any earlier file as it was and no partial one. Imports nothing from Blender.
"""

import os
import secrets
import shutil
import struct

import numpy as np

MAGIC = b"POINTCACHE2\0"
VERSION = 1
HEADER = struct.Struct("<12siiffi")
FRAME_DTYPE = np.dtype("<f4")
DISK_MARGIN = 64 * 1024 * 1024  # bytes left free on the disk after a bake


def file_size(points, samples):
    return HEADER.size + points * samples * 3 * FRAME_DTYPE.itemsize


class Writer:
    """Write ``samples`` frames of ``points`` positions to ``path``.

    points, samples: the counts, fixed up front (the disk space is checked for all of them);
    start: the frame of the first sample; rate: frames between samples.
    Raises ValueError for nonsense counts and OSError when the folder cannot be made or written,
    or the disk has no room for the whole file.
    """

    def __init__(self, path, points, samples, start=0.0, rate=1.0):
        if not (isinstance(points, int) and points > 0 and isinstance(samples, int) and samples > 0):
            raise ValueError("a point cache needs at least one point and one sample (got %r, %r)"
                             % (points, samples))
        if not (np.isfinite(start) and np.isfinite(rate) and rate > 0):
            raise ValueError("start frame and sample rate must be finite, the rate positive (got %r, %r)"
                             % (start, rate))
        self.path = os.path.abspath(path)
        self.points, self.samples, self.written = points, samples, 0
        folder = os.path.dirname(self.path)
        try:
            os.makedirs(folder, exist_ok=True)  # as Blender's own caches and render output do
        except OSError as exc:
            raise OSError("cannot make the folder %s: %s" % (folder, exc.strerror or exc)) from exc
        needed = file_size(points, samples)
        free = shutil.disk_usage(folder).free
        if needed + DISK_MARGIN > free:
            raise OSError("the point cache needs %.1f MB but %s has %.1f MB free"
                          % (needed / 1e6, folder, free / 1e6))
        self._file, self.temp_path = _new_temporary(self.path)
        self._file.write(HEADER.pack(MAGIC, VERSION, points, float(start), float(rate), samples))

    def add(self, coords):
        """Append one frame: (points, 3) finite coordinates."""
        frame = np.asarray(coords)
        if frame.shape != (self.points, 3):
            raise ValueError("a frame must have shape (%d, 3), got %s" % (self.points, frame.shape))
        if self.written == self.samples:
            raise ValueError("all %d samples are written already" % self.samples)
        frame = np.ascontiguousarray(frame, FRAME_DTYPE)
        if not np.isfinite(frame).all():
            raise ValueError("a frame holds NaN or infinite coordinates")
        self._file.write(frame.tobytes())
        self.written += 1

    def commit(self):
        """Finish the file and move it to ``path`` (replacing what was there)."""
        if self.written != self.samples:
            raise ValueError("%d of %d samples written" % (self.written, self.samples))
        self._file.flush()
        os.fsync(self._file.fileno())
        self._file.close()
        os.replace(self.temp_path, self.path)

    def discard(self):
        """Drop the temporary file; ``path`` is left as it was."""
        if not self._file.closed:
            self._file.close()
        if os.path.exists(self.temp_path):
            os.remove(self.temp_path)


def _new_temporary(path):
    """A new file '<path>.<random>.partial' open for writing, with the permissions a plain new file
    gets (tempfile.mkstemp's would be owner-only: render-farm nodes reading the cache as another user
    could not open it)."""
    for _ in range(100):
        candidate = "%s.%s.partial" % (path, secrets.token_hex(4))
        try:
            handle = os.open(candidate, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0), 0o666)
        except FileExistsError:
            continue
        return os.fdopen(handle, "wb"), candidate
    raise OSError("cannot make a temporary file next to %s" % path)


class PointCache:
    """frames: (samples, points, 3) float32; start, rate: as in the header."""

    def __init__(self, frames, start, rate):
        self.frames, self.start, self.rate = frames, start, rate


def read(path):
    """Read a .pc2 file; ValueError if it is not a complete one (header())."""
    points, start, rate, samples = header(path)
    frames = np.fromfile(path, FRAME_DTYPE, samples * points * 3, offset=HEADER.size)
    return PointCache(frames.astype(np.float32).reshape(samples, points, 3), start, rate)


def header(path):
    """(points, start, rate, samples) of a complete .pc2 file; ValueError as read()."""
    with open(path, "rb") as handle:
        data = handle.read(HEADER.size)
        size = os.fstat(handle.fileno()).st_size
    if len(data) != HEADER.size:
        raise ValueError("%s is too short for a PC2 header" % path)
    magic, version, points, start, rate, samples = HEADER.unpack(data)
    if magic != MAGIC or version != VERSION:
        raise ValueError("%s is not a version %d PC2 file" % (path, VERSION))
    if points <= 0 or samples < 0 or size != file_size(points, samples):
        raise ValueError("%s is truncated or has trailing data (%d samples of %d points expected)"
                         % (path, samples, points))
    return points, start, rate, samples


def merge(paths, out):
    """Join the caches of consecutive frame ranges of one object (farm chunks, in any order) into
    ``out``: the same bytes as one cache of the whole range. The chunks must have the same points and
    sample rate and follow one another without gap or overlap (ValueError naming the culprit).
    Returns (start, samples) of the joined cache."""
    if not paths:
        raise ValueError("no chunks to merge")
    chunks = sorted((header(path) + (path,) for path in paths), key=lambda chunk: chunk[1])
    points, start, rate, _samples, first = chunks[0]
    expected = start
    for chunk_points, chunk_start, chunk_rate, samples, path in chunks:
        if (chunk_points, chunk_rate) != (points, rate):
            raise ValueError("%s has %d points at %g frames per sample, %s %d at %g: not chunks of one bake"
                             % (path, chunk_points, chunk_rate, first, points, rate))
        if chunk_start != expected:
            raise ValueError("%s starts at frame %g, the chunks before it end before frame %g: %s"
                             % (path, chunk_start, expected, "a gap" if chunk_start > expected else "an overlap"))
        expected = chunk_start + samples * rate
    total = sum(chunk[3] for chunk in chunks)
    writer = Writer(out, points, total, start=start, rate=rate)
    try:
        for chunk in chunks:
            for frame in read(chunk[4]).frames:
                writer.add(frame)
        writer.commit()
    except BaseException:
        writer.discard()
        raise
    return start, total

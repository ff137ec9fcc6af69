"""Read dumps in Phantom's native binary format into numpy arrays: the
snapshot_NNNNN.phantom files of mote's SPH problems (output.sph_format =
"phantom" or "both"), and dumps written by Phantom itself.

    import mote
    dump = mote.read_phantom("runs/sph_dustybox/snapshot_00001.phantom")
    dump.header["time"], dump.header["massoftype"], dump.header["udist"]
    dump.arrays["x"], dump.arrays["h"], dump.arrays["itype"], dump.arrays["dustfrac"]

The format is described in "The phantom native binary format"
(docs/dumpfile.rst of github:danieljprice/phantom): Fortran unformatted
records (a 4-byte length before and after the bytes) holding the magic
numbers, a 100-character file identifier, a header of 16-character tags and
values for each of 8 types (default int, int*1, int*2, int*4, int*8, default
real, real*4, real*8), then blocks of arrays of those types. Reads
little-endian files with either size of default int and real.

A tag repeated within one header type is one entry, an array of its values
(npartoftype, massoftype); a tag that appears again under a later type
(Phantom writes nparttot as default int and as int*8) keeps its first
values. A tag repeated among the particle arrays (one "dustfrac" per dust
species) is one array of shape (n, repeats). The per-species values keep
their species axis with one species too: "dustfrac" (and Phantom's tstop,
deltavx/y/z) is (n, N), "grainsize" and "graindens" arrays of N values. Array block 1 of each MPI
block holds the particles (concatenated over the MPI blocks), block 2 the
sink particles (`sinks`); other blocks are not read.
"""
import struct
from dataclasses import dataclass, field

import numpy as np

MAGIC_I1, MAGIC_I2, MAGIC_I3 = 60769, 60878, 690706
TAG_LENGTH = 16
PER_SPECIES_ARRAYS = {"dustfrac", "tstop", "deltavx", "deltavy", "deltavz"}
PER_SPECIES_HEADER = {"grainsize", "graindens"}
# the 8 types after the two default ones are resolved: dtype per type index
FIXED_TYPES = {1: "<i1", 2: "<i2", 3: "<i4", 4: "<i8", 6: "<f4", 7: "<f8"}


@dataclass
class PhantomDump:
    file_id: str
    header: dict = field(default_factory=dict)
    arrays: dict = field(default_factory=dict)
    sinks: dict = field(default_factory=dict)
    default_int: str = "<i4"
    default_real: str = "<f8"


class _Records:
    """Fortran unformatted records of a little-endian file."""

    def __init__(self, data):
        self.data, self.pos = data, 0

    def next(self):
        if self.pos + 4 > len(self.data):
            raise ValueError("Phantom dump: file ends before a record")
        (length,) = struct.unpack_from("<i", self.data, self.pos)
        end = self.pos + 4 + length
        if length < 0 or end + 4 > len(self.data) or struct.unpack_from("<i", self.data, end)[0] != length:
            raise ValueError(f"Phantom dump: corrupt record at byte {self.pos}")
        record = self.data[self.pos + 4:end]
        self.pos = end + 4
        return record


def _default_kinds(record):
    """(default int dtype, default real dtype) from the magic-number record."""
    for int_dtype, real_dtype in (("<i4", "<f8"), ("<i4", "<f4"), ("<i8", "<f8"), ("<i8", "<f4")):
        isize, rsize = np.dtype(int_dtype).itemsize, np.dtype(real_dtype).itemsize
        if len(record) != 4 * isize + rsize:
            continue
        i1 = np.frombuffer(record, int_dtype, 1, 0)[0]
        r1 = np.frombuffer(record, real_dtype, 1, isize)[0]
        i2, _version, i3 = np.frombuffer(record, int_dtype, 3, isize + rsize)
        if (i1, i2, i3) == (MAGIC_I1, MAGIC_I2, MAGIC_I3) and r1 == MAGIC_I2:
            return int_dtype, real_dtype
    raise ValueError("Phantom dump: the first record holds no Phantom magic numbers (not a little-endian Phantom dump)")


def _tags(record):
    text = record.decode("ascii")
    return [text[k:k + TAG_LENGTH].strip() for k in range(0, len(text), TAG_LENGTH)]


def _read_header(records, dtypes):
    header = {}
    for dtype in dtypes:
        (count,) = np.frombuffer(records.next(), "<i4", 1)
        if count == 0:
            continue
        tags = _tags(records.next())
        values = np.frombuffer(records.next(), dtype, count)
        block = {}
        for tag, value in zip(tags, values):
            block.setdefault(tag, []).append(value)
        for tag, vals in block.items():
            header.setdefault(tag, vals[0] if len(vals) == 1 and tag not in PER_SPECIES_HEADER else np.array(vals))
    return header


def _read_block(records, length, counts, dtypes):
    """{tag: array} of one array block; a repeated tag gives an (n, repeats) array."""
    columns = {}
    for dtype, count in zip(dtypes, counts):
        for _ in range(count):
            (tag,) = _tags(records.next())
            columns.setdefault(tag, []).append(np.frombuffer(records.next(), dtype, length))
    return {tag: c[0] if len(c) == 1 and tag not in PER_SPECIES_ARRAYS else np.stack(c, axis=1)
            for tag, c in columns.items()}


def _join(parts):
    if not parts:
        return {}
    return {tag: np.concatenate([p[tag] for p in parts]) for tag in parts[0]}


def read_phantom(path):
    """The PhantomDump of the file at `path`."""
    with open(path, "rb") as f:
        records = _Records(f.read())
    default_int, default_real = _default_kinds(records.next())
    dtypes = [default_int, *[FIXED_TYPES[k] for k in (1, 2, 3, 4)], default_real, FIXED_TYPES[6], FIXED_TYPES[7]]
    dump = PhantomDump(records.next().decode("ascii").rstrip(), default_int=default_int, default_real=default_real)
    dump.header = _read_header(records, dtypes)
    mpi_blocks = int(dump.header.get("nblocks", 1))
    (total,) = np.frombuffer(records.next(), "<i4", 1)
    per_mpi_block = int(total) // mpi_blocks
    particles, sinks = [], []
    for _ in range(mpi_blocks):
        heads = []
        for _ in range(per_mpi_block):
            record = records.next()
            heads.append((int(np.frombuffer(record, "<i8", 1)[0]), np.frombuffer(record, "<i4", 8, 8)))
        blocks = [_read_block(records, length, counts, dtypes) for length, counts in heads]
        particles.append(blocks[0])
        if len(blocks) > 1 and heads[1][0] > 0:
            sinks.append(blocks[1])
    dump.arrays, dump.sinks = _join(particles), _join(sinks)
    return dump

"""What vibromap's writers give every HDF5 file last, for the files the tests write with h5py:
the root attribute `version` (the format version of the file's kind, vibromap_h5io's
FORMAT_VERSIONS) and then the attribute checksum over every attribute (vibromap_seal.py, the
readers' own code): stamp(). A file changed after it is stamped is damaged until stamped again,
but for its version: set_version() makes a file of another format version (used by the
campaign tests and the fuzzer too).
"""

from __future__ import annotations

import zlib

import h5py
import numpy as np

from vibromap._io import h5io as vibromap_h5io
from vibromap._io import seal as vibromap_seal


def stamp(path, kind: str, uncovered=(), version: int | None = None) -> None:
    """Writes `version` (default: the one this vibromap reads for `kind`) and the seal into the
    file at `path`; root attributes in `uncovered` stay out of the seal, as a map's cells_done,
    complete and ranks do."""
    with h5py.File(path, "r+") as f:
        f.attrs[vibromap_h5io.VERSION_ATTRIBUTE] = np.int64(vibromap_h5io.FORMAT_VERSIONS[kind] if version is None
                                                            else version)  # fmt: skip
        crc = zlib.crc32(vibromap_seal.attribute_record(f, uncovered)) & 0xFFFFFFFF
        text = f"crc32 {crc:08x}" + (f"; not covered: {' '.join(uncovered)}" if uncovered else "")
        f.attrs[vibromap_seal.SEAL_ATTRIBUTE] = text


def set_version(path, version: int | None) -> None:
    """The file's root attribute `version` changed in place to `version` (None: removed, as in a
    file made before files were versioned), the seal left as it was: a file of another format
    version, as a reader meets it (the version is checked before the seal)."""
    with h5py.File(path, "r+") as f:
        if version is None:
            del f.attrs[vibromap_h5io.VERSION_ATTRIBUTE]
        else:
            f.attrs.modify(vibromap_h5io.VERSION_ATTRIBUTE, np.int64(version))

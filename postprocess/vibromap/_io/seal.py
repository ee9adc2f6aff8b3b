"""The attribute checksum ("seal") of vibromap's HDF5 files, checked as vibromap checks it.

Chunks carry HDF5's Fletcher32 checksum, attributes do not: a variable-length string attribute
(scene, identity, title, units) lives in HDF5's global heap, which has no checksum. So vibromap
writes the root attribute `attribute_checksum` = "crc32 XXXXXXXX" (8 lowercase hex digits,
zlib's CRC-32), optionally followed by "; not covered: NAME ..." (root attributes a writer
updates in place and no reader trusts: a map's cells_done, complete and ranks), over the
canonical record of the file's metadata that src/io/attribute_seal.cpp builds and documents.
attribute_record() builds the same bytes with h5py's low-level API (raw bytes of every string,
never a decoded str), so a file vibromap wrote checks here exactly as in `vibromap sweep --resume`.

check_heaps(f) refuses a file whose global heaps HDF5 would read for ever (before any attribute is
read); check_seal(f) refuses one whose seal is missing or does not match its attributes: both
raise DamagedAttributes with a one-line reason.
"""

from __future__ import annotations

import re
import zlib

import h5py
import numpy as np

SEAL_ATTRIBUTE = "attribute_checksum"
_SEAL_NAME = SEAL_ATTRIBUTE.encode()
_SEAL_TEXT = re.compile(rb"crc32 ([0-9a-f]{8})(?:; not covered: ([a-z_]+(?: [a-z_]+)*))?")
_SKIPPED = (b"DIMENSION_LIST", b"REFERENCE_LIST")  # object references: the layout's scales stand for them


class DamagedAttributes(Exception):
    """The file's attributes fail their checksum, or cannot be read: the message says which."""


def _field(data: bytes) -> bytes:
    return str(len(data)).encode() + b":" + data


def _record(path: bytes, name: bytes, kind: bytes, value: bytes) -> bytes:
    return _field(path) + _field(name) + kind + _field(value)


def _attribute_names(oid) -> list[bytes]:
    names: list[bytes] = []
    h5py.h5a.iterate(oid, lambda name: names.append(name))  # None: go on
    return sorted(names)


def _attribute_value(oid, name: bytes) -> tuple[bytes, bytes]:
    """(kind, value) of one attribute as src/io/attribute_seal.cpp writes them in the record."""
    aid = h5py.h5a.open(oid, name)
    tid = aid.get_type()
    cls = tid.get_class()
    count = aid.get_space().get_simple_extent_npoints()
    if cls == h5py.h5t.STRING and count == 1:
        if tid.is_variable_str():
            array = np.empty(aid.shape, dtype=h5py.string_dtype("ascii"))
            aid.read(array)
        else:  # the raw bytes, trailing NULs dropped (numpy's bytes_ drops them)
            array = np.empty(aid.shape, dtype=f"S{tid.get_size()}")
            aid.read(array, mtype=tid)
        value = array.reshape(-1)[0]
        return b"s", bytes(value) if value is not None else b""
    if cls in (h5py.h5t.INTEGER, h5py.h5t.FLOAT):
        integer = cls == h5py.h5t.INTEGER
        array = np.empty(aid.shape if count else (0,), dtype="<i8" if integer else "<f8")
        if count:
            aid.read(array)
        if integer:
            return b"i", ",".join(str(int(v)) for v in array.reshape(-1)).encode()
        return b"f", ",".join(f"{int(v):016x}" for v in array.reshape(-1).view("<u8")).encode()
    return b"x", str(int(cls)).encode()


def _layout_text(dsid) -> bytes:
    """b"<f8 3x4 /E1;/E2": element type as numpy spells it, shape, attached dimension scales."""
    tid = dsid.get_type()
    cls = tid.get_class()
    if cls in (h5py.h5t.INTEGER, h5py.h5t.FLOAT):
        size = tid.get_size()
        order = "|" if size == 1 else (">" if tid.get_order() == h5py.h5t.ORDER_BE else "<")
        kind = "f" if cls == h5py.h5t.FLOAT else ("u" if tid.get_sign() == h5py.h5t.SGN_NONE else "i")
        dtype = f"{order}{kind}{size}".encode()
    else:
        dtype = b"other"
    shape = dsid.shape or ()
    dims = b"x".join(str(n).encode() for n in shape) or b"scalar"
    scales = []
    for dim in range(len(shape)):
        names: list[bytes] = []
        if h5py.h5ds.get_num_scales(dsid, dim) > 0:
            h5py.h5ds.iterate(dsid, dim, lambda scale: names.append(h5py.h5i.get_name(scale)))
        scales.append(b",".join(names))
    return dtype + b" " + dims + b" " + b";".join(scales)


def _attributes(oid, path: bytes, skipped=()) -> bytes:
    out = []
    for name in _attribute_names(oid):
        if name in _SKIPPED or name in skipped:
            continue
        kind, value = _attribute_value(oid, name)
        out.append(_record(path, name, kind, value))
    return b"".join(out)


def _group(gid, path: bytes, skipped=()) -> bytes:
    names: list[bytes] = []
    gid.links.iterate(lambda name: names.append(name))
    out = []
    for name in sorted(names):
        if name in skipped:
            continue
        child = (b"" if path == b"/" else path) + b"/" + name
        kind = None
        if gid.links.get_info(name).type == h5py.h5l.TYPE_HARD:
            oid = h5py.h5o.open(gid, name)
            kind = h5py.h5i.get_type(oid)
        if kind == h5py.h5i.DATASET:
            out.append(_record(child, b"", b"l", _layout_text(oid)))
            out.append(_attributes(oid, child))
        elif kind == h5py.h5i.GROUP:
            out.append(_attributes(oid, child))
            out.append(_group(oid, child))
        else:
            out.append(_record(child, b"", b"x", b"link"))
    return b"".join(out)


def attribute_record(f: h5py.File, uncovered=()) -> bytes:
    """The canonical record of the file's metadata (src/io/attribute_seal.hpp), without the
    seal itself and the root attributes named in `uncovered` (and root groups of those names: a
    census map's /families)."""
    names = {name.encode() if isinstance(name, str) else name for name in uncovered}
    skipped = {_SEAL_NAME} | names
    return _attributes(f.id, b"/", skipped) + _group(f.id, b"/", names)


def _printable(data: bytes) -> str:
    text = "".join(chr(c) if 0x20 <= c < 0x7F else f"\\x{c:02x}" for c in data[:60])
    return text + ("..." if len(data) > 60 else "")


_HEAP_SIGNATURE = b"GCOL\x01\x00\x00\x00"
_SCAN_WHOLE = 1 << 30   # files up to this are scanned whole, larger ones at both ends (their heaps)
_SCAN_ENDS = 256 << 20


def _stuck_object(f, at: int, file_size: int) -> int:
    """Where HDF5's walk of the global heap collection at `at` would stop advancing, or -1.
    The same walk as src/io/attribute_seal.cpp (endless_global_heap)."""
    f.seek(at)
    head = f.read(16)
    size = min(int.from_bytes(head[8:16], "little"), file_size - at)
    f.seek(at)
    heap = f.read(size)
    p = 16
    while p + 16 <= len(heap):
        index = int.from_bytes(heap[p:p + 2], "little")
        obj = int.from_bytes(heap[p + 8:p + 16], "little")
        need = 16 + (obj + 7) // 8 * 8 if index > 0 else obj
        if need == 0:
            return at + p
        if need > len(heap) - p:
            break
        p += need
    return -1


def endless_global_heap(path) -> str:
    """Empty, or why the HDF5 library would loop for ever reading the file's string attributes:
    a global heap collection whose free-space object has size 0 (one flipped bit can do it).
    Read 4 MiB at a time."""
    block = 4 << 20
    with open(path, "rb") as f:
        f.seek(0, 2)
        size = f.tell()
        spans = [(0, size)] if size <= _SCAN_WHOLE else [(0, _SCAN_ENDS), (size - _SCAN_ENDS, size)]
        for start, end in spans:
            for at in range(start, end, block):
                f.seek(at)
                data = f.read(min(block + len(_HEAP_SIGNATURE) - 1, end - at))
                found = data.find(_HEAP_SIGNATURE)
                while found >= 0:
                    stuck = _stuck_object(f, at + found, size)
                    if stuck >= 0:
                        return (f"a global heap (HDF5's store of string attributes) has a free-space object of "
                                f"size 0 at byte {stuck}, which the HDF5 library would read for ever")
                    found = data.find(_HEAP_SIGNATURE, found + 1)
    return ""


def check_heaps(f: h5py.File) -> None:
    """DamagedAttributes when the HDF5 library would loop for ever reading the file's string
    attributes (endless_global_heap); a file that cannot be read here is left to h5py."""
    try:
        why = endless_global_heap(f.filename)
    except OSError:
        why = ""
    if why:
        raise DamagedAttributes(why)


def check_seal(f: h5py.File) -> None:
    """DamagedAttributes with a one-line reason when the file has no seal, when its attributes do
    not match it, or when they cannot be read."""
    try:
        if _SEAL_NAME not in _attribute_names(f.id):
            raise DamagedAttributes(f"it has no attribute '{SEAL_ATTRIBUTE}'")
        kind, value = _attribute_value(f.id, _SEAL_NAME)
        match = _SEAL_TEXT.fullmatch(value) if kind == b"s" else None
        if match is None:
            raise DamagedAttributes(f"its attribute '{SEAL_ATTRIBUTE}' is not 'crc32 XXXXXXXX' ('{_printable(value)}')")
        uncovered = match.group(2).split() if match.group(2) else []
        computed = f"{zlib.crc32(attribute_record(f, uncovered)) & 0xFFFFFFFF:08x}"
        stored = match.group(1).decode()
        if computed != stored:
            raise DamagedAttributes(f"its attributes fail their checksum ({SEAL_ATTRIBUTE} says crc32 {stored}, "
                                    f"the attributes give {computed})")
    except DamagedAttributes:
        raise
    except Exception as exc:  # h5py/HDF5 could not read them (KeyError, OSError, ValueError, ...)
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise DamagedAttributes(f"its attributes cannot be read ({reason})") from exc

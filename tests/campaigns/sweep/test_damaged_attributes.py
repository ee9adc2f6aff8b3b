"""Damage in a map's attributes is damage (issue 28): `vibromap sweep --resume` of a finished map
with one byte flipped inside an attribute's value (found by searching the file for the value's
text) exits 4 with one line "FILE: damaged: its attributes fail their checksum (...)", before
any identity is compared: never exit 0 with nothing computed, never "made by another run" naming
a garbled key. Random bytes flipped outside the chunks' storage (object headers, heaps, B-trees:
where a chunk's Fletcher32 checksum does not reach), at fixed seeds, either leave a map that
resumes to the undamaged one or are refused in one line. And a chunk that a damaged chunk index
no longer finds (HDF5 then reads fill values without an error) is a damaged chunk: the reader
refuses the map, --resume computes its cells again.

Run by ctest (tests/campaigns/campaign_tests.cmake)."""
import os
import random
import shutil
import struct
import subprocess
import sys

import h5py
import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postprocess"))
from campaign_helpers import ENV, EXE, reference_map  # noqa: E402
from vibromap import _io as vibromap_h5  # noqa: E402

# Cheap cells (no forcing: no contact), 4 x 3.
SCENE = """
[forcing]
F0 = 0.0

[sweep]
E1 = { from = 2e4, to = 2.1e11, n = 4, scale = "log" }
E2 = { from = 2e4, to = 2.1e11, n = 3, scale = "log" }
store = ["T_con", "k_con"]
"""
PROGRESS = ("cells_done", "complete", "ranks")  # rewritten by every run's end: not compared


def resume(scene, path):
    return subprocess.run([EXE, "sweep", str(scene), "-o", str(path), "-q", "--resume"], env=ENV,
                          capture_output=True, text=True, timeout=300)


def content(path):
    """Every attribute but the progress ones, every dataset's type and values but wall_s."""
    out = {}

    def visit(name, obj):
        for key in obj.attrs:
            if key not in PROGRESS + ("DIMENSION_LIST", "REFERENCE_LIST"):
                out[(name, key)] = repr(obj.attrs[key])
        if isinstance(obj, h5py.Dataset):
            out[(name, "dtype")] = str(obj.dtype)
            if name != "wall_s":
                out[(name, "values")] = np.asarray(obj[()]).tobytes()

    with h5py.File(path, "r") as f:
        visit("/", f)
        f.visititems(visit)
    return out


def chunk_bytes(path):
    """A mask of the file's bytes that hold dataset storage (covered by Fletcher32)."""
    mask = np.zeros(os.path.getsize(path), dtype=bool)
    with h5py.File(path, "r") as f:
        for item in f.values():
            for i in range(item.id.get_num_chunks() if item.chunks else 0):
                info = item.id.get_chunk_info(i)
                mask[info.byte_offset:info.byte_offset + info.size] = True
    return mask


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    return reference_map(tmp_path_factory.mktemp("attributes"), SCENE)


def assert_damage_refused(proc, path, reason, before):
    """Refused in one line, and the file left byte for byte as it was (issue 43: the resume once
    opened it for writing before checking it, and HDF5 rewrote its superblock on closing)."""
    context = f"exit {proc.returncode}\nstdout: {proc.stdout}\nstderr: {proc.stderr}"
    assert path.read_bytes() == before, "the refused map was changed\n" + context
    assert proc.returncode == 4, context
    assert proc.stdout == "", context
    assert proc.stderr.count("\n") == 1 and proc.stderr.startswith(f"vibromap: error: {path}: damaged: {reason}"), context
    assert "made by another run" not in proc.stderr, context


@pytest.mark.parametrize("needle", [b"vibromap regime map", b"CF-1.8", b"F0 = 0.0", b"system.m2 = ",
                                    b"Young's modulus of body 2", b"not_computed periodic chatter", b"log\0"])
def test_a_flipped_byte_inside_an_attribute_is_refused_as_damage(reference, tmp_path, needle):
    """The title, Conventions, the scene text, the identity (once "made by another run" naming a
    garbled key), an axis's long_name, regime's flag_meanings, an axis's scale."""
    scene, ref = reference
    damaged = tmp_path / "damaged.h5"
    data = bytearray(ref.read_bytes())
    where = data.find(needle)
    assert where >= 0, needle
    data[where + 1] ^= 0x01
    # And a byte of the superblock's root entry that nothing reads (its scratch pad, unused with
    # cache type 0), which HDF5 writes back as 0 on closing a file opened for writing (fuzz seed
    # 662607, damage case 182): the refusal must leave it flipped.
    assert data[:9] == b"\x89HDF\r\n\x1a\n\x00" and data[72:76] == bytes(4)  # superblock version 0, no cache
    data[81] ^= 0x01
    damaged.write_bytes(bytes(data))
    assert_damage_refused(resume(scene, damaged), damaged, "its attributes fail their checksum (attribute_checksum says crc32 ",
                          bytes(data))
    assert damaged.exists()  # refused, not removed


def size_before(data, text):
    """Offset of the size field of the global heap object stored just before the one holding
    `text` (a collection: "GCOL", version, 3 reserved bytes, its size (8); then per object its
    index (2), reference count (2), 4 reserved bytes, size (8) and data padded to 8 bytes)."""
    target = data.find(text) - 16
    at, previous = data.rfind(b"GCOL", 0, target) + 16, None
    while at < target:
        previous, at = at, at + 16 + (struct.unpack_from("<Q", data, at + 8)[0] + 7) // 8 * 8
    assert at == target and previous is not None
    return previous + 8


def test_the_map_of_issue_28_is_refused_as_damage(reference, tmp_path):
    """Issue 28's byte (offset 4470 of its map): the size of the global heap object before the
    title's, after which title, Conventions and vibromap_version read back empty, and the map was
    resumed with exit 0 and nothing computed."""
    scene, ref = reference
    damaged = tmp_path / "damaged.h5"
    data = bytearray(ref.read_bytes())
    data[size_before(data, b"vibromap regime map")] ^= 0xFF
    damaged.write_bytes(bytes(data))
    with h5py.File(damaged, "r") as f:  # what the damage does, unseen by HDF5 and h5py
        assert (f.attrs["title"], f.attrs["Conventions"], f.attrs["vibromap_version"]) == ("", "", "")
    assert_damage_refused(resume(scene, damaged), damaged, "its attribute", bytes(data))


def test_a_heap_that_hdf5_would_read_for_ever_is_refused_as_damage(reference, tmp_path):
    """The long fuzz run's hang: a flipped bit in a heap object's size sent the walk of the
    collection onto a free-space object (index 0) of size 0, which HDF5 1.10 reads for ever (the
    resume ignored every signal). Made here directly: the first object's header becomes that."""
    scene, ref = reference
    damaged = tmp_path / "damaged.h5"
    data = bytearray(ref.read_bytes())
    first = data.find(b"GCOL\x01\x00\x00\x00") + 16
    struct.pack_into("<HHIQ", data, first, 0, 0, 0, 0)
    damaged.write_bytes(bytes(data))
    assert_damage_refused(resume(scene, damaged), damaged,
                          f"a global heap (HDF5's store of string attributes) has a free-space object of size 0 at byte {first}",
                          bytes(data))
    with pytest.raises(vibromap_h5.VibromapFileError,
                       match="free-space object of size 0"):
        vibromap_h5.read_map(str(damaged))


@pytest.mark.parametrize("seed", range(1, 9))
def test_metadata_flips_are_refused_or_harmless(reference, tmp_path, seed):
    scene, ref = reference
    outside = np.flatnonzero(~chunk_bytes(ref))
    want = content(ref)
    rng = random.Random(seed)
    outcomes = []
    for trial in range(5):
        damaged = tmp_path / f"damaged{trial}.h5"
        shutil.copy(ref, damaged)
        offset = int(outside[rng.randrange(outside.size)])
        data = bytearray(damaged.read_bytes())
        data[offset] ^= rng.randint(1, 255)
        damaged.write_bytes(bytes(data))
        proc = resume(scene, damaged)
        context = f"seed {seed}, byte {offset}: exit {proc.returncode}\n{proc.stderr}"
        assert proc.returncode in (0, 2, 4), context
        assert "made by another run" not in proc.stderr, context
        if proc.returncode == 0:
            assert content(damaged) == want, context  # an unused byte: the map is the reference's
            outcomes.append("resumed")
        else:
            assert proc.stderr.count("\n") == 1 and proc.stderr.startswith("vibromap: error: "), context
            assert damaged.read_bytes() == bytes(data), "the refused map was changed\n" + context
            outcomes.append("refused")
    print(f"seed {seed}: {outcomes}")


@pytest.mark.parametrize("key", [0, 2], ids=["first offset", "element offset"])
def test_a_chunk_missing_from_its_index_is_a_damaged_chunk(reference, tmp_path, key):
    """The chunk's key in the index damaged: its offset in the first dimension, or the trailing 0
    of the element dimension (which HDF5's lookup by coordinate ignores, but a read does not)."""
    scene, ref = reference
    damaged = tmp_path / "damaged.h5"
    shutil.copy(ref, damaged)
    with h5py.File(damaged, "r") as f:
        address, ndim = f["k_con"].id.get_chunk_info(0).byte_offset, f["k_con"].ndim
        assert np.isfinite(f["k_con"][()]).all()
    data = bytearray(damaged.read_bytes())
    # In the chunk index (a version 1 B-tree node), the chunk's key comes just before its address:
    # size (4 bytes), filter mask (4), then its offset in each dimension and a 0 (8 bytes each).
    child = data.find(struct.pack("<Q", address))
    assert child > 0 and data.find(struct.pack("<Q", address), child + 1) < 0
    data[child - 8 * (ndim + 1) + 8 * key + 1] ^= 0x01  # that offset + 256: no chunk where the cells are
    damaged.write_bytes(bytes(data))
    with h5py.File(damaged, "r") as f:
        assert np.isnan(f["k_con"][()]).all()  # read alone: fill values, and no error
    with pytest.raises(vibromap_h5.VibromapFileError, match=r"dataset 'k_con' is damaged: its chunk at \(0, 0\) is missing"):
        vibromap_h5.read_map(str(damaged))
    proc = resume(scene, damaged)
    assert proc.returncode == 0, proc.stderr
    assert ("1 damaged chunk (a failed checksum or a chunk missing from its index, in k_con) wiped; their 12 cells "
            "are computed again") in proc.stderr
    assert content(damaged) == content(ref)

"""Damaged and truncated files, and files of another format version: the postprocess scripts say
so in one line on stderr and exit 2, never with a traceback and never by printing what the damage
made up or reading an older layout.

The maps are the C++ writer's sample (VIBROMAP_SAMPLE_MAP, set by ctest; its attribute checksum
made by src/io/attribute_seal.cpp) and a map written here by make_map.py and sealed by the
reader's own code (so these tests also run without ctest). Damage is (a) one byte flipped inside
an attribute's value, found by searching the file for the value's text (the title, the scene,
an axis's units and long_name, the regime's flag_meanings), as in the map of issue 28 whose
title, Conventions and vibromap_version read back empty, (b) the file cut short, (c) random bytes
flipped anywhere, at fixed seeds: each run of summarize_map then either prints exactly what it
prints for the undamaged map (the byte was unused) or refuses the map in one line; (d) the seal
removed. A map whose root attribute `version` is another (or absent: version 0) is refused with
the line vibromap prints for it, naming the file and both versions."""
import contextlib
import io
import os
import random
import subprocess
import sys

import h5py
import numpy as np
import pytest

import make_map
from stamp import set_version
from vibromap import _summarize_map as summarize_map
from vibromap import _io as vibromap_h5

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.dirname(HERE)
AXES = [("E1", np.array([1e5, 1e7, 1e9]), "log"), ("R1", np.array([0.1, 1.0]), "lin")]
SCENE = '[sweep]\naxes = ["E1", "R1"]\nnote = "UTF-8: \u03bb"\n'  # the C++ sample's (test_map_file.cpp)


def python_map(path):
    regime = np.array([[0, 0], [0, 2], [2, 2]], dtype=np.int8)
    n = np.where(regime == 0, 1, 0)
    make_map.write_map(path, AXES, regime, n, n, stable=np.ones((3, 2), np.int8), scene=SCENE,
                       quantities={"k_con": np.full((3, 2), 5.0)})


@pytest.fixture(params=["cpp", "python"])
def sealed_map(request, tmp_path):
    """A sealed map: the C++ writer's sample (skipped without ctest) or one made here."""
    path = tmp_path / "map.h5"
    if request.param == "cpp":
        sample = os.environ.get("VIBROMAP_SAMPLE_MAP")
        if not sample:
            pytest.skip("no map file from the C++ writer (VIBROMAP_SAMPLE_MAP is set by ctest)")
        path.write_bytes(open(sample, "rb").read())
    else:
        python_map(str(path))
    return path


def run(script, *args):
    return subprocess.run([sys.executable, "-m", "vibromap", script, *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def summarize(path):
    """summarize_map's main() in this process (its exit status, stdout, stderr): an exception
    escaping it, which the script would print as a traceback, fails the test."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = summarize_map.main([str(path)])
    return subprocess.CompletedProcess([], code, out.getvalue(), err.getvalue())


def assert_refused(proc, prog, path, reason=""):
    """Exit 2, nothing on stdout, one line "<prog>: error: <path>: ..." on stderr, no traceback."""
    context = f"exit {proc.returncode}\nstdout: {proc.stdout}\nstderr: {proc.stderr}"
    assert proc.returncode == 2, context
    assert "Traceback" not in proc.stderr, context
    assert proc.stdout == "", context
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{prog}: error: {path}: "), context
    assert reason in lines[0], context


def flip_inside(path, needle: bytes, at=2):
    data = bytearray(path.read_bytes())
    where = data.find(needle)
    assert where >= 0 and data.find(needle, where + 1) < 0, f"{needle!r} not in the file exactly once"
    data[where + at] ^= 0x01
    path.write_bytes(bytes(data))


def test_a_sealed_map_reads_as_verified(sealed_map):
    proc = run("summarize_map", sealed_map)
    assert proc.returncode == 0, proc.stderr
    assert "attributes: verified by their checksum" in proc.stdout


def test_a_map_without_its_seal_is_refused_as_damaged(sealed_map):
    with h5py.File(sealed_map, "r+") as f:
        del f.attrs["attribute_checksum"]
    assert_refused(summarize(sealed_map), "summarize_map", sealed_map,
                   "damaged: it has no attribute 'attribute_checksum'; make it again with vibromap --overwrite")


@pytest.mark.parametrize("version", [0, vibromap_h5.FORMAT_VERSIONS["regime map"] + 1, None])
def test_a_map_of_another_format_version_is_refused_naming_both_versions(sealed_map, version):
    """The version changed (None: removed, version 0) without sealing again: it is checked first,
    so it is named, not reported as damage; the scripts as programs exit 2 with that one line."""
    set_version(sealed_map, version)
    line = (f"{sealed_map}: a regime map of format version {version or 0}; this vibromap reads version "
            f"{vibromap_h5.FORMAT_VERSIONS['regime map']} only: "
            "make the file again with this vibromap")
    with pytest.raises(vibromap_h5.FileVersionError) as error:
        vibromap_h5.read_map(str(sealed_map))
    assert str(error.value) == line
    for script in ("summarize_map", "plot_regime_map", "plot_kcon_map", "plot_soft_map"):
        proc = run(script, sealed_map)
        assert_refused(proc, script, sealed_map)
        assert proc.stderr == f"{script}: error: {line}\n"


@pytest.mark.parametrize("needle", [b"vibromap regime map", b"CF-1.8", b'note = "UTF-8: \xce\xbb"', b"Young's modulus",
                                    b"not_computed periodic chatter"])
def test_a_flipped_attribute_byte_is_refused_in_one_line(sealed_map, needle):
    flip_inside(sealed_map, needle)
    assert_refused(summarize(sealed_map), "summarize_map", sealed_map,
                   "damaged: its attributes fail their checksum (attribute_checksum says crc32 ")


def test_the_scripts_refuse_a_damaged_map_in_one_line_as_programs(sealed_map):
    """As the user runs them: a new interpreter, its stderr and exit status."""
    flip_inside(sealed_map, b"vibromap regime map")
    assert_refused(run("summarize_map", sealed_map), "summarize_map", sealed_map,
                   "damaged: its attributes fail their checksum (attribute_checksum says crc32 ")
    out = sealed_map.parent / "regime.png"
    assert_refused(run("plot_regime_map", sealed_map, "-o", out), "plot_regime_map", sealed_map, "damaged: ")
    assert not out.exists()


def test_the_map_of_issue_28_title_conventions_and_version_emptied_is_refused(sealed_map):
    """Issue 28's byte: the size of a global heap object, which empties the strings after it."""
    data = bytearray(sealed_map.read_bytes())
    heap = data.find(b"GCOL")
    assert heap >= 0
    # The first object of the collection: index (2 bytes), refcount (2), reserved (4), size (8).
    data[heap + 16 + 8] ^= 0x10
    sealed_map.write_bytes(bytes(data))
    assert_refused(summarize(sealed_map), "summarize_map", sealed_map, "damaged: ")


@pytest.mark.parametrize("fraction", [0.0, 0.01, 0.25, 0.5, 0.9, 0.999])
def test_a_truncated_map_is_refused_in_one_line(sealed_map, fraction):
    data = sealed_map.read_bytes()
    sealed_map.write_bytes(data[: int(len(data) * fraction)])
    assert_refused(summarize(sealed_map), "summarize_map", sealed_map)


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5, 6, 7, 8])
def test_random_flips_are_refused_or_harmless(sealed_map, seed):
    reference = summarize(sealed_map)
    assert reference.returncode == 0, reference.stderr
    data = bytearray(sealed_map.read_bytes())
    rng = random.Random(seed)
    offsets = [rng.randrange(len(data)) for _ in range(rng.choice([1, 2, 3]))]
    for offset in offsets:
        data[offset] ^= rng.randint(1, 255)
    sealed_map.write_bytes(bytes(data))
    proc = summarize(sealed_map)
    if proc.returncode == 0:
        assert proc.stdout == reference.stdout, f"offsets {offsets}: accepted with another summary"
        assert proc.stderr == ""
    else:
        assert_refused(proc, "summarize_map", sealed_map)

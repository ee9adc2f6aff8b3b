"""vibromap reads only the format version it writes (include/vibromap/io/file_format.hpp): a file
of another version that a command reads is refused with exit 2 and one line naming the file and
both versions, before anything is computed or written, and is left as it was:

- `sweep --resume` of a map, `basins --resume` of a basins file, whose root attribute `version`
  is 0 (or absent: version 0, a file made before files were versioned) or 2 (a newer vibromap's);
- `optimise` seeding from a map of another version ([optimise] map);
- `optimise --resume` with a journal of another version in its header.

The version is changed in place, without sealing the file again: it is checked before the
attribute checksum, so it is named, not reported as damage. Run by ctest
(tests/campaigns/campaign_tests.cmake)."""
import os
import struct
import subprocess
import sys
import zlib

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postprocess"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postprocess", "tests"))
from campaign_helpers import ENV, EXE, TABLE2_POINT  # noqa: E402
from stamp import set_version  # noqa: E402
from vibromap._io.h5io import FORMAT_VERSIONS  # noqa: E402

MAP = FORMAT_VERSIONS["regime map"]  # the versions this vibromap reads
BASINS_VERSION = FORMAT_VERSIONS["basins file"]

# The bistable Table 2 point, its [sweep] two cells of E2 (a few seconds).
SWEEP = TABLE2_POINT + """
[sweep]
E2 = { from = 8e5, to = 1.2e6, n = 2, scale = "log" }
store = ["k_con", "T_con"]
"""
FREE_E2 = """
[optimise]
E2 = { min = 7e5, max = 1.3e6, scale = "log" }
seeds = 1
max_evaluations = 2
best = 1
regime = "any"
"""
BASINS = ["basins", "jobs/paper/table2.toml", "--grid", "3x2", "--set", "census.max_attractors=4", "-q"]


def vibromap(*args):
    return subprocess.run([EXE, *map(str, args)], env=ENV, capture_output=True, text=True, timeout=600)


def refusal(path, kind, found, reads):
    article = "an" if kind[0] in "aeiou" else "a"
    return (f"vibromap: error: {path}: {article} {kind} of format version {found}; this vibromap reads version {reads} "
            "only: make the file again with this vibromap\n")


def assert_refused(proc, line):
    context = f"exit {proc.returncode}\nstdout: {proc.stdout}\nstderr: {proc.stderr}"
    assert (proc.returncode, proc.stdout, proc.stderr) == (2, "", line), context


@pytest.fixture(scope="module")
def sweep_map(tmp_path_factory):
    """(scene, map) of SWEEP, made once; each test copies the map."""
    folder = tmp_path_factory.mktemp("versions")
    scene = folder / "sweep.toml"
    scene.write_text(SWEEP)
    path = folder / "map.h5"
    proc = vibromap("sweep", scene, "-q", "-o", path)
    assert proc.returncode == 0, proc.stderr
    return scene, path


@pytest.mark.parametrize("version", [0, MAP - 1, MAP + 1, None])
def test_sweep_resume_refuses_a_map_of_another_format_version(sweep_map, tmp_path, version):
    scene, reference = sweep_map
    path = tmp_path / "map.h5"
    path.write_bytes(reference.read_bytes())
    set_version(path, version)
    before = path.read_bytes()
    assert_refused(vibromap("sweep", scene, "-q", "--resume", "-o", path), refusal(path, "regime map", version or 0, MAP))
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.h5"]  # no lock, nothing beside it


def test_optimise_refuses_a_seeding_map_of_another_format_version(sweep_map, tmp_path):
    _, reference = sweep_map
    seeds = tmp_path / "seeds.h5"
    seeds.write_bytes(reference.read_bytes())
    set_version(seeds, MAP + 1)
    scene = tmp_path / "optimise.toml"
    scene.write_text(TABLE2_POINT + FREE_E2 + f'map = "{seeds}"\n')
    assert_refused(vibromap("optimise", scene, "-q", "-o", tmp_path / "opt.h5"), refusal(seeds, "regime map", MAP + 1, MAP))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["optimise.toml", "seeds.h5"]


def test_optimise_resume_refuses_a_journal_of_another_format_version(sweep_map, tmp_path):
    _, reference = sweep_map
    seeds = tmp_path / "seeds.h5"
    seeds.write_bytes(reference.read_bytes())
    scene = tmp_path / "optimise.toml"
    scene.write_text(TABLE2_POINT + FREE_E2 + f'map = "{seeds}"\n')
    journal = tmp_path / "opt.h5.journal"
    header = b"VMJ1" + struct.pack("<IQ", 2, 2) + b"id"  # magic, version 2, identity "id"
    journal.write_bytes(header + struct.pack("<I", zlib.crc32(header)))
    before = journal.read_bytes()
    proc = vibromap("optimise", scene, "-q", "--resume", "-o", tmp_path / "opt.h5")
    assert_refused(proc, refusal(journal, "optimisation journal", 2, 3))
    assert journal.read_bytes() == before
    assert not (tmp_path / "opt.h5").exists()


@pytest.mark.parametrize("version", sorted({0, BASINS_VERSION - 1, BASINS_VERSION + 1}))
def test_basins_resume_refuses_a_file_of_another_format_version(tmp_path, version):
    path = tmp_path / "basins.h5"
    assert vibromap(*BASINS, "-o", path).returncode == 0
    set_version(path, version)
    before = path.read_bytes()
    assert_refused(vibromap(*BASINS, "--resume", "-o", path), refusal(path, "basins file", version, BASINS_VERSION))
    assert path.read_bytes() == before

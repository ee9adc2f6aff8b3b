"""Damage in the attributes of vibromap's other HDF5 files (issue 28):

- every file kind vibromap writes (basins, orbit diagram, branch, trajectory; maps, curves and
  optimisation files in tests/campaigns/outputs) carries the attribute checksum, and the
  postprocess's own check (postprocess/vibromap/_io/seal.py) agrees with vibromap's on it;
- `vibromap basins --resume` of a file with one byte flipped inside an attribute's value exits 4
  with one line "FILE: damaged: ...", before the run's identity is compared.

Run by ctest (tests/campaigns/campaign_tests.cmake)."""
import os
import subprocess
import sys

import h5py
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postprocess"))
from campaign_helpers import ENV, EXE  # noqa: E402
from vibromap._io import h5io as vibromap_h5io  # noqa: E402

SCENE = "jobs/paper/table2.toml"
BASINS = ["basins", SCENE, "--grid", "3x2", "--set", "census.max_attractors=4", "-q"]


def vibromap(*args):
    return subprocess.run([EXE, *map(str, args)], env=ENV, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("command, kind", [
    (BASINS, "basins file"),
    (["orbit-diagram", SCENE, "-p", "forcing.omega", "--from", "7", "--to", "7.2", "--steps", "3"], "orbit-diagram file"),
    (["continue", "jobs/paper/table1.toml", "-p", "forcing.omega", "--from", "7", "--to", "7.2", "--max-points", "5"],
     "branch file"),
    (["run", SCENE, "--trajectory"], "trajectory file"),
], ids=["basins", "orbit-diagram", "continue", "run"])  # fmt: skip
def test_every_file_kind_is_sealed_and_checks_in_the_postprocess(tmp_path, command, kind):
    path = tmp_path / "out.h5"
    proc = vibromap(*command, path) if command[0] == "run" else vibromap(*command, "-o", path)
    assert proc.returncode == 0, proc.stderr
    with h5py.File(path, "r") as f:
        assert str(f.attrs["attribute_checksum"]).startswith("crc32 ")
    with vibromap_h5io.open_h5(path, kind):  # the postprocess checks its version and seal, or raises
        pass


def test_basins_resume_of_a_damaged_file_is_refused_as_damage(tmp_path):
    path = tmp_path / "basins.h5"
    assert vibromap(*BASINS, "-o", path).returncode == 0
    data = bytearray(path.read_bytes())
    where = data.find(b"vibromap basins: the attractor")
    assert where >= 0
    data[where + 3] ^= 0x01
    path.write_bytes(bytes(data))
    proc = vibromap(*BASINS, "-o", path, "--resume")
    assert proc.returncode == 4, proc.stderr
    assert proc.stdout == ""
    assert proc.stderr.count("\n") == 1
    assert proc.stderr.startswith(f"vibromap: error: {path}: damaged: its attributes fail their checksum "
                                  "(attribute_checksum says crc32 "), proc.stderr

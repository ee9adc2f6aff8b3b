"""The format versions of vibromap's files in the Python readers: FORMAT_VERSIONS is the table
include/vibromap/io/file_format.hpp declares, and every reader refuses a file of another version
(older, newer, or without the attribute: version 0) with FileVersionError, the one line vibromap
prints, which the scripts print and exit 2 on. The version is changed without sealing the file
again: it is checked first, so it is named, not reported as damage. Maps and curve files are
tested in test_damaged_files.py and test_curves.py."""
import os
import re
import subprocess
import sys

import pytest

import conftest
from vibromap.plot import _branch as plot_branch
from vibromap.plot import _optimise as plot_optimise
from vibromap.plot import _orbit_diagram as plot_orbit_diagram
from stamp import set_version
import test_plot_basins
import test_plot_branch
import test_plot_optimise
import test_plot_orbit_diagram
from vibromap import _io as vibromap_h5

HEADER = os.path.join(conftest.POSTPROCESS_DIR, "..", "include", "vibromap", "io", "file_format.hpp")


def test_the_python_table_is_the_cpp_one():
    """Every HDF5 kind of file_format.hpp (the journal is vibromap's own) with its version."""
    text = open(HEADER, encoding="utf-8").read()
    declared = {kind: int(version) for kind, version in
                re.findall(r'inline constexpr FileFormat k\w+Format\{"([^"]+)", (\d+)\};', text)}  # fmt: skip
    assert declared.pop("optimisation journal") == 3
    assert declared == vibromap_h5.FORMAT_VERSIONS


def trajectory(path):
    conftest.write_trajectory_h5(path, conftest.analytic_trajectory(10, 1))


# kind: (writer of a file of that kind, its script, its reader)
KINDS = {
    "trajectory file": (trajectory, "plot_trajectory", vibromap_h5.read_trajectory),
    "basins file": (test_plot_basins.basins_file, "plot_basins", vibromap_h5.read_basins),
    "optimisation file": (test_plot_optimise.write_optimisation, "plot_optimise", plot_optimise.read_optimise),
    "branch file": (test_plot_branch.branch_file, "plot_branch", plot_branch.read_branch),
    "orbit-diagram file": (test_plot_orbit_diagram.diagram, "plot_orbit_diagram",
                           lambda path: plot_orbit_diagram.read_diagram(path, "x1")),
}


@pytest.mark.parametrize("version", [0, "next", None])
@pytest.mark.parametrize("kind", list(KINDS))
def test_a_file_of_another_format_version_is_refused_in_one_line(tmp_path, kind, version):
    write, script, read = KINDS[kind]
    path = tmp_path / "file.h5"
    write(path)
    assert read(str(path)) is not None  # the current version reads
    reads = vibromap_h5.FORMAT_VERSIONS[kind]
    version = reads + 1 if version == "next" else version
    set_version(path, version)
    article = "an" if kind[0] in "aeiou" else "a"
    line = (f"{path}: {article} {kind} of format version {version or 0}; this vibromap reads version {reads} only: make the "
            "file again with this vibromap")
    with pytest.raises(vibromap_h5.FileVersionError) as error:
        read(str(path))
    assert str(error.value) == line
    proc = subprocess.run([*conftest.script(script), str(path), "-o",
                           str(tmp_path / "out.png")], capture_output=True, text=True, timeout=120)  # fmt: skip
    assert (proc.returncode, proc.stdout, proc.stderr) == (2, "", f"{script}: error: {line}\n")
    assert not list(tmp_path.glob("out*.png"))

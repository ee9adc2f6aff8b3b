"""Every HDF5 file the commands write opens in xarray with both netCDF-4 engines (issue #29).

Each file kind is written by build/vibromap from a tiny scene: a sweep map, a census map, a
trajectory (run -t), a basins file, an optimisation (its result file with groups, its _map.h5
and its _trajectory.h5), a branch file (continue -o), an orbit diagram (orbit-diagram -o) and a
curve file (continue --curve -o).
Every group of every file is opened as xarray opens a group (open_dataset(path, group=...))
with engine netcdf4 and with h5netcdf, and:

- every axis of every dataset carries a dimension scale (h5py sees a label on each axis);
- xarray lists exactly the group's datasets, each with the dimensions its scales name, of the
  sizes h5py reads, and the same values (decoding off: bytes as stored);
- the dimensions and variables each kind documents (docs/file-formats.md) are there;
- the file carries its kind's format version, the one the postprocess reads
  (postprocess/vibromap/_io/h5io.py's FORMAT_VERSIONS), and still passes its attribute checksum
  (postprocess/vibromap/_io/seal.py); a resumed basins run and sweep still accept their file.
"""
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(REPO, "postprocess"))
from vibromap._io.h5io import FORMAT_VERSIONS, open_h5  # noqa: E402

sys.path.insert(0, os.path.join(REPO, "postprocess", "tests"))
import real_files  # noqa: E402

# The format kind (file_format.hpp) of each file written.
KINDS = {"sweep": "regime map", "census": "regime map", "optimise_map": "regime map", "trajectory": "trajectory file",
         "optimise_trajectory": "trajectory file", "basins": "basins file", "optimise": "optimisation file",
         "branch": "branch file", "orbit": "orbit-diagram file", "curves": "curve file"}

ENGINES = {"netcdf4": "netCDF4", "h5netcdf": "h5netcdf"}


def vibromap(*args, timeout=600):
    proc = subprocess.run([EXE, *map(str, args)], env=ENV, capture_output=True, text=True, timeout=timeout)
    assert proc.returncode == 0, proc.stderr
    return proc


def scene(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Every file kind, written once: {kind: path} (postprocess/tests/real_files.py's files)."""
    made = real_files.make_all(tmp_path_factory.mktemp("xarray"), EXE, ENV, text_files=False)
    return dict(made, sweep=made["map"])


def groups(path):
    """The file's groups as xarray names them: None for the root, then "/a", "/a/b", ..."""
    found = [None]
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, item: found.append("/" + name) if isinstance(item, h5py.Group) else None)
    return found


def h5_layout(path, group):
    """{dataset: (dimension names, shape, values)} of the datasets directly in `group`, the
    dimension names from the scales attached to each axis (None where an axis has none); a
    dimension scale is its own dimension."""
    layout = {}
    with h5py.File(path, "r") as f:
        g = f[group or "/"]
        for name, item in g.items():
            if not isinstance(item, h5py.Dataset):
                continue
            if h5py.h5ds.is_scale(item.id):
                dims = (name,) if item.ndim == 1 else (None,) * item.ndim
            else:
                dims = tuple(d[0].name.rsplit("/", 1)[-1] if len(d) else None for d in item.dims)
            layout[name] = (dims, item.shape, item[()])
    return layout


def open_with(path, engine, group=None):
    xr = pytest.importorskip("xarray")
    pytest.importorskip(ENGINES[engine])
    # No decoding: the values exactly as stored (h5py's), the float fill values included.
    with xr.open_dataset(path, engine=engine, group=group, mask_and_scale=False, decode_times=False) as ds:
        return ds.load()


@pytest.mark.parametrize("engine", list(ENGINES))
@pytest.mark.parametrize("kind", ["sweep", "census", "trajectory", "basins", "optimise", "optimise_map",
                                  "optimise_trajectory", "branch", "orbit", "curves"])
def test_every_group_opens_with_every_dataset_as_h5py_reads_it(files, kind, engine):
    path = files[kind]
    for group in groups(path):
        layout = h5_layout(path, group)
        ds = open_with(path, engine, group)
        assert sorted(ds.variables) == sorted(layout), (group, engine)
        for name, (dims, shape, values) in layout.items():
            assert None not in dims, f"{group}/{name}: an axis without a dimension scale"
            variable = ds[name].variable
            assert variable.dims == dims, (group, name)
            assert variable.shape == shape, (group, name)
            if values.dtype == object:  # strings: h5py gives bytes, netCDF readers str
                values = np.array([v.decode() if isinstance(v, bytes) else v for v in values.ravel()], dtype=object)
            np.testing.assert_array_equal(variable.values, values, err_msg=f"{group}/{name} ({engine})")


def sizes(path, engine, group=None):
    return dict(open_with(path, engine, group).sizes)


def dims_of(path, engine, group, names):
    ds = open_with(path, engine, group)
    return {name: ds[name].dims for name in names}


@pytest.mark.parametrize("engine", list(ENGINES))
def test_maps_have_their_axes_and_the_census_its_attractor_dimension(files, engine):
    assert sizes(files["sweep"], engine) == {"E1": 2, "E2": 3}
    ds = open_with(files["sweep"], engine)
    for name in ("done", "status", "regime", "stable", "soft", "n", "k", "wall_s", "steady_residual", "hertz_valid",
                 "k_con", "T_con", "F_max"):
        assert ds[name].dims == ("E1", "E2"), name
    np.testing.assert_array_equal(ds["E2"].values, [1e6, 1.5e6, 2e6])
    np.testing.assert_allclose(ds["E1"].values, [1e9, 2.1e11], rtol=1e-15)
    assert sizes(files["census"], engine) == {"E1": 2, "E2": 2, "attractor": 3, "period_start": 4, "state": 4}
    census = dims_of(files["census"], engine, None, ["k_con", "attractors", "attractor_fraction", "attractor_x1",
                                                     "attractor_strobe", "family"])
    assert census == {"k_con": ("E1", "E2"), "attractors": ("E1", "E2"), "attractor_fraction": ("E1", "E2", "attractor"),
                      "attractor_x1": ("E1", "E2", "attractor"),
                      "attractor_strobe": ("E1", "E2", "attractor", "period_start", "state"),
                      "family": ("E1", "E2", "attractor")}


@pytest.mark.parametrize("engine", list(ENGINES))
@pytest.mark.parametrize("kind", ["trajectory", "optimise_trajectory"])
def test_a_trajectory_is_indexed_by_time(files, kind, engine):
    ds = open_with(files[kind], engine)
    with h5py.File(files[kind], "r") as f:
        samples = f["t"].shape[0]
        t = f["t"][()]
    assert samples > 100
    assert dict(ds.sizes) == {"t": samples}
    assert list(ds.coords) == ["t"] and sorted(ds.data_vars) == ["F", "Fc", "v1", "v2", "x1", "x2"]
    assert all(ds[name].dims == ("t",) for name in ds.data_vars)
    np.testing.assert_array_equal(ds["t"].values, t)
    assert ds["t"].attrs["units"] == "s" and ds["x1"].attrs["units"] == "m"


@pytest.mark.parametrize("engine", list(ENGINES))
def test_basins_has_its_plane_attractors_and_strobe_dimensions(files, engine):
    path = files["basins"]
    with h5py.File(path, "r") as f:
        attractors = int(f.attrs["attractors"])
        longest = int(f["strobe_points"][()].max())
    assert attractors >= 1 and longest >= 1
    x1, v1 = map(int, real_files.BASINS_GRID.split("x"))
    assert sizes(path, engine) == {"x1": x1, "v1": v1, "attractor": attractors, "period_start": longest, "state": 4}
    ds = open_with(path, engine)
    assert ds["label"].dims == ("v1", "x1") and ds["done"].dims == ("v1", "x1")
    assert ds["strobe"].dims == ("attractor", "period_start", "state")
    for name in ("regime", "n", "k", "k_con", "fraction", "pixels", "first_pixel", "strobe_points"):
        assert ds[name].dims == ("attractor",), name
    assert ds["state"].attrs["flag_meanings"] == "x1 x2 v1 v2"
    # The dimension scales' own attributes (DIMENSION_LIST, REFERENCE_LIST, CLASS, NAME) stay hidden.
    assert sorted(ds["strobe"].attrs) == ["long_name"] and sorted(ds["x1"].attrs) == ["long_name", "units"]
    np.testing.assert_array_equal(ds["state"].values, [0, 1, 2, 3])


@pytest.mark.parametrize("engine", list(ENGINES))
def test_optimise_groups_have_their_dimensions(files, engine):
    path = files["optimise"]
    with h5py.File(path, "r") as f:
        evaluations = f["starts/000/objective"].shape[0]
        multipliers = f["best/00/integrate/floquet"].shape[0]
        census = f["best/00/soft_check/fraction"].shape[0]
        assert sorted(f["starts"]) == ["000"] and sorted(f["best"]) == ["00"]
    assert evaluations >= 2 and multipliers >= 1 and census >= 1
    assert sizes(path, engine) == {"variable": 1, "bound": 2, "seed": 1}
    assert dims_of(path, engine, None, ["bounds", "seeds", "seed_cell", "seed_objective"]) == {
        "bounds": ("variable", "bound"), "seeds": ("seed", "variable"), "seed_cell": ("seed",),
        "seed_objective": ("seed",)}
    # A group sees the root's "variable" dimension (netCDF-4 dimensions are visible in subgroups).
    assert sizes(path, engine, "/starts/000") == {"evaluation": evaluations, "variable": 1}
    start = open_with(path, engine, "/starts/000")
    assert start["x"].dims == ("evaluation", "variable")
    for name in ("objective", "value", "violation", "feasible", "regime", "n", "k", "stable", "wall_s", "k_con"):
        assert start[name].dims == ("evaluation",), name
    assert sizes(path, engine, "/best/00") == {"variable": 1}
    assert sizes(path, engine, "/best/00/integrate") == {"multiplier": multipliers, "part": 2}
    assert open_with(path, engine, "/best/00/shooting")["floquet"].dims == ("multiplier", "part")
    assert sizes(path, engine, "/best/00/soft_check") == {"attractor": census}
    assert open_with(path, engine, "/best/00/soft_check")["fraction"].dims == ("attractor",)


@pytest.mark.parametrize("engine", list(ENGINES))
def test_branch_and_orbit_diagram_have_their_dimensions(files, engine):
    with h5py.File(files["branch"], "r") as f:
        points, branches, bifurcations = f["point"].shape[0], f["branch"].shape[0], f["bifurcation"].shape[0]
        strobes = f["strobe"].shape[0]
    assert points >= 2 and branches >= 1
    assert sizes(files["branch"], engine) == {"point": points, "strobe": strobes, "multiplier": 4, "branch": branches,
                                              "bifurcation": bifurcations}
    assert dims_of(files["branch"], engine, None, ["param", "strobe_x1", "multiplier_re", "branch_n"]) == {
        "param": ("point",), "strobe_x1": ("point", "strobe"), "multiplier_re": ("point", "multiplier"),
        "branch_n": ("branch",)}
    assert sizes(files["orbit"], engine) == {"omega": 3, "direction": 2, "sample": 2}
    assert dims_of(files["orbit"], engine, None, ["x1", "status"]) == {"x1": ("direction", "omega", "sample"),
                                                                        "status": ("direction", "omega")}


@pytest.mark.parametrize("kind", list(KINDS))
def test_every_file_carries_its_format_version_and_passes_its_attribute_checksum(files, kind):
    with open_h5(files[kind], KINDS[kind]) as f:  # checks both, or raises
        version = f.attrs["version"]
    assert version.dtype == np.int64 and version == FORMAT_VERSIONS[KINDS[kind]]


def test_basins_and_sweeps_resume_from_their_files(files, tmp_path):
    """--resume verifies the seal and reads the layout back (C++ readers): nothing left to do."""
    vibromap("basins", "jobs/paper/table2.toml", "--grid", real_files.BASINS_GRID, "-q", "--resume", "-o", files["basins"])
    vibromap("sweep", scene(tmp_path, "sweep.toml", real_files.SWEEP), "-q", "--resume", "-o", files["sweep"])
    vibromap("sweep", scene(tmp_path, "census.toml", real_files.CENSUS), "-q", "--resume", "-o", files["census"])
    with h5py.File(files["basins"], "r") as f:
        assert int(f.attrs["complete"]) == 1 and f["done"][()].all()

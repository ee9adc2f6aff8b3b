"""vibromap.plot: each picture function on a file the built program makes (real_files.py), or
on the Dataset vibromap.files.open gives for it, returns a Figure that pyplot does not hold,
whose texts carry the file's numbers; a damaged file raises DamagedFileError."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

from vibromap import files, plot


def texts(fig) -> list[str]:
    return [t.get_text() for t in fig.findobj(lambda a: hasattr(a, "get_text"))]


def legend_entries(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes for legend in [ax.get_legend()] if legend for t in legend.get_texts()]


def figure_of(function, *args, **kwargs) -> Figure:
    before = plt.get_fignums()
    fig = function(*args, **kwargs)
    assert isinstance(fig, Figure) and plt.get_fignums() == before  # pyplot holds nothing
    fig.savefig(__import__("io").BytesIO(), format="png", dpi=40)  # draws on Agg
    return fig


@pytest.mark.parametrize("function", [plot.regime_map, plot.soft_map])
def test_a_map_picture_counts_the_cells_of_each_regime(made, function):
    ds = files.open(made["map"])
    labels, counts = np.unique(ds.regime_name.values, return_counts=True)
    fig = figure_of(function, ds, x="E1", y="E2")
    for label, count in zip(labels, counts):
        if function is plot.regime_map:
            assert f"{label}: {count} cells" in legend_entries(fig) + texts(fig)
    assert any("E1" in t for t in texts(fig))


def test_kcon_map_colours_k_con_between_the_map_s_values(made):
    ds = files.open(made["map"])
    fig = figure_of(plot.kcon_map, made["map"], x="E1", y="E2")
    meshes = [c for ax in fig.axes for c in ax.collections if c.get_array() is not None and c.get_gid() is None]
    shown = np.concatenate([np.ma.compressed(m.get_array()) for m in meshes])
    assert np.isclose(shown.max(), np.nanmax(ds.k_con.values)) or np.isclose(shown.min(), np.nanmin(ds.k_con.values))
    assert isinstance(fig.vibromap_notes, list)


@pytest.mark.parametrize("show", ["attractors", "soft", "families", "cell"])
def test_census_map_shows_each_view(made, show):
    ds = files.open(made["census"])
    at = {"E1": float(ds.E1.values[0]), "E2": float(ds.E2.values[0])} if show == "cell" else None
    fig = figure_of(plot.census_map, made["census"], show=show, at=at)
    if show == "cell":
        n = int(ds.attractors.values[0, 0])
        assert sum("(1,1)" in t or "(3,3)" in t for t in texts(fig)) >= n


def test_basins_name_their_attractors(made):
    fig = figure_of(plot.basins, files.open(made["basins"]))
    shown = " ".join(legend_entries(fig) + texts(fig))
    assert "(1,1)" in shown and "(3,3)" in shown


def test_branch_orbit_diagram_and_trajectory(made):
    branch = files.open(made["branch"])
    fig = figure_of(plot.branch, made["branch"], diagram=made["orbit"])
    assert len(fig.axes) >= 3
    fig = figure_of(plot.orbit_diagram, made["orbit"], var="x2")
    assert any("x2" in ax.get_ylabel() for ax in fig.axes)
    traj = files.open(made["trajectory"])
    fig = figure_of(plot.trajectory, traj, periods=1)
    assert f"regime {traj.attrs['regime']}" in fig._suptitle.get_text()
    assert branch.sizes["point"] > 0


def test_optimise_draws_convergence_map_and_best_point(made):
    for show in ("convergence", "map", "best"):
        fig = figure_of(plot.optimise, made["optimise"], show=show)
        assert fig.axes


def test_restitution_draws_one_line_per_law(made):
    ds = files.open(made["restitution"])
    fig = figure_of(plot.restitution, made["restitution"])
    laws = sorted(set(ds.law.values.tolist()))
    assert all(any(law in entry for entry in legend_entries(fig)) for law in laws)


def test_work_precision_draws_one_line_per_method_of_the_study(made):
    ds = files.open(made["accuracy"])
    fig = figure_of(plot.work_precision, made["accuracy"], quantity="k_con")
    methods = sorted(set(ds.method.values.tolist()) - {"reference"})
    assert methods and all(any(entry.startswith(m) for entry in legend_entries(fig)) for m in methods)
    assert any(f"k_con = {ds.k_con.values[0]:.6g}" in t for t in texts(fig))  # the reference's, in the title


def test_a_damaged_file_raises_one_value_error(made, tmp_path):
    cut = tmp_path / "cut.h5"
    cut.write_bytes(open(made["map"], "rb").read()[:-4096])
    with pytest.raises(files.DamagedFileError, match=str(cut)):
        plot.regime_map(cut)

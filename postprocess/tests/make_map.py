"""Writes synthetic vibromap map files with h5py, in the layout of
include/vibromap/io/map_file.hpp, for the tests of the map readers and plots.

Layout written (N axes, first axis slowest):
  /<axis>          1-D float64, a dimension scale (make_scale), attributes units, long_name,
                   scale ("lin" | "log")
  /done            N-D uint8
  /status          N-D int8, flag_values -1..3, flag_meanings
  /regime          N-D int8, flag_values -1..8, flag_meanings
  /stable          N-D int8, flag_values -1..1, flag_meanings "unknown unstable stable"
  /n, /k           N-D int32
  /wall_s          N-D float64, units s
  /steady_residual N-D float64, units 1
  /<quantity>      N-D float64 with units (T_con, k_con, ..., max_multiplier, lyapunov) or
                   int64 (hertz_valid, ...); NaN in a float one may also mean "not computed"
Every N-D dataset has the axes attached as dimension scales, in order; links and attributes
keep their creation order (netCDF-4 needs it tracked). Where done == 0,
float datasets hold NaN (their _FillValue), integer ones 0, regime, status and stable -1: write_map
enforces that, so callers may pass full arrays.
Root attributes: title, Conventions, vibromap_version, scene, ranks, cells_total, cells_done,
complete, stored.

Run as a script (python3 make_map.py OUT.h5) it writes a demo 3-D map for looking at plots.
"""

from __future__ import annotations

import sys

import h5py
import numpy as np

AXIS_UNITS = {"law": "1", "E1": "Pa", "E2": "Pa", "R1": "m", "R2": "m", "m2": "kg", "k2": "N/m", "omega2": "rad/s"}
AXIS_LONG_NAMES = {
    "law": "contact law",
    "E1": "Young's modulus of body 1",
    "E2": "Young's modulus of body 2",
    "R1": "radius of the contact surface of body 1",
    "R2": "radius of the contact surface of body 2",
    "m2": "mass of the attached body",
    "k2": "stiffness of the spring joining the bodies",
    "omega2": "partial natural frequency of the attached body",
}
QUANTITY_UNITS = {
    "T_con": "s",
    "k_con": "1",
    "F_max": "N",
    "z_max": "m",
    "z_ratio": "1",
    "v_in": "m/s",
    "impulse": "N s",
    "hertz_valid": "1",
    "periods": "1",
    "rhs_evals": "1",
    "max_multiplier": "1",
    "lyapunov": "1/s",
}
INTEGER_QUANTITIES = ("hertz_valid", "periods", "rhs_evals")
REGIME_MEANINGS = (
    "not_computed periodic chatter no_contact permanent_contact quasi_periodic chaotic non_periodic unresolved failed"
)
STATUS_MEANINGS = "not_computed ok budget failed invalid_input"
STABLE_MEANINGS = "unknown unstable stable"
# Regime codes (RegimeKind order, -1 for a cell not computed).
REGIME = {name: code for code, name in enumerate(REGIME_MEANINGS.split(), start=-1)}
STATUS = {name: code for code, name in enumerate(STATUS_MEANINGS.split(), start=-1)}
STABLE = {name: code for code, name in enumerate(STABLE_MEANINGS.split(), start=-1)}


def _int_dataset(f, name, values, dtype, done, fill):
    values = np.where(done == 0, fill, np.asarray(values)).astype(dtype)
    return f.create_dataset(name, data=values, dtype=dtype)


def _float_dataset(f, name, values, done, units):
    values = np.where(done == 0, np.nan, np.asarray(values, dtype=np.float64))
    dataset = f.create_dataset(name, data=values, dtype="f8", fillvalue=np.nan)
    dataset.attrs["_FillValue"] = np.float64(np.nan)
    dataset.attrs["units"] = units
    return dataset


def write_map(
    path,
    axes,
    regime,
    n,
    k,
    *,
    done=None,
    status=None,
    stable=None,
    wall_s=None,
    steady_residual=None,
    quantities=None,
    scene="[system]\nm1 = 1000.0\n\n[sweep]\n",
    ranks=2,
    attach_scales=True,
    title="vibromap regime map",
    categories=None,
):
    """Writes a map file. axes: [(name, values, scale), ...] in order (first slowest);
    regime, n, k and the optional arrays have the grid's shape; done defaults to regime != -1,
    status to ok where done, stable to unknown (-1) everywhere; quantities: {name: array} of the optional stored quantities.
    attach_scales=False leaves the axes unattached (a malformed map, for the reader's checks);
    categories: {axis name: [choice names]} makes that axis categorical (CF flag_meanings)."""
    shape = tuple(len(values) for _, values, _ in axes)
    regime = np.asarray(regime)
    assert regime.shape == shape, (regime.shape, shape)
    done = (regime != REGIME["not_computed"]) if done is None else np.asarray(done)
    done = done.astype(np.uint8)
    if status is None:
        status = np.full(shape, STATUS["ok"])
    if wall_s is None:
        wall_s = np.full(shape, 0.25)
    if steady_residual is None:
        steady_residual = np.full(shape, 1e-9)
    quantities = dict(quantities or {})

    # Creation order tracked, as the C++ writer does: xarray then lists the variables in the
    # order written (done, status, regime, ...), not alphabetically.
    with h5py.File(path, "w", track_order=True) as f:
        scales = []
        for name, values, scale in axes:
            axis = f.create_dataset(name, data=np.asarray(values, dtype=np.float64), dtype="f8")
            axis.attrs["units"] = AXIS_UNITS[name]
            axis.attrs["long_name"] = AXIS_LONG_NAMES[name]
            axis.attrs["scale"] = scale
            if categories and name in categories:
                axis.attrs["flag_values"] = np.arange(len(categories[name]), dtype=np.int8)
                axis.attrs["flag_meanings"] = " ".join(categories[name])
            axis.make_scale(name)
            scales.append(axis)

        datasets = [f.create_dataset("done", data=done, dtype="u1")]
        status_ds = _int_dataset(f, "status", status, "i1", done, STATUS["not_computed"])
        status_ds.attrs["flag_values"] = np.arange(-1, 4, dtype=np.int8)
        status_ds.attrs["flag_meanings"] = STATUS_MEANINGS
        regime_ds = _int_dataset(f, "regime", regime, "i1", done, REGIME["not_computed"])
        regime_ds.attrs["flag_values"] = np.arange(-1, 9, dtype=np.int8)
        regime_ds.attrs["flag_meanings"] = REGIME_MEANINGS
        stable = np.full(shape, STABLE["unknown"]) if stable is None else stable
        stable_ds = _int_dataset(f, "stable", stable, "i1", done, STABLE["unknown"])
        stable_ds.attrs["flag_values"] = np.arange(-1, 2, dtype=np.int8)
        stable_ds.attrs["flag_meanings"] = STABLE_MEANINGS
        datasets += [status_ds, regime_ds, stable_ds]
        datasets.append(_int_dataset(f, "n", n, "i4", done, 0))
        datasets.append(_int_dataset(f, "k", k, "i4", done, 0))
        datasets.append(_float_dataset(f, "wall_s", wall_s, done, "s"))
        datasets.append(_float_dataset(f, "steady_residual", steady_residual, done, "1"))
        for name, values in quantities.items():
            if name in INTEGER_QUANTITIES:
                dataset = _int_dataset(f, name, values, "i8", done, 0)
                dataset.attrs["units"] = QUANTITY_UNITS[name]
            else:
                dataset = _float_dataset(f, name, values, done, QUANTITY_UNITS[name])
            datasets.append(dataset)

        if attach_scales:
            for dataset in datasets:
                for i, axis in enumerate(scales):
                    dataset.dims[i].attach_scale(axis)

        f.attrs["title"] = title
        f.attrs["Conventions"] = "CF-1.8"
        f.attrs["vibromap_version"] = "0.1.0"
        f.attrs["scene"] = scene
        f.attrs["ranks"] = np.int64(ranks)
        f.attrs["cells_total"] = np.int64(done.size)
        f.attrs["cells_done"] = np.int64(done.sum())
        f.attrs["complete"] = np.int64(1 if done.all() else 0)
        f.attrs["stored"] = " ".join(quantities)


def demo_map(path):
    """A 3-D map E1 x E2 x R1 (log, log, lin) with a plausible look: (1,1) where the contact is
    soft, (2,1) and chatter for stiff bodies (the stiffest (2,1) orbits unstable), no contact at
    one corner, some cells not done."""
    e1 = np.geomspace(2e4, 2.1e11, 25)
    e2 = np.geomspace(2e4, 2.1e11, 20)
    r1 = np.array([0.09, 0.5, 1.0, 2.0])
    L1, L2, R = np.meshgrid(np.log10(e1), np.log10(e2), r1, indexing="ij")
    stiffness = 0.5 * (L1 + L2) + 0.3 * R  # a made-up hardness index, 4.3 .. 11.6
    k_con = 10.0 ** (0.35 * (stiffness - 4.0) + 0.1)  # ~1.3 (soft) .. ~600 (rigid)
    regime = np.where(stiffness < 8.5, REGIME["periodic"], REGIME["chatter"])
    regime = np.where((stiffness >= 7.5) & (stiffness < 8.5) & (L1 > L2), REGIME["periodic"], regime)
    n = np.where(regime == REGIME["periodic"], np.where((stiffness >= 7.5) & (L1 > L2), 2, 1), 0)
    k = np.where(regime == REGIME["periodic"], 1, 0)
    regime = np.where((L1 < 5.0) & (L2 > 10.0), REGIME["no_contact"], regime)
    n = np.where(regime == REGIME["no_contact"], 0, n)
    k = np.where(regime == REGIME["no_contact"], 0, k)
    k_con = np.where(regime == REGIME["no_contact"], 0.0, k_con)
    regime[-3:, -4:, :] = REGIME["not_computed"]
    # Periodic orbits stable, but the (2,1) ones losing stability next to the chatter region.
    stable = np.where(regime == REGIME["periodic"], STABLE["stable"], STABLE["unknown"])
    stable = np.where((n == 2) & (stiffness >= 8.2), STABLE["unstable"], stable)
    write_map(
        path,
        [("E1", e1, "log"), ("E2", e2, "log"), ("R1", r1, "lin")],
        regime,
        n,
        k,
        stable=stable,
        quantities={"T_con": (2 * np.pi / 7.23) / np.where(k_con > 0, k_con, np.inf), "k_con": k_con},
    )


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: make_map.py OUT.h5", file=sys.stderr)
        sys.exit(2)
    demo_map(sys.argv[1])
    print(f"make_map: wrote {sys.argv[1]}")

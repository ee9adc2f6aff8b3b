"""Writes synthetic vibromap map files with h5py, in the layout of
include/vibromap/io/map_file.hpp (the current format: version and attribute checksum included),
for the tests of the map readers and plots.

Layout written (N axes, first axis slowest):
  /<axis>          1-D float64, a dimension scale (make_scale), attributes units, long_name,
                   key (the full scene key, AXIS_KEYS), scale ("lin" | "log")
  /done            N-D uint8
  /status          N-D int8, flag_values -1..3, flag_meanings
  /regime          N-D int8, flag_values -1..8, flag_meanings
  /stable          N-D int8, flag_values -1..1, flag_meanings "unknown unstable stable"
  /soft            N-D int8, flag_values -1..1, flag_meanings "not_computed no yes", long_name
                   (given as soft=, else the definition applied to the arrays: periodic with
                   impacts, stable, Hertz-valid and 0 < k_con <= soft_kcon)
  /n, /k           N-D int32
  /wall_s          N-D float64, units s
  /steady_residual N-D float64, units 1
  /<quantity>      N-D float64 with units (T_con, k_con, ..., max_multiplier, lyapunov) or
                   int64 (hertz_valid, ...); NaN in a float one may also mean "not computed".
                   hertz_valid is always one (given as hertz_valid=, else z_ratio <= hertz_limit,
                   else 1 everywhere), first in `stored`
Every N-D dataset has the axes attached as dimension scales, in order; links and attributes
keep their creation order (netCDF-4 needs it tracked). Where done == 0,
float datasets hold NaN (their _FillValue), integer ones 0, regime, status and stable -1: write_map
enforces that, so callers may pass full arrays.
Root attributes: title, Conventions, vibromap_version, scene, identity, ranks, cells_total,
cells_done, complete, stored, census_attractors (0), steady, hertz_limit, soft_kcon (MAP_DEFAULTS,
or as given), then version and attribute_checksum (stamp.py). A test that changes a map after
write_map stamps it again (seal), or finds it damaged.

Run as a script (python3 make_map.py OUT.h5 [--shooting]) it writes a demo 3-D map for looking
at plots (--shooting: as if made with analysis.steady = "shooting").
"""

from __future__ import annotations

import sys

import h5py
import numpy as np

from stamp import stamp

AXIS_UNITS = {"law": "1", "E1": "Pa", "E2": "Pa", "R1": "m", "R2": "m", "m2": "kg", "k2": "N/m", "omega2": "rad/s"}
AXIS_KEYS = {"law": "contact.law", "E1": "contact.E1", "E2": "contact.E2", "R1": "contact.R1", "R2": "contact.R2",
             "m2": "system.m2", "k2": "system.k2", "omega2": "system.omega2"}
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
SOFT_MEANINGS = "not_computed no yes"
SOFT_LONG_NAME = (
    "1 where the motion is soft: periodic with impacts, stable, Hertz-valid (z_ratio <= hertz_limit) and "
    "k_con <= soft_kcon"
)
# Regime codes (RegimeKind order, -1 for a cell not computed).
REGIME = {name: code for code, name in enumerate(REGIME_MEANINGS.split(), start=-1)}
STATUS = {name: code for code, name in enumerate(STATUS_MEANINGS.split(), start=-1)}
STABLE = {name: code for code, name in enumerate(STABLE_MEANINGS.split(), start=-1)}
# The root attributes a map has whatever it holds, as write_map writes them unless given.
MAP_DEFAULTS = {"identity": "system.m1 = 1000\n", "census_attractors": np.int64(0), "steady": "follow",
                "hertz_limit": 0.05, "soft_kcon": 10.0}
UNCOVERED = ("cells_done", "complete", "ranks")  # what a map's seal leaves out (a run rewrites them)


def _int_dataset(f, name, values, dtype, done, fill):
    values = np.where(done == 0, fill, np.asarray(values)).astype(dtype)
    return f.create_dataset(name, data=values, dtype=dtype)


def _float_dataset(f, name, values, done, units):
    values = np.where(done == 0, np.nan, np.asarray(values, dtype=np.float64))
    dataset = f.create_dataset(name, data=values, dtype="f8", fillvalue=np.nan)
    dataset.attrs["_FillValue"] = np.float64(np.nan)
    dataset.attrs["units"] = units
    return dataset


def _flag_dataset(f, name, values, done, meanings, long_name=None):
    """An int8 CF flag dataset (flag_values -1, 0, ...; -1 where not done)."""
    dataset = _int_dataset(f, name, values, "i1", done, -1)
    if long_name:
        dataset.attrs["long_name"] = long_name
    dataset.attrs["flag_values"] = np.arange(-1, len(meanings.split()) - 1, dtype=np.int8)
    dataset.attrs["flag_meanings"] = meanings
    return dataset


def _write_axes(f, axes, categories):
    """The coordinate datasets, made dimension scales; returns them in order."""
    scales = []
    for name, values, scale in axes:
        axis = f.create_dataset(name, data=np.asarray(values, dtype=np.float64), dtype="f8")
        axis.attrs["units"] = AXIS_UNITS[name]
        axis.attrs["long_name"] = AXIS_LONG_NAMES[name]
        axis.attrs["key"] = AXIS_KEYS[name]
        axis.attrs["scale"] = scale
        if categories and name in categories:
            axis.attrs["flag_values"] = np.arange(len(categories[name]), dtype=np.int8)
            axis.attrs["flag_meanings"] = " ".join(categories[name])
        axis.make_scale(name)
        scales.append(axis)
    return scales


def _write_cells(f, done, arrays, quantities, long_names):
    """The per-cell datasets in the C++ writer's order; arrays: status, regime, stable, soft, n,
    k, wall_s, steady_residual; quantities: the stored ones, hertz_valid first; long_names: the
    quantities' long_name attributes (a quantity without one has none; units "1" for a name
    QUANTITY_UNITS does not know)."""
    datasets = [f.create_dataset("done", data=done, dtype="u1")]
    datasets.append(_flag_dataset(f, "status", arrays["status"], done, STATUS_MEANINGS))
    datasets.append(_flag_dataset(f, "regime", arrays["regime"], done, REGIME_MEANINGS))
    datasets.append(_flag_dataset(f, "stable", arrays["stable"], done, STABLE_MEANINGS))
    datasets.append(_flag_dataset(f, "soft", arrays["soft"], done, SOFT_MEANINGS, SOFT_LONG_NAME))
    datasets.append(_int_dataset(f, "n", arrays["n"], "i4", done, 0))
    datasets.append(_int_dataset(f, "k", arrays["k"], "i4", done, 0))
    datasets.append(_float_dataset(f, "wall_s", arrays["wall_s"], done, "s"))
    datasets.append(_float_dataset(f, "steady_residual", arrays["steady_residual"], done, "1"))
    for name, values in quantities.items():
        if name in INTEGER_QUANTITIES:
            dataset = _int_dataset(f, name, values, "i8", done, 0)
            dataset.attrs["units"] = QUANTITY_UNITS[name]
        else:
            dataset = _float_dataset(f, name, values, done, QUANTITY_UNITS.get(name, "1"))
        if name in long_names:
            dataset.attrs["long_name"] = long_names[name]
        datasets.append(dataset)
    return datasets


def _defining_soft(done, regime, k, stable, hertz_valid, k_con, soft_kcon):
    """The soft flag by the one definition: periodic with impacts, stable, Hertz-valid and
    0 < k_con <= soft_kcon (0 everywhere without a k_con)."""
    if k_con is None:
        return np.zeros(done.shape, dtype=np.int8)
    k_con = np.asarray(k_con, dtype=np.float64)
    periodic = (done != 0) & (np.asarray(regime) == REGIME["periodic"]) & (np.asarray(k) > 0)
    soft = periodic & (np.asarray(stable) == STABLE["stable"]) & (np.asarray(hertz_valid) != 0) & (k_con > 0) \
        & (k_con <= soft_kcon)
    return soft.astype(np.int8)


def write_map(path, axes, regime, n, k, *, done=None, status=None, stable=None, wall_s=None, steady_residual=None,
              quantities=None, scene="[system]\nm1 = 1000.0\n\n[sweep]\n", ranks=2, attach_scales=True,
              title="vibromap regime map", categories=None, soft=None, hertz_valid=None, attributes=None,
              long_names=None):  # fmt: skip
    """Writes a map file, stamped (version and attribute checksum). axes: [(name, values, scale),
    ...] in order (first slowest); regime, n, k and the optional arrays have the grid's shape;
    done defaults to regime != -1, status to ok where done, stable to unknown (-1) everywhere;
    quantities: {name: array} of the optional stored quantities.
    attach_scales=False leaves the axes unattached (a malformed map, for the reader's checks);
    categories: {axis name: [choice names]} makes that axis categorical (CF flag_meanings);
    soft, hertz_valid: /soft (0/1) and /hertz_valid (0/1), by default as the module docstring
    says; attributes: root attributes replacing MAP_DEFAULTS (soft_kcon, hertz_limit, steady);
    long_names: {quantity: long_name} (the C++ writer gives every quantity one; tests give those
    they need)."""
    shape = tuple(len(values) for _, values, _ in axes)
    regime = np.asarray(regime)
    assert regime.shape == shape, (regime.shape, shape)
    done = ((regime != REGIME["not_computed"]) if done is None else np.asarray(done)).astype(np.uint8)
    root = {**MAP_DEFAULTS, **(attributes or {})}
    quantities = dict(quantities or {})
    if hertz_valid is None:
        hertz_valid = quantities.get("hertz_valid")
    if hertz_valid is None:
        z_ratio = quantities.get("z_ratio")
        hertz_valid = np.ones(shape) if z_ratio is None else np.asarray(z_ratio) <= root["hertz_limit"]
    quantities = {"hertz_valid": np.asarray(hertz_valid).astype(np.int64), **quantities}
    stable = np.full(shape, STABLE["unknown"]) if stable is None else stable
    if soft is None:
        soft = _defining_soft(done, regime, k, stable, hertz_valid, quantities.get("k_con"), root["soft_kcon"])
    arrays = dict(
        status=np.full(shape, STATUS["ok"]) if status is None else status,
        regime=regime, stable=stable, soft=soft, n=n, k=k,
        wall_s=np.full(shape, 0.25) if wall_s is None else wall_s,
        steady_residual=np.full(shape, 1e-9) if steady_residual is None else steady_residual,
    )  # fmt: skip
    # Creation order tracked, as the C++ writer does: xarray then lists the variables in the
    # order written (done, status, regime, ...), not alphabetically.
    with h5py.File(path, "w", track_order=True) as f:
        scales = _write_axes(f, axes, categories)
        datasets = _write_cells(f, done, arrays, quantities, dict(long_names or {}))
        if attach_scales:
            for dataset in datasets:
                for i, axis in enumerate(scales):
                    dataset.dims[i].attach_scale(axis)
        root = dict(title=title, Conventions="CF-1.8", vibromap_version="0.1.0", scene=scene, ranks=np.int64(ranks),
                    cells_total=np.int64(done.size), cells_done=np.int64(done.sum()),
                    complete=np.int64(1 if done.all() else 0), stored=" ".join(quantities), **root)  # fmt: skip
        for name, value in root.items():
            if value is not None:
                f.attrs[name] = value
    seal(path)


def seal(path):
    """Stamps a map written by write_map (again, after a change) as vibromap's writer stamps its
    maps: the version, then the attribute checksum over all attributes but UNCOVERED."""
    stamp(path, "regime map", UNCOVERED)


# The soft test map: E1 (log, 6 points) x E2 (log, 4 points), cell [i, j] (i along E1).
SOFT_AXES = [("E1", np.geomspace(1e5, 1e10, 6), "log"), ("E2", np.array([1e4, 1e6, 1e8, 1e10]), "log")]
SOFT_HERTZ_INVALID = ((0, 0), (1, 1), (3, 0), (5, 3))  # z_ratio 0.2: the first two have k_con <= 10
SOFT_CELLS = ((0, 1), (0, 2), (1, 0), (1, 3))  # periodic, stable, Hertz-valid, k_con <= 10


def soft_pattern():
    """The soft test map's arrays: (1,1) everywhere with k_con = 2 * 3^i (2, 6, 18, 54, 162, 486),
    stable, z_ratio 0.01, except: [0, 3] no contact (k_con 0, z_ratio 0), [4, 3] and [5, 3]
    chatter, [5, 2] not computed, [1, 2] unstable (k_con 6), and SOFT_HERTZ_INVALID with z_ratio
    0.2. soft and hertz_valid are the definition applied to them (soft_kcon 10, hertz_limit 0.05):
    soft exactly in SOFT_CELLS."""
    shape = (6, 4)
    i = np.indices(shape)[0]
    regime = np.full(shape, REGIME["periodic"])
    regime[0, 3] = REGIME["no_contact"]
    regime[4, 3] = regime[5, 3] = REGIME["chatter"]
    regime[5, 2] = REGIME["not_computed"]
    periodic = regime == REGIME["periodic"]
    k_con = np.where(regime == REGIME["no_contact"], 0.0, 2.0 * 3.0**i)
    stable = np.where(periodic, STABLE["stable"], STABLE["unknown"])
    stable[1, 2] = STABLE["unstable"]
    z_ratio = np.where(regime == REGIME["no_contact"], 0.0, 0.01)
    for cell in SOFT_HERTZ_INVALID:
        z_ratio[cell] = 0.2
    hertz_valid = (z_ratio <= 0.05).astype(np.int64)
    soft = (periodic & (stable == STABLE["stable"]) & (hertz_valid == 1) & (k_con > 0) & (k_con <= 10.0)).astype(np.int8)
    n = np.where(periodic, 1, 0)
    return dict(regime=regime, n=n, k=n.copy(), k_con=k_con, stable=stable, z_ratio=z_ratio, hertz_valid=hertz_valid,
                soft=soft)  # fmt: skip


def write_soft_map(path, steady="follow", quantities=("k_con", "z_ratio"), **changes):
    """Writes the soft test map. quantities: the stored ones kept (hertz_valid always); changes:
    arrays or root attributes (soft_kcon=..., hertz_limit=..., any of MAP_DEFAULTS) replacing
    soft_pattern's. Returns the arrays written."""
    arrays = soft_pattern()
    attributes = {"soft_kcon": 10.0, "hertz_limit": 0.05, "steady": steady}
    for name, value in changes.items():
        (attributes if name in attributes or name in MAP_DEFAULTS else arrays)[name] = value
    write_map(path, SOFT_AXES, arrays["regime"], arrays["n"], arrays["k"], stable=arrays["stable"],
              quantities={name: arrays[name] for name in quantities}, soft=arrays["soft"],
              hertz_valid=arrays["hertz_valid"], attributes=attributes)  # fmt: skip
    return arrays


def demo_map(path, steady="follow"):
    """A 3-D map E1 x E2 x R1 (log, log, lin) with a plausible look: (1,1) where the contact is
    soft, (2,1) and chatter for stiff bodies (the stiffest (2,1) orbits unstable), no contact at
    one corner, some cells not done; the softest bodies deform beyond the Hertz limit
    (z_ratio > 0.05), so /soft there is 0 though k_con is small."""
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
    z_ratio = np.where(k_con > 0, 0.3 * 10.0 ** (-0.45 * (stiffness - 4.3)), 0.0)
    hertz_valid = z_ratio <= 0.05
    soft = (regime == REGIME["periodic"]) & (k > 0) & (stable == STABLE["stable"]) & hertz_valid & (k_con <= 10.0)
    write_map(
        path,
        [("E1", e1, "log"), ("E2", e2, "log"), ("R1", r1, "lin")],
        regime,
        n,
        k,
        stable=stable,
        quantities={"T_con": (2 * np.pi / 7.23) / np.where(k_con > 0, k_con, np.inf), "k_con": k_con,
                    "z_ratio": z_ratio},
        soft=soft,
        hertz_valid=hertz_valid,
        attributes={"soft_kcon": 10.0, "hertz_limit": 0.05, "steady": steady},
    )


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3) or sys.argv[2:] not in ([], ["--shooting"]):
        print("usage: make_map.py OUT.h5 [--shooting]", file=sys.stderr)
        sys.exit(2)
    demo_map(sys.argv[1], "shooting" if sys.argv[2:] else "follow")
    print(f"make_map: wrote {sys.argv[1]}")

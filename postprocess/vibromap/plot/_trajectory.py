"""Plot a vibromap trajectory file the way the source paper shows a steady motion.

Top panel: displacements x1(t), x2(t) of the main and the attached body. Bottom panel: the
Hertz contact force Fc(t) (left axis) against the external force F(t) (right axis): the two
differ by orders of magnitude (1e5 N against 500 N for a rigid impact), so each has its own
axis. Time is in forcing periods, t/T. The title gives the regime, k_con = T/T_con and T_con.

Exit status: 0 on success, 2 for a bad argument or an unreadable or invalid file (one line
on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import argparse
import sys

from .._guard import guarded_main

PROG = "plot_trajectory"

import matplotlib
from . import _args, _figure
import numpy as np

from .._io import Trajectory, VibromapFileError, read_trajectory, write_plot

FIGSIZE_IN = (8.0, 6.0)  # width, height in inches; at the default 150 dpi: 1200 x 900 px
COLOR_X1, COLOR_X2, COLOR_FC, COLOR_F = "C0", "C1", "C3", "C0"


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Plot displacements and contact/external force of a vibromap trajectory file.",
    )
    parser.add_argument("trajectory", metavar="TRAJ.h5", help="trajectory file written by vibromap")
    _args.add_image(parser, "TRAJ.png")
    _args.add_periods(parser, "plot only the first N forcing periods of the kept window (default: all)")
    return _args.finish(parser, argv, "trajectory")


def select_periods(traj: Trajectory, periods: float | None) -> np.ndarray:
    """Boolean mask of the samples within the first `periods` forcing periods (all if None)."""
    if periods is None:
        return np.ones(traj.t.shape, dtype=bool)
    # A relative slack so that the sample at exactly N T is kept despite rounding in t.
    return traj.phase - traj.phase[0] <= periods * (1.0 + 1e-12)


def title(traj: Trajectory) -> str:
    parts = [f"regime {traj.regime}"]
    if traj.T_con > 0:
        parts.append(f"k_con = T/T_con = {traj.k_con:.4g}")
        parts.append(f"T_con = {traj.T_con:.3g} s")
    else:
        parts.append("no impact")
    return ",  ".join(parts)


def plot(traj: Trajectory, mask: np.ndarray):
    """The figure: displacements on top, contact force against external force below."""
    phase = traj.phase[mask]
    fig, (ax_x, ax_f) = _figure.subplots(2, 1, sharex=True, figsize=FIGSIZE_IN, constrained_layout=True)

    ax_x.plot(phase, traj.x1[mask], color=COLOR_X1, label="x1 (main body)")
    ax_x.plot(phase, traj.x2[mask], color=COLOR_X2, label="x2 (attached body)")
    ax_x.set_ylabel(f"displacement, {traj.units.get('x1') or 'm'}")
    ax_x.grid(True, alpha=0.3)
    fig.suptitle(title(traj))

    line_fc = ax_f.plot(phase, traj.Fc[mask], color=COLOR_FC, label="Fc, contact force")
    ax_f.set_ylabel(f"contact force Fc, {traj.units.get('Fc') or 'N'}", color=COLOR_FC)
    ax_f.tick_params(axis="y", colors=COLOR_FC)
    ax_f.set_xlabel("t / T")
    ax_f.grid(True, alpha=0.3)
    ax_ext = ax_f.twinx()
    line_f = ax_ext.plot(phase, traj.F[mask], color=COLOR_F, linestyle="--", label="F, external force")
    ax_ext.set_ylabel(f"external force F, {traj.units.get('F') or 'N'}", color=COLOR_F)
    ax_ext.tick_params(axis="y", colors=COLOR_F)
    lines = line_fc + line_f
    # Legends above their panels, where they cannot hide a curve.
    above = dict(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=2, frameon=False, borderaxespad=0.2)
    ax_x.legend(**above)
    ax_f.legend(lines, [line.get_label() for line in lines], **above)
    return fig


def read(path: str) -> Trajectory:
    """The trajectory file, refused when it has no samples or no positive period."""
    traj = read_trajectory(path)
    if traj.t.size == 0:
        raise VibromapFileError(f"{path}: the trajectory has no samples")
    if not traj.T > 0:
        raise VibromapFileError(f"{path}: attribute 'T' is not a positive period")
    return traj


def from_dataset(ds) -> Trajectory:
    """A Trajectory from a Dataset with the trajectory file's variables and attributes
    (vibromap.trajectory(scene))."""
    columns = {name: np.asarray(ds[name].values) for name in ("t", "x1", "x2", "v1", "v2", "Fc", "F")}
    units = {name: str(ds[name].attrs.get("units", "")) for name in columns}
    a = ds.attrs
    return Trajectory(path="", units=units, T=float(a["T"]), regime=str(a.get("regime", "")), n=int(a.get("n", 0)),
                      k=int(a.get("k", 0)), T_con=float(a.get("T_con", 0.0)), k_con=float(a.get("k_con", 0.0)),
                      scene=str(a.get("scene", "")), vibromap_version=str(a.get("vibromap_version", "")), **columns)


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    from . import trajectory

    args = parse_args(argv)

    def figure():
        return trajectory(args.trajectory, args.periods)

    return write_plot(PROG, figure, args.output, args.dpi)



"""Plot a vibromap accuracy study as a work-precision diagram: error against cost.

Input: the CSV of `vibromap accuracy SCENE --csv FILE.csv` (src/campaigns/accuracy/accuracy_run.cpp),
one row per case: columns method (rk4, dopri5, hybrid+shooting, reference), setting ("rtol 1e-8"
or "2^11 steps/T"), status, regime, regime_matches (1/0), wall_s (solve time of one point, s),
rel_err_T_con, rel_err_F_max, rel_err_k_con (|x - x_ref|/|x_ref|, "nan" when undefined), ...

The figure: log-log relative error of one quantity (--quantity, default T_con) against the
solve time of one point, one line per method, each point annotated with its tolerance (rtol)
or its steps per forcing period. Lower left is better: a method whose line lies below another
buys more accuracy for the same time. The reference row (zero error by construction) is named
in the title, not plotted; cases without a finite positive error (no impact, failed, or equal
to the reference to the last digit) cannot be drawn on a log axis and are listed under the
plot. Points whose regime differs from the reference's are ringed in black.

Exit status: 0 on success, 2 for a bad argument or an unreadable or invalid file (one line
on stderr), 3 when numpy or matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import math
import sys

from .._guard import guarded_main

PROG = "plot_work_precision"

import matplotlib
from . import _args, _figure
import numpy as np

from .._io import VibromapFileError, write_plot

FIGSIZE_IN = (8.0, 6.0)  # width, height in inches; at the default 150 dpi: 1200 x 900 px
QUANTITIES = {"T_con": "T_con (impact duration)", "F_max": "F_max (peak contact force)", "k_con": "k_con = T/T_con"}
REFERENCE = "reference"
# Fixed colours for the study's methods (other labels take the next free ones).
METHOD_COLORS = {"rk4": "C3", "dopri5": "C0", "hybrid+shooting": "C2"}
COLOR_MISMATCH = "black"  # ring around a point whose regime differs from the reference's
REQUIRED_COLUMNS = ("method", "setting", "status", "regime", "wall_s")


class StudyFileError(Exception):
    """The CSV cannot be read or is not an accuracy study."""


@dataclasses.dataclass
class Case:
    """One row of the study."""

    method: str
    setting: str  # "rtol 1e-8" or "2^11 steps/T"
    status: str
    regime: str
    regime_matches: bool
    wall_s: float  # solve time of one point, s
    errors: dict[str, float]  # quantity -> relative error (nan when undefined)
    values: dict[str, float]  # quantity -> value (s, N, -), nan when the column is absent


@dataclasses.dataclass
class Study:
    path: str
    reference: Case | None
    cases: list[Case]  # every row but the reference, in file order


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog=PROG, formatter_class=argparse.RawDescriptionHelpFormatter, description=__doc__)
    parser.add_argument("csv", metavar="CSV", help="accuracy study written by vibromap accuracy --csv")
    _args.add_image(parser, "CSV's name with .png")
    parser.add_argument(
        "--quantity",
        choices=tuple(QUANTITIES),
        default="T_con",
        help="whose relative error to plot: T_con (impact duration), F_max (peak contact force) or "
        "k_con = T/T_con (default: T_con)",
    )
    return _args.finish(parser, argv, "csv")


def number(row: dict[str, str], column: str, where: str) -> float:
    text = (row.get(column) or "").strip()
    if text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise StudyFileError(f"{where}: {column} '{text}' is not a number") from None


def case_of(row: dict[str, str], where: str) -> Case:
    return Case(
        method=row["method"].strip(),
        setting=row["setting"].strip(),
        status=row["status"].strip(),
        regime=row["regime"].strip(),
        regime_matches=(row.get("regime_matches") or "1").strip() not in ("0", "false", "False"),
        wall_s=number(row, "wall_s", where),
        errors={q: number(row, f"rel_err_{q}", where) for q in QUANTITIES},
        values={q: number(row, q, where) for q in QUANTITIES},
    )


def read_study(path: str) -> Study:
    """The study's rows; StudyFileError (one line, naming the file) when it cannot be one."""
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            header = reader.fieldnames or []
    except FileNotFoundError:
        raise StudyFileError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise StudyFileError(f"{path}: is a directory") from None
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise StudyFileError(f"{path}: cannot read ({exc})") from None
    if not rows:
        raise StudyFileError(f"{path}: no rows: not an accuracy study CSV (vibromap accuracy --csv)")
    for column in REQUIRED_COLUMNS:
        if column not in header:
            raise StudyFileError(f"{path}: no column '{column}': not an accuracy study CSV (vibromap accuracy --csv)")
    cases = [case_of(row, f"{path}:{line}") for line, row in enumerate(rows, start=2)]
    reference = next((c for c in cases if c.method == REFERENCE), None)
    return Study(path, reference, [c for c in cases if c.method != REFERENCE])


def plottable(case: Case, quantity: str) -> bool:
    err = case.errors[quantity]
    return math.isfinite(err) and err > 0 and math.isfinite(case.wall_s) and case.wall_s > 0


def short_setting(setting: str) -> str:
    """'rtol 1e-8' -> '1e-8', '2^11 steps/T' -> '2^11': the legend says which it is."""
    return setting.removeprefix("rtol ").removesuffix(" steps/T")


def methods_in_order(study: Study) -> list[str]:
    seen: list[str] = []
    for c in study.cases:
        if c.method not in seen:
            seen.append(c.method)
    return seen


def legend_label(method: str, cases: list[Case]) -> str:
    if all(c.setting.startswith("rtol ") for c in cases):
        return f"{method} (rtol)"
    if all(c.setting.endswith(" steps/T") for c in cases):
        return f"{method} (steps per period)"
    return method


def title(study: Study, quantity: str) -> str:
    head = f"relative error of {QUANTITIES[quantity]} against solve time"
    ref = study.reference
    if ref is None:
        return head + "\n(no reference row in the file)"
    value = ref.values[quantity]
    unit = {"T_con": " s", "F_max": " N", "k_con": ""}[quantity]
    shown = f", {quantity} = {value:.6g}{unit}" if math.isfinite(value) else ""
    return f"{head}\nreference: dopri5 {ref.setting}, {ref.status} {ref.regime}{shown}"


def draw_method(ax, method: str, cases: list[Case], quantity: str, color: str) -> None:
    points = [c for c in cases if plottable(c, quantity)]  # in file order: loosest to tightest
    if not points:
        return
    x = np.array([c.wall_s for c in points])
    y = np.array([c.errors[quantity] for c in points])
    ax.plot(x, y, marker="o", color=color, label=legend_label(method, cases), gid=f"method:{method}")
    for c, xi, yi in zip(points, x, y):
        ax.annotate(short_setting(c.setting), (xi, yi), textcoords="offset points", xytext=(5, 4),
                    fontsize=8, color=color)
    bad = [(c.wall_s, c.errors[quantity]) for c in points if not c.regime_matches]
    if bad:
        bx, by = zip(*bad)
        ax.plot(bx, by, linestyle="none", marker="o", markersize=12, markerfacecolor="none",
                markeredgecolor=COLOR_MISMATCH, gid=f"mismatch:{method}")


def not_shown(study: Study, quantity: str) -> list[str]:
    out = []
    for c in study.cases:
        if not plottable(c, quantity):
            why = c.status if c.status != "ok" else ("no impact" if not math.isfinite(c.errors[quantity]) else "error 0")
            out.append(f"{c.method} {short_setting(c.setting)} ({why})")
    return out


def plot(study: Study, quantity: str):
    """The figure: one line per method; raises StudyFileError when nothing can be drawn."""
    if not any(plottable(c, quantity) for c in study.cases):
        raise StudyFileError(f"{study.path}: no case has a finite positive error of {quantity} and a solve time")
    fig, ax = _figure.subplots(figsize=FIGSIZE_IN, constrained_layout=True)
    free = iter(f"C{i}" for i in range(4, 10))
    for method in methods_in_order(study):
        cases = [c for c in study.cases if c.method == method]
        draw_method(ax, method, cases, quantity, METHOD_COLORS.get(method) or next(free, "k"))
    if any(not c.regime_matches and plottable(c, quantity) for c in study.cases):
        ax.plot([], [], linestyle="none", marker="o", markerfacecolor="none", markeredgecolor=COLOR_MISMATCH,
                label="regime differs from the reference")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.margins(0.08)  # room for the annotations of the outermost points
    ax.set_xlabel("solve time of one point, s")
    ax.set_ylabel(f"relative error of {quantity}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best")
    ax.set_title(title(study, quantity), fontsize=10)
    missing = not_shown(study, quantity)
    if missing:
        fig.text(0.01, 0.005, "not shown: " + ", ".join(missing), fontsize=7, wrap=True, va="bottom")
    return fig


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    from . import work_precision

    return write_plot(PROG, lambda: work_precision(args.csv, args.quantity), args.output, args.dpi,
                      (StudyFileError, VibromapFileError))



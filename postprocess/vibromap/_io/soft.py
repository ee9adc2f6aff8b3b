"""The soft flag and the Hertz validity of a map's cells: add_soft_cells() takes them from the
map's /soft and /hertz_valid, or computes the soft flag by the one definition of a soft motion
for another soft_kcon than the map's. Part of the readers that vibromap._io gathers (import them
from there).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .h5io import VibromapFileError
from .map import SweepMap
from .regimes import (FLAG_NO, FLAG_UNKNOWN, FLAG_YES, HERTZ_KEY, REGIME_PERIODIC, SOFT_FROM_MAP, SOFT_KEY,
                              STABLE_YES)  # fmt: skip


@dataclasses.dataclass
class SoftInfo:
    """What add_soft_cells found: the definition it used and where the soft flag came from."""

    soft_kcon: float
    hertz_limit: float
    soft_source: str  # SOFT_FROM_MAP, or "computed from ..." for another soft_kcon
    overruled: int = 0  # cells the map's /soft calls soft though Hertz-invalid: not soft here

    def rule(self) -> str:
        """The one definition of soft, e.g. "stable periodic with impacts, Hertz-valid, k_con <= 10"."""
        return f"stable periodic with impacts, Hertz-valid, k_con <= {self.soft_kcon:g}"

    def definition(self) -> str:
        """The one definition, as legends name it: "soft: " and the rule."""
        return f"soft: {self.rule()}"

    def invalid_text(self) -> str:
        """e.g. "Hertz-invalid (z_max/R* > 0.05)", with the map's hertz_limit."""
        return f"Hertz-invalid (z_max/R* > {self.hertz_limit:g})"


def periodic_with_impacts(data: dict[str, np.ndarray]) -> np.ndarray:
    """Cells computed whose motion is periodic with k > 0 impacts per period."""
    return (np.asarray(data["done"]) != 0) & (np.asarray(data["regime"]) == REGIME_PERIODIC) & (np.asarray(data["k"]) > 0)


def impact_cells(data: dict[str, np.ndarray]) -> np.ndarray:
    """Cells computed with at least one impact: k_con > 0 where the map stores k_con, else
    z_ratio > 0, else periodic with impacts."""
    done = np.asarray(data["done"]) != 0
    for name in ("k_con", "z_ratio"):
        if name in data:
            values = np.asarray(data[name], dtype=np.float64)
            return done & np.isfinite(values) & (values > 0)
    return periodic_with_impacts(data)


def hertz_validity(sweep: SweepMap) -> np.ndarray:
    """Each cell's Hertz validity from the map's hertz_valid, as int8: 1 valid, 0 invalid
    (z_max/R* > hertz_limit), -1 not computed."""
    done = np.asarray(sweep.data["done"]) != 0
    valid = np.asarray(sweep.data["hertz_valid"]) != 0
    return np.where(done, valid, FLAG_UNKNOWN).astype(np.int8)


def computed_soft(sweep: SweepMap, hertz: np.ndarray, soft_kcon: float) -> np.ndarray:
    """The soft flag by the one definition (is_soft, regime.hpp) with another soft_kcon, cell by
    cell: periodic with impacts, stable == 1 (unknown is not soft), Hertz-valid and
    0 < k_con <= soft_kcon; -1 where not computed. VibromapFileError when the map did not store
    k_con."""
    if "k_con" not in sweep.data:
        raise VibromapFileError(f"{sweep.path}: cannot tell the soft cells for k_con <= {soft_kcon:g}: the map did "
                                "not store k_con")
    k_con = np.asarray(sweep.data["k_con"], dtype=np.float64)
    soft = (periodic_with_impacts(sweep.data) & (np.asarray(sweep.data["stable"]) == STABLE_YES) & (hertz == FLAG_YES)
            & (k_con > 0) & (k_con <= soft_kcon))  # fmt: skip
    done = np.asarray(sweep.data["done"]) != 0
    return np.where(done, soft, FLAG_UNKNOWN).astype(np.int8)


def add_soft_cells(sweep: SweepMap, soft_kcon: float | None = None) -> SoftInfo:
    """Puts each cell's soft flag (data[SOFT_KEY]) and Hertz validity (data[HERTZ_KEY]) into the
    map's data, so that its slices carry them, and says where the soft flag came from: the map's
    /soft for the map's own soft_kcon (the default), else computed from the other datasets for
    the soft_kcon asked for. A cell the map calls soft but Hertz-invalid is not soft here: no
    picture presents an invalid answer as soft."""
    kcon = sweep.soft_kcon if soft_kcon is None else float(soft_kcon)
    hertz = hertz_validity(sweep)
    if kcon == sweep.soft_kcon:
        done = np.asarray(sweep.data["done"]) != 0
        soft, soft_source = np.where(done, sweep.data["soft"], FLAG_UNKNOWN).astype(np.int8), SOFT_FROM_MAP
    else:
        soft, soft_source = computed_soft(sweep, hertz, kcon), "computed from regime, stable, hertz_valid and k_con"
    wrong = (soft == FLAG_YES) & (hertz == FLAG_NO)
    sweep.data[HERTZ_KEY] = hertz
    sweep.data[SOFT_KEY] = np.where(wrong, FLAG_NO, soft).astype(np.int8)
    return SoftInfo(soft_kcon=kcon, hertz_limit=sweep.hertz_limit, soft_source=soft_source, overruled=int(wrong.sum()))

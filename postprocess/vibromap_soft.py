"""The soft flag and the Hertz validity of a map's cells: add_soft_cells() takes them from the
map's /soft and /hertz_valid, or computes them by the one definition of a soft motion for an older
map, or says why it cannot. Part of the readers that vibromap_h5 gathers (import them from there).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vibromap_map import SweepMap
from vibromap_regimes import (FLAG_NO, FLAG_UNKNOWN, FLAG_YES, HERTZ_KEY, REGIME_PERIODIC, SOFT_FROM_MAP, SOFT_KEY,
                              STABLE_YES)  # fmt: skip


@dataclasses.dataclass
class SoftInfo:
    """What add_soft_cells found: the definition it used and where each flag came from."""

    soft_kcon: float
    hertz_limit: float
    soft_source: str  # SOFT_FROM_MAP, "computed from ...", or why it cannot be told
    hertz_source: str  # "from the map's hertz_valid", "from z_ratio <= 0.05", or why it cannot be told
    soft_known: bool
    hertz_known: bool
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


def hertz_validity(sweep: SweepMap) -> tuple[np.ndarray | None, str]:
    """Each cell's Hertz validity as int8 (1 valid, 0 invalid: z_max/R* > hertz_limit, -1 not
    computed or z_ratio NaN) and where it came from: the map's hertz_valid, else z_ratio against
    the map's hertz_limit (0.05 in maps without it); (None, why) when the map holds neither."""
    done = np.asarray(sweep.data["done"]) != 0
    if "hertz_valid" in sweep.data:
        valid = np.asarray(sweep.data["hertz_valid"]) != 0
        return np.where(done, valid, FLAG_UNKNOWN).astype(np.int8), "from the map's hertz_valid"
    if "z_ratio" in sweep.data:
        z = np.asarray(sweep.data["z_ratio"], dtype=np.float64)
        flags = np.select([~done | np.isnan(z), z <= sweep.hertz_limit], [FLAG_UNKNOWN, FLAG_YES], FLAG_NO)
        return flags.astype(np.int8), f"from z_ratio <= {sweep.hertz_limit:g}"
    return None, "the map stores neither hertz_valid nor z_ratio"


def computed_soft(sweep: SweepMap, hertz: np.ndarray | None, soft_kcon: float) -> tuple[np.ndarray | None, str]:
    """The soft flag by the one definition (is_soft, regime.hpp), cell by cell: periodic with
    impacts, stable == 1 (unknown is not soft), Hertz-valid and 0 < k_con <= soft_kcon; -1 where
    not computed. (None, why) when the map lacks what it takes: no guessing."""
    lacking = [what for what, missing in (("k_con", "k_con" not in sweep.data), ("hertz_valid or z_ratio", hertz is None),
                                          ("stable (written before stability was kept)", "stable" in sweep.filled))
               if missing]  # fmt: skip
    if lacking:
        return None, "the map has no /soft, and no " + ", ".join(lacking) + " to compute it from"
    k_con = np.asarray(sweep.data["k_con"], dtype=np.float64)
    soft = (periodic_with_impacts(sweep.data) & (np.asarray(sweep.data["stable"]) == STABLE_YES) & (hertz == FLAG_YES)
            & (k_con > 0) & (k_con <= soft_kcon))  # fmt: skip
    done = np.asarray(sweep.data["done"]) != 0
    source = "hertz_valid" if "hertz_valid" in sweep.data else "z_ratio"
    return np.where(done, soft, FLAG_UNKNOWN).astype(np.int8), f"computed from regime, stable, {source} and k_con"


def add_soft_cells(sweep: SweepMap, soft_kcon: float | None = None) -> SoftInfo:
    """Puts each cell's soft flag (data[SOFT_KEY]) and Hertz validity (data[HERTZ_KEY]) into the
    map's data, so that its slices carry them, and says where they came from. The map's /soft is
    used when it has one and soft_kcon is the map's own (the default); else soft is computed from
    the other datasets (an older map, or another soft_kcon asked for). A cell the map calls soft
    but Hertz-invalid is not soft here: no picture presents an invalid answer as soft. A flag
    that cannot be told is left out of data, and SoftInfo says why."""
    kcon = sweep.soft_kcon if soft_kcon is None else float(soft_kcon)
    hertz, hertz_source = hertz_validity(sweep)
    if "soft" in sweep.data and kcon == sweep.soft_kcon:
        done = np.asarray(sweep.data["done"]) != 0
        soft, soft_source = np.where(done, sweep.data["soft"], FLAG_UNKNOWN).astype(np.int8), SOFT_FROM_MAP
    else:
        soft, soft_source = computed_soft(sweep, hertz, kcon)
    overruled = 0
    if hertz is not None:
        sweep.data[HERTZ_KEY] = hertz
        if soft is not None:
            wrong = (soft == FLAG_YES) & (hertz == FLAG_NO)
            overruled = int(wrong.sum())
            soft = np.where(wrong, FLAG_NO, soft).astype(np.int8)
    if soft is not None:
        sweep.data[SOFT_KEY] = soft
    return SoftInfo(soft_kcon=kcon, hertz_limit=sweep.hertz_limit, soft_source=soft_source, hertz_source=hertz_source,
                    soft_known=soft is not None, hertz_known=hertz is not None, overruled=overruled)  # fmt: skip

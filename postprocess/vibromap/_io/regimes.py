"""The codes of a vibromap map's flag datasets (regime, status, stable, soft) and the names of
regimes: regime_labels() names each cell's regime "(n,k)", "chatter", "no-contact",
"not-computed"; regime_counts() counts them in a fixed order. Part of the readers that
vibromap._io gathers (import them from there).
"""

from __future__ import annotations

import numpy as np

# The regime and status flags as map_file.hpp lists them (RegimeKind / SolveStatus order, -1
# first); read_map takes the file's own flag_values/flag_meanings, regime_labels these by default.
REGIME_FLAG_VALUES = tuple(range(-1, 9))
REGIME_FLAG_MEANINGS = (
    "not_computed periodic chatter no_contact permanent_contact quasi_periodic chaotic non_periodic unresolved failed"
)
STATUS_FLAG_VALUES = tuple(range(-1, 4))
STATUS_FLAG_MEANINGS = "not_computed ok budget failed invalid_input"
STABLE_FLAG_VALUES = (-1, 0, 1)
STABLE_FLAG_MEANINGS = "unknown unstable stable"
STABLE_UNKNOWN, STABLE_NO, STABLE_YES = STABLE_FLAG_VALUES  # codes of the stable dataset
REGIME_PERIODIC = 0  # regime code whose label is "(n,k)"
NOT_COMPUTED = "not-computed"
# The soft flag and the Hertz validity of a cell (the map's /soft, add_soft_cells' derived ones).
FLAG_UNKNOWN, FLAG_NO, FLAG_YES = -1, 0, 1
# add_soft_cells' keys in SweepMap.data (so that slices carry them): 1 yes, 0 no, -1 not computed
# or unknown. Their own keys, so that the file's /soft stays as read.
SOFT_KEY, HERTZ_KEY = "soft_flag", "hertz_flag"
SOFT_FROM_MAP = "from the map's /soft"  # SoftInfo.soft_source when the map's own flag is used
# analysis.hertz_limit's default: the limit of a scene that does not set it.
HERTZ_LIMIT_DEFAULT = 0.05
# What a cell's answer is, by the map's steady attribute (analysis.steady).
STEADY_ANSWERS = {
    "follow": "the motion the initial state settles into (follow)",
    "integrate": "the motion the initial state settles into, by brute-force integration (integrate)",
    "shooting": "some stable orbit (shooting), not necessarily the motion from rest",
}


def regime_labels(regime, n, k, meanings: dict[int, str] | None = None, done=None) -> np.ndarray:
    """Names each cell's regime: "(n,k)" for a periodic one, else its flag meaning with '_'
    written '-' ("chatter", "no-contact", "not-computed"); an unknown code gives "regime-<code>".
    Cells with done == 0 (when done is given) are "not-computed" whatever their code."""
    if meanings is None:
        meanings = dict(zip(REGIME_FLAG_VALUES, REGIME_FLAG_MEANINGS.split()))
    regime = np.asarray(regime).astype(np.int64)
    periodic = regime == REGIME_PERIODIC
    n = np.where(periodic, np.broadcast_to(np.asarray(n), regime.shape), 0).astype(np.int64)
    k = np.where(periodic, np.broadcast_to(np.asarray(k), regime.shape), 0).astype(np.int64)
    # Name each distinct (code, n, k) once: maps have many cells but few regimes.
    keys = np.stack([regime.ravel(), n.ravel(), k.ravel()], axis=1)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    names = []
    for code, n_i, k_i in unique.tolist():
        if code == REGIME_PERIODIC and n_i > 0:
            names.append(f"({n_i},{k_i})")
        elif code in meanings:
            names.append(meanings[code].replace("_", "-"))
        else:
            names.append(f"regime-{code}")
    # NOT_COMPUTED in the table makes the str dtype wide enough for the done == 0 overwrite.
    labels = np.array(names + [NOT_COMPUTED], dtype=str)[inverse.reshape(-1)].reshape(regime.shape)
    if done is not None:
        labels[np.broadcast_to(np.asarray(done), regime.shape) == 0] = NOT_COMPUTED
    return labels


def _label_key(label: str, kind_order: dict[str, int]):
    """Sort key: periodic (n,k) by n then k, then the kinds in flag order, not-computed last."""
    if label.startswith("(") and label.endswith(")"):
        try:
            n, k = (int(part) for part in label[1:-1].split(","))
            return (0, n, k, "")
        except ValueError:
            pass
    if label == NOT_COMPUTED:
        return (3, 0, 0, label)
    if label in kind_order:
        return (1, kind_order[label], 0, label)
    return (2, 0, 0, label)


def regime_counts(labels) -> dict[str, int]:
    """label -> number of cells, in a fixed order: (n,k) by n then k, chatter, no-contact, ...
    (flag order), unknown labels, not-computed last."""
    kinds = [meaning.replace("_", "-") for meaning in REGIME_FLAG_MEANINGS.split()]
    kind_order = {kind: i for i, kind in enumerate(kinds)}
    unique, counts = np.unique(np.asarray(labels, dtype=str), return_counts=True)
    pairs = sorted(zip(unique.tolist(), counts.tolist()), key=lambda pair: _label_key(pair[0], kind_order))
    return {label: int(count) for label, count in pairs}

"""The answers of :func:`vibromap.run` and :func:`vibromap.census`: the quantities of their JSON."""

from __future__ import annotations

import copy
import json
from typing import Any, Dict, List


class _Answer:
    """The quantities of a command's JSON answer as attributes (null: None); pickles."""

    __slots__ = ("_data",)

    def __init__(self, data: Dict[str, Any]) -> None:
        self._data = data

    @classmethod
    def from_json(cls, text: str):
        """The answer of the JSON text the command prints."""
        return cls(json.loads(text))

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self._data[name]
        except KeyError:
            quantities = ", ".join(self._data)
            raise AttributeError(f"{type(self).__name__} has no quantity '{name}' (quantities: {quantities})") from None

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self._data))

    def keys(self) -> List[str]:
        """The quantities, in the JSON's order."""
        return list(self._data)

    def to_dict(self) -> Dict[str, Any]:
        """Every quantity, as the JSON's dict (a copy)."""
        return copy.deepcopy(self._data)

    @property
    def json(self) -> str:
        """The quantities as JSON text."""
        return json.dumps(self._data, indent=2)

    def __eq__(self, other: object) -> bool:
        return type(other) is type(self) and self._data == other._data

    __hash__ = None  # type: ignore[assignment]

    def __getstate__(self) -> Dict[str, Any]:
        return self._data

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self._data = state



class Result(_Answer):
    """One solved point: the quantities of ``vibromap run SCENE --format json``, bit for bit.

    Each JSON key is an attribute (``r.k_con``, ``r.regime``, ``r.soft``, ``r.T_con``,
    ``r.impacts``, ``r.floquet``, ...) in SI units, as docs/guide-run.md describes them; a
    number the command writes as null (not computed, or not finite) is None. ``to_dict()``
    gives them all as the JSON's dict, ``json`` the text itself. Results pickle.
    """

    __slots__ = ()

    @property
    def multipliers(self) -> List[complex]:
        """The Floquet multipliers as complex numbers (empty when not computed)."""
        return [complex(m["re"], m["im"]) for m in self._data.get("floquet", [])]

    def __repr__(self) -> str:
        d = self._data
        shown = ("status", "regime", "k_con", "T_con", "F_max", "soft", "stable")
        fields = ", ".join(f"{k}={d[k]!r}" for k in shown if k in d)
        if d.get("message"):
            fields += f", message={d['message']!r}"
        return f"Result({fields}, impacts={len(d.get('impacts', []))})"


class Census(_Answer):
    """The attractors of one point: the quantities of ``vibromap run SCENE --census --format json``.

    ``c.attractors`` lists them, each a dict (regime, k_con, T_con, soft, fraction,
    fraction_stderr, count, from_rest, stable, strobe, ...); ``c.K`` initial states were
    followed, ``c.soft_fraction`` of them to a soft attractor, ``c.unresolved`` and
    ``c.unlisted`` to none listed; docs/guide-census-and-basins.md explains them. With
    ``labels``, ``c.initial_conditions`` and ``c.labels`` give each state and its attractor.
    """

    __slots__ = ()

    def fractions(self) -> Dict[str, float]:
        """Each attractor's basin fraction by its regime label (summed over equal labels)."""
        out: Dict[str, float] = {}
        for a in self._data.get("attractors", []):
            out[a["regime"]] = out.get(a["regime"], 0.0) + a["fraction"]
        return out

    def __repr__(self) -> str:
        d = self._data
        found = ", ".join(f"{a['regime']}: {a['fraction']:.3g}" for a in d.get("attractors", []))
        return f"Census(status={d.get('status')!r}, K={d.get('K')}, attractors=[{found}], soft_fraction={d.get('soft_fraction')!r})"

"""Scenes: one parameter point and how to solve it, read and checked by the C++ scene reader.

A :class:`Scene` is what a scene file (TOML) and ``--set`` overrides give the command line:
every value checked against the one key table of the C++ core, with the same one-line messages.
The keys, their units, ranges, defaults and meanings come from that table too
(:meth:`Scene.keys`), never from a list kept here.
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import dataclass
from typing import Any, Dict, Iterator, List, Optional, Tuple, Union

from . import _core

Value = Union[float, int, bool, str]


@dataclass(frozen=True)
class KeyInfo:
    """One key of a point, as ``vibromap keys`` lists it.

    ``name`` is the full name ("contact.E2"); ``type`` is "real", "integer", "choice" or
    "boolean"; ``allowed`` the allowed values as the command line words them ("> 0");
    ``bounds`` (lo, hi, lo_open, hi_open) for numeric keys; ``choices`` the names a choice key
    takes; ``default`` the value at the default point (derived for a key its partner gives:
    k1 from omega1; None for a solver or analysis key that is unset), ``default_text`` as
    ``vibromap keys`` prints it ("m1*omega1^2" for a derived one); ``partner`` the other key
    of an either-or pair (k1 | omega1).
    """

    name: str
    section: str
    key: str
    type: str
    unit: str
    meaning: str
    allowed: str
    bounds: Tuple[float, float, bool, bool]
    choices: Tuple[str, ...]
    partner: str
    default: Optional[Value]
    default_text: str
    default_given: bool

    def __str__(self) -> str:
        unit = "" if self.unit == "-" else f" ({self.unit})"
        return f"{self.name} = {self.default_text}: {self.meaning}{unit}, {self.allowed}"


_KEYS: Optional[Dict[str, KeyInfo]] = None


def _key_table() -> Dict[str, KeyInfo]:
    global _KEYS
    if _KEYS is None:
        rows = (dict(r, bounds=tuple(r["bounds"]), choices=tuple(r["choices"])) for r in _core.keys())
        _KEYS = {r["name"]: KeyInfo(**r) for r in rows}
    return _KEYS


def _value_text(value: Any) -> str:
    """A Python value as a ``--set`` value: TOML for numbers and booleans, a string as it is.

    A string is read as ``--set`` reads it (as TOML, or else as a string), so ``"rk4"`` and
    ``"1e6"`` mean what they mean on the command line.
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)  # the shortest text that reads back as the same double
    if isinstance(value, str):
        return value
    raise TypeError(f"a key's value must be a number, a bool or a str, not {type(value).__name__}")


def _overrides(keys: Dict[str, Any]) -> List[str]:
    return [f"{name}={_value_text(value)}" for name, value in keys.items()]


_EXACT_INT = 2**53  # an int of at most this size is the same number as a float


def _numbers(keys: Dict[str, Any]) -> Optional[Tuple[List[str], List[float]]]:
    """The keys as (full names, floats) when every key is named in full and every value is a
    number (not a bool, not a str): those the core may set on the point directly."""
    names: List[str] = []
    values: List[float] = []
    for name, value in keys.items():
        if "." not in name or isinstance(value, bool):
            return None
        if isinstance(value, float) or (isinstance(value, int) and -_EXACT_INT <= value <= _EXACT_INT):
            names.append(name)
            values.append(float(value))
        else:
            return None
    return names, values


class Scene:
    """One parameter point and the options to solve it, checked as the command line checks it.

    ``Scene(**{"contact.E2": 1e6})`` starts from the defaults (``vibromap keys``) and sets the
    keys given; ``Scene.from_toml(path)`` reads a scene file; ``scene.with_(...)`` returns a
    changed copy. Keys are named in full ("contact.E2") or by a name one section alone has
    ("E2", "omega"); a key of a pair replaces its partner (``omega2`` replaces ``k2``). A bad
    key or value raises :class:`SceneError` with the command line's message. ``scene[key]``
    is a key's value. Scenes are immutable and pickle (as their TOML text).
    """

    # _origin: (file, --set overrides) that give this scene on the command line, for a scene
    # read from a file and changed by with_(); None for one made otherwise.
    __slots__ = ("_scene", "_origin")

    def __init__(self, **keys: Value) -> None:
        self._scene = _core.Scene.parse("", _core.default_scene_path, _overrides(keys))
        self._origin: Optional[Tuple[str, Tuple[str, ...]]] = None

    @classmethod
    def from_toml(cls, path: Union[str, "os.PathLike[str]"], **keys: Value) -> "Scene":
        """Reads the scene file at ``path`` (TOML), then sets ``keys`` as ``--set`` does."""
        overrides = _overrides(keys)
        return cls._wrap(_core.Scene.load(os.fspath(path), overrides), (os.fspath(path), tuple(overrides)))

    @classmethod
    def from_text(cls, text: str, path: Optional[str] = None) -> "Scene":
        """A scene from TOML text; ``path`` names it in messages (the defaults' path when None)."""
        return cls._wrap(_core.Scene.parse(text, _core.default_scene_path if path is None else path, []))

    @classmethod
    def _wrap(cls, scene: "_core.Scene", origin: Optional[Tuple[str, Tuple[str, ...]]] = None) -> "Scene":
        self = cls.__new__(cls)
        self._scene = scene
        self._origin = origin
        return self

    def with_(self, **keys: Value) -> "Scene":
        """A copy of this scene with ``keys`` set (``--set`` overrides); this one is unchanged.

        Model parameters named in full and set to numbers (``**{"contact.E2": 2e6}``) are set
        on the point directly, with the reader's checks, without reading the scene again; any
        other key, or a value a check refuses, goes through the reader (same values, same
        messages).
        """
        overrides = _overrides(keys)
        origin = (self._origin[0], self._origin[1] + tuple(overrides)) if self._origin else None
        numbers = _numbers(keys)
        if numbers is not None:
            fast = self._scene.with_numbers(numbers[0], numbers[1], overrides)
            if fast is not None:
                return self._wrap(fast, origin)
        return self._wrap(self._scene.with_overrides(overrides), origin)

    @property
    def path(self) -> str:
        """The scene file as named (``"Scene()"`` for a scene made from the defaults)."""
        return self._scene.path

    def to_toml(self) -> str:
        """The scene as TOML: the keys given (after every change), in the key table's order."""
        return self._scene.text

    def __getitem__(self, name: str) -> Optional[Value]:
        """The value of key ``name`` at this point (derived for a pair's other form: k2 from omega2)."""
        return self._scene.get(name)

    @staticmethod
    def keys() -> List[KeyInfo]:
        """Every key of a point, in the order of ``vibromap keys``."""
        return list(_key_table().values())

    @staticmethod
    def key(name: str) -> KeyInfo:
        """The key ``name`` ("contact.E2", or "E2" when one section alone has it)."""
        table = _key_table()
        if name in table:
            return table[name]
        matches = [k for k in table.values() if k.key == name]
        if len(matches) != 1:
            raise KeyError(f"no key '{name}' (or a name several sections have: give section.key)")
        return matches[0]

    def __iter__(self) -> Iterator[str]:
        return iter(_key_table())

    def _settings(self) -> Tuple[str, ...]:
        """The scene's lines but its comments (which name the file and the last overrides)."""
        return tuple(line for line in self.to_toml().splitlines() if line.strip() and not line.startswith("#"))

    def __eq__(self, other: object) -> bool:
        """Scenes are equal when they give the same keys the same values (in the same form)."""
        return isinstance(other, Scene) and self._settings() == other._settings()

    def __hash__(self) -> int:
        return hash(self._settings())

    def __reduce__(self):
        return (Scene.from_text, (self.to_toml(), self.path))

    def __repr__(self) -> str:
        given = [line for line in self._settings() if not line.startswith("[")]
        shown = ", ".join(given[:6]) + (f", ... ({len(given)} keys)" if len(given) > 6 else "")
        return f"<Scene {self.path}: {shown or 'defaults'}>"

"""Opening vibromap's HDF5 files and reading their datasets safely; writing a plot's figure.
Part of the readers that vibromap._io gathers (import them from there).

Every reader raises VibromapFileError with a one-line message (naming the file) when the file is
missing, is not HDF5, is of another format version, lacks what the reader needs, or is damaged.
open_h5(path, kind) checks, before any value is read, the file's format version (the root
attribute `version`, FORMAT_VERSIONS: a file of another version, older or newer, raises
FileVersionError, "FILE: a regime map of format version 0; this vibromap reads version 2 only:
make the file again with this vibromap", the line vibromap itself prints) and then the attribute
checksum vibromap writes into every file (_io/seal.py; "FILE: damaged: its attributes fail
their checksum (...)"); read_dataset names a chunk that fails its Fletcher32 checksum or is
missing from its chunk index, and whatever else h5py raises while reading a damaged or truncated
file inside `with open_h5(path, kind) as f:` becomes one line too. Scripts turn that into exit
status 2. There is no reader of an older layout: a file of another version is refused.
"""

from __future__ import annotations

import itertools
import os

import h5py
import numpy as np

from .seal import DamagedAttributes, check_heaps, check_seal

# The format version of each kind of file vibromap writes and reads, as
# include/vibromap/io/file_format.hpp declares them (tests/campaigns/outputs checks that they
# agree): a reader takes its kind's version and no other. A file without the root attribute
# `version` is version 0 (made before vibromap versioned its files).
FORMAT_VERSIONS = {
    "regime map": 2,
    "basins file": 1,
    "optimisation file": 1,
    "trajectory file": 1,
    "branch file": 1,
    "curve file": 1,
    "orbit-diagram file": 1,
}
VERSION_ATTRIBUTE = "version"


class VibromapFileError(Exception):
    """A vibromap file cannot be read: missing, not HDF5, or not of the expected layout."""


class FileVersionError(VibromapFileError):
    """A file of another format version than this vibromap reads: one line naming the file and
    both versions (version_refusal)."""


def version_refusal(path: str, kind: str, found: int) -> str:
    """The line vibromap prints for a file of kind `kind` at version `found` (file_format.cpp)."""
    article = "an" if kind[0] in "aeiou" else "a"
    return (f"{path}: {article} {kind} of format version {found}; this vibromap reads version "
            f"{FORMAT_VERSIONS[kind]} only: make the file again with this vibromap")


def _text(value) -> str:
    """An HDF5 string attribute as str (h5py gives bytes for fixed-length strings, and keeps the
    bytes of an invalid UTF-8 one as surrogates, which could not be printed: replaced here)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return _text(value.reshape(()).item())
    return str(value).encode("utf-8", errors="surrogateescape").decode("utf-8", errors="replace")


def _scalar(value, path: str, name: str, kind):
    """A numeric scalar attribute as float or int."""
    array = np.asarray(value)
    if array.size != 1 or array.dtype.kind not in "iuf":
        raise VibromapFileError(f"{path}: attribute '{name}' is not a number")
    return kind(array.reshape(()).item())


# What reading a damaged or truncated HDF5 file raises from h5py and numpy (a missing or
# garbled object, a size or type that makes no sense): reported as one line, never a traceback.
READ_ERRORS = (OSError, LookupError, ValueError, TypeError, RuntimeError, ArithmeticError, MemoryError)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


class OpenFile:
    """open_h5's answer, for `with open_h5(path, kind) as f:` (f is the h5py.File). Leaving the
    block closes the file and turns what a damaged file raises there (READ_ERRORS) into
    VibromapFileError naming the file."""

    def __init__(self, file: h5py.File, path: str):
        self.file, self.path = file, path

    def __enter__(self) -> h5py.File:
        return self.file

    def __exit__(self, kind, exc, traceback) -> bool:
        self.file.close()
        if isinstance(exc, READ_ERRORS) and not isinstance(exc, VibromapFileError):
            raise VibromapFileError(f"{self.path}: damaged or not a vibromap file: cannot read it ({_one_line(exc)})") from exc
        return False


def _stored_version(f: h5py.File, path: str, kind: str) -> int:
    """The file's format version: its root attribute `version`, 0 when it has only
    vibromap_version (made before files were versioned); VibromapFileError for a file with
    neither, DamagedAttributes for a version that is not one integer."""
    try:
        if VERSION_ATTRIBUTE not in f.attrs:
            if "vibromap_version" in f.attrs:
                return 0
            raise VibromapFileError(f"{path}: not a vibromap {kind} (no root attribute '{VERSION_ATTRIBUTE}')")
        value = np.asarray(f.attrs[VERSION_ATTRIBUTE])
    except READ_ERRORS as exc:
        raise DamagedAttributes(f"its attributes cannot be read ({_one_line(exc)})") from exc
    if value.size != 1 or value.dtype.kind not in "iu":
        raise DamagedAttributes(f"its attribute '{VERSION_ATTRIBUTE}' is not one integer")
    return int(value.reshape(()).item())


# The root attribute (and its value) that marks a kind of file, and how a file without it is named.
KIND_MARKS = {
    "regime map": ("title", "vibromap regime map", "not a vibromap map file"),
    "curve file": ("vibromap_file", "curves", "not a curve file of vibromap continue --curve"),
}


def _check_kind_mark(f: h5py.File, path: str, kind: str) -> None:
    """VibromapFileError when the file lacks the mark of `kind` (KIND_MARKS): another kind of file,
    whose own version says nothing about this kind's."""
    if kind not in KIND_MARKS:
        return
    name, value, what = KIND_MARKS[kind]
    try:
        have = _text(f.attrs[name]) if name in f.attrs else None
    except READ_ERRORS:
        return
    if have is None and kind == "regime map":
        raise VibromapFileError(f"{path}: {what} (no root attribute '{name}')")
    if have is None:
        raise VibromapFileError(f"{path}: {what} (no root attribute {name} = \"{value}\")")
    if have != value:
        raise VibromapFileError(f"{path}: {what} (its {name} is '{have}')")


def open_h5(path: str, kind: str) -> OpenFile:
    """Opens a vibromap HDF5 file of kind `kind` (a key of FORMAT_VERSIONS) for reading and checks
    it before any value is read: its global heaps and its format version, then its attribute
    checksum (_io/seal.py); or raises VibromapFileError (FileVersionError for another
    version) with a one-line reason."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise VibromapFileError(f"{path}: no such file")
    if os.path.isdir(path):
        raise VibromapFileError(f"{path}: is a directory, not a file")
    try:
        if not h5py.is_hdf5(path):
            raise VibromapFileError(f"{path}: not an HDF5 file")
        f = h5py.File(path, "r")
    except READ_ERRORS as exc:
        if isinstance(exc, VibromapFileError):
            raise
        raise VibromapFileError(f"{path}: cannot open ({_one_line(exc)})") from exc
    try:
        check_heaps(f)
        found = _stored_version(f, path, kind)
        if found != FORMAT_VERSIONS[kind]:
            _check_kind_mark(f, path, kind)  # a file of another kind is named as such, not by its version
            raise FileVersionError(version_refusal(path, kind, found))
        check_seal(f)
    except DamagedAttributes as exc:
        f.close()
        raise VibromapFileError(f"{path}: damaged: {exc}; make it again with vibromap --overwrite") from None
    except VibromapFileError:
        f.close()
        raise
    return OpenFile(f, path)


def _flag_meanings(dataset: h5py.Dataset, path: str) -> dict[int, str]:
    """code -> meaning from a dataset's CF flag_values / flag_meanings."""
    for name in ("flag_values", "flag_meanings"):
        if name not in dataset.attrs:
            raise VibromapFileError(f"{path}: dataset '{dataset.name.lstrip('/')}' has no attribute '{name}'")
    meanings = _text(dataset.attrs["flag_meanings"]).split()
    values = [int(v) for v in np.asarray(dataset.attrs["flag_values"]).ravel()]
    if len(values) != len(meanings):
        raise VibromapFileError(
            f"{path}: dataset '{dataset.name.lstrip('/')}' has {len(values)} flag_values but {len(meanings)} flag_meanings"
        )
    return dict(zip(values, meanings))


def _attribute_value(value):
    """A root attribute as str, int, float or (for arrays) a numpy array."""
    if isinstance(value, (bytes, str)):
        return _text(value)
    array = np.asarray(value)
    if array.dtype.kind in "SUO":
        return _text(value)
    if array.size == 1 and array.ndim <= 1:
        return array.reshape(()).item()
    return array


def _missing_chunk(dataset: h5py.Dataset):
    """The offset of a chunk missing from the chunk index of a dataset whose chunks are all made
    with it (a map's: HDF5 would read fill values there without an error); None when none is.
    Each chunk is looked up as a read looks it up (read_direct_chunk; get_chunk_info_by_coord
    does not compare the whole key, and can find a chunk that a read then misses)."""
    if dataset.chunks is None or dataset.id.get_create_plist().get_alloc_time() != h5py.h5d.ALLOC_TIME_EARLY:
        return None
    for offset in itertools.product(*(range(0, n, c) for n, c in zip(dataset.shape, dataset.chunks))):
        try:
            dataset.id.read_direct_chunk(offset)
        except READ_ERRORS:
            return offset
    return None


def read_dataset(dataset: h5py.Dataset, path: str) -> np.ndarray:
    """The whole dataset as a numpy array, or VibromapFileError naming it when a chunk of it fails
    to read (vibromap's maps checksum every chunk: a damaged byte fails instead of reading wrong)
    or is missing from its chunk index."""
    name = dataset.name.lstrip("/")
    try:
        missing = _missing_chunk(dataset)
    except READ_ERRORS as exc:
        raise VibromapFileError(f"{path}: dataset '{name}' is damaged: its chunk index cannot be read ({_one_line(exc)})") from exc
    if missing is not None:
        raise VibromapFileError(f"{path}: dataset '{name}' is damaged: its chunk at {tuple(int(i) for i in missing)} is "
                                "missing from its chunk index; vibromap sweep --resume recomputes the damaged cells")
    try:
        return np.asarray(dataset[()])
    except OSError as exc:
        name = dataset.name.lstrip("/")
        raise VibromapFileError(
            f"{path}: dataset '{name}' is damaged: a chunk of it fails its checksum or cannot be read ({exc}); "
            "vibromap sweep --resume recomputes the damaged cells"
        ) from exc


def save_figure(fig, path: str, dpi: int) -> None:
    """Writes a matplotlib figure and closes it; VibromapFileError names the path on failure."""
    import matplotlib.pyplot as plt  # only the plotting scripts need matplotlib

    try:
        fig.savefig(path, dpi=dpi)
    except OSError as exc:
        raise VibromapFileError(f"{path}: cannot write ({exc.strerror or exc})") from exc
    finally:
        plt.close(fig)


def write_plot(prog: str, make_figure, output: str, dpi: int, errors: tuple = (VibromapFileError,),
               notes: list[str] | None = None) -> int:  # fmt: skip
    """A plotting script's end: draws make_figure() into output and says so (exit status 0), or
    prints the one-line error of an unreadable input or unwritable output (2). `notes`, which
    make_figure may fill, are printed before the "wrote" line."""
    import sys

    try:
        save_figure(make_figure(), output, dpi)
    except errors as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 2
    for note in notes or []:
        print(f"{prog}: note: {note}")
    print(f"{prog}: wrote {output}")
    return 0

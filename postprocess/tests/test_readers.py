"""vibromap._io gathers the readers of its modules (map, runfiles, curves, ...): every name they
define is importable from vibromap._io as the same object, so that the package's pictures and
scripts import them from one place; postprocess/ holds the package alone (and its tests, build
files and launcher); and no file of postprocess/ is over 600 lines (the house limit)."""
import ast
import glob
import importlib
import os

import conftest
from vibromap import _io as readers


def defined_names(path: str) -> list[str]:
    """The names a module's own top-level statements define (not the ones it imports)."""
    names = []
    for node in ast.parse(open(path, encoding="utf-8").read()).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.append(node.name)
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                names += [t.id for t in (target.elts if isinstance(target, ast.Tuple) else [target])]
    return names


def test_every_name_of_the_reader_modules_is_vibromap_ios():
    missing = []
    for module_name in readers.MODULES:
        module = importlib.import_module(module_name)
        for name in defined_names(module.__file__):
            if getattr(readers, name, None) is not getattr(module, name):
                missing.append(f"{module_name}.{name}")
    assert missing == []
    # The names the scripts and tests use, among them: readers, a private helper, a constant.
    assert readers.read_map.__module__ == "vibromap._io.map"
    assert readers.read_basins.__module__ == "vibromap._io.runfiles"
    assert readers._nearest_index.__module__ == "vibromap._io.slice"
    assert readers.SOFT_KEY == "soft_flag"
    assert "read_map" in readers.__all__ and "_text" not in readers.__all__


def test_the_reader_modules_are_all_the_io_modules_but_seal():
    files = glob.glob(os.path.join(conftest.POSTPROCESS_DIR, "vibromap", "_io", "*.py"))
    names = sorted(f"vibromap._io.{os.path.basename(f)[:-3]}" for f in files)
    assert names == sorted(list(readers.MODULES) + ["vibromap._io.__init__", "vibromap._io.seal"])


def test_postprocess_holds_one_package():
    assert sorted(os.listdir(conftest.POSTPROCESS_DIR)) == sorted(
        ["pyproject.toml", "setup.py", "tests", "vibromap", "vibromap-post"]
        + [n for n in os.listdir(conftest.POSTPROCESS_DIR) if n in ("__pycache__", "build", ".pytest_cache")]
        + [n for n in os.listdir(conftest.POSTPROCESS_DIR) if n.endswith(".egg-info")])


def test_no_postprocess_file_is_over_600_lines():
    files = glob.glob(os.path.join(conftest.POSTPROCESS_DIR, "**", "*.py"), recursive=True)
    files.append(conftest.LAUNCHER)
    lengths = {os.path.relpath(f, conftest.POSTPROCESS_DIR): sum(1 for _ in open(f, encoding="utf-8")) for f in files}
    assert len(lengths) > 40
    assert {name: n for name, n in lengths.items() if n > 600} == {}

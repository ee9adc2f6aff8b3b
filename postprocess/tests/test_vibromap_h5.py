"""vibromap_h5 gathers the readers of its modules (vibromap_map, vibromap_files, ...): every name
they define is importable from vibromap_h5 as the same object, so that scripts and user code keep
`from vibromap_h5 import ...`; and no file of postprocess/ is over 600 lines (the house limit)."""
import ast
import glob
import importlib
import os

import conftest
import vibromap_h5


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


def test_every_name_of_the_reader_modules_is_vibromap_h5s():
    missing = []
    for module_name in vibromap_h5.MODULES:
        module = importlib.import_module(module_name)
        for name in defined_names(module.__file__):
            if getattr(vibromap_h5, name, None) is not getattr(module, name):
                missing.append(f"{module_name}.{name}")
    assert missing == []
    # The names the scripts and tests use, among them: readers, a private helper, a constant.
    assert vibromap_h5.read_map.__module__ == "vibromap_map"
    assert vibromap_h5.read_basins.__module__ == "vibromap_files"
    assert vibromap_h5._nearest_index.__module__ == "vibromap_slice"
    assert vibromap_h5.SOFT_KEY == "soft_flag"
    assert "read_map" in vibromap_h5.__all__ and "_text" not in vibromap_h5.__all__


def test_the_reader_modules_are_all_the_vibromap_modules_but_seal_deps_and_guard():
    files = glob.glob(os.path.join(conftest.POSTPROCESS_DIR, "vibromap_*.py"))
    names = sorted(os.path.basename(f)[:-3] for f in files)
    assert names == sorted(list(vibromap_h5.MODULES) + ["vibromap_deps", "vibromap_guard", "vibromap_h5", "vibromap_seal"])


def test_no_postprocess_file_is_over_600_lines():
    files = glob.glob(os.path.join(conftest.POSTPROCESS_DIR, "*.py")) + [os.path.join(conftest.POSTPROCESS_DIR, "vmpy")]
    files += glob.glob(os.path.join(conftest.POSTPROCESS_DIR, "tests", "*.py"))
    lengths = {os.path.relpath(f, conftest.POSTPROCESS_DIR): sum(1 for _ in open(f, encoding="utf-8")) for f in files}
    assert len(lengths) > 20
    assert {name: n for name, n in lengths.items() if n > 600} == {}

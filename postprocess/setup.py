"""The compiled core, vibromap._core, for `pip install ./postprocess` (the rest is pyproject.toml).

The core is the CMake target vibromap_python (src/python/), made from the same libraries as the
vibromap executable, so pip has CMake build it, without network:
- with VIBROMAP_BUILD_DIR set to a configured build tree of the checkout (cmake -S . -B build),
  the target is built there (nothing to do when it is up to date) and its module taken;
- else the checkout around postprocess/ is configured in pip's build folder for the interpreter
  running pip (tests off) and only the module and the libraries it links are built.
"""

import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

CHECKOUT = Path(__file__).resolve().parent.parent


def configure(build: Path) -> None:
    if not (CHECKOUT / "src" / "python" / "CMakeLists.txt").is_file():
        sys.exit(f"vibromap._core: {CHECKOUT} is not a vibromap checkout; set VIBROMAP_BUILD_DIR to a "
                 "configured CMake build tree of one")
    args = ["cmake", "-S", str(CHECKOUT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DVIBROMAP_BUILD_TESTS=OFF", f"-DVIBROMAP_PYTHON={sys.executable}"]
    if shutil.which("ccache"):
        args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
    subprocess.run(args, check=True)


class CMakeBuild(build_ext):
    """Builds the extension with CMake and copies the module where setuptools packs it."""

    def build_extension(self, ext: Extension) -> None:
        given = os.environ.get("VIBROMAP_BUILD_DIR")
        build = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not given:
            configure(build)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "--target", "vibromap_python", "-j", jobs], check=True)
        built = build / "python" / "vibromap" / ("_core" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            sys.exit(f"vibromap._core: {built} was not made: is {build} configured for {sys.executable} "
                     "(-DVIBROMAP_PYTHON=...), with pybind11 and the Python headers?")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(ext_modules=[Extension("vibromap._core", sources=[])], cmdclass={"build_ext": CMakeBuild})

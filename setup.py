"""Builds canopy's Python package for the interpreter that runs it (pyproject.toml).

The extension is the CMake target ``_canopy`` (tools/python/), configured with this interpreter
as ``Python3_EXECUTABLE`` in a build folder of its own under build/pip/, so a venv, a pyenv or
the system Python each get a module built against their own headers; the pure-Python part is
tools/python/canopy/. Extra CMake arguments: the environment variable CANOPY_CMAKE_ARGS
(e.g. ``-DCANOPY_CUDA=OFF``); CMAKE_CXX_COMPILER_LAUNCHER=ccache is honoured by CMake itself.
CANOPY_BUILD_DIR names an existing build (scripts/build.sh's build/) to take the module from
where that build was configured for this same interpreter (a venv counts as its base Python):
the target is brought up to date there instead of building the library a second time.
"""
import hashlib
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD = ROOT / "build" / "pip"


def version():
    """The version CMakeLists.txt declares (the module's canopy.__version__ is the same)."""
    found = re.search(r"project\(canopy VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not found:
        raise RuntimeError("CMakeLists.txt: no 'project(canopy VERSION ...)'")
    return found.group(1)


def built_for_this_python(folder):
    """Whether the CMake build in ``folder`` found this interpreter (the same real file)."""
    cache = Path(folder) / "CMakeCache.txt"
    if not cache.is_file():
        return False
    found = re.search(r"^_Python3_EXECUTABLE:INTERNAL=(.*)$", cache.read_text(), re.M)
    return bool(found) and os.path.realpath(found.group(1)) == os.path.realpath(sys.executable)


class CMakeBuild(build_ext):
    """Configures and builds the _canopy target, then copies the module where setuptools wants it."""

    def build_extension(self, ext):
        env = dict(os.environ)
        given = env.get("CANOPY_BUILD_DIR")
        if given and built_for_this_python(given):
            folder = Path(given).resolve()
        else:
            if given:
                print(f"setup.py: {given} was not configured for {sys.executable}; building in build/pip/")
            folder = self.configure(env)
        subprocess.run(["cmake", "--build", str(folder), "--target", "_canopy", "canopy_python_files"], check=True,
                       env=env)
        built = list((folder / "python" / "canopy").glob("_canopy*" + (".pyd" if os.name == "nt" else ".so")))
        if len(built) != 1:
            raise RuntimeError(f"expected one _canopy module in {folder / 'python' / 'canopy'}, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)

    @staticmethod
    def configure(env):
        """A CMake folder of this interpreter's own (by its real path: a venv shares its base's)."""
        key = hashlib.sha1(os.path.realpath(sys.executable).encode()).hexdigest()[:8]
        folder = BUILD / f"cmake-{sys.implementation.cache_tag}-{key}"
        args = ["-S", str(ROOT), "-B", str(folder), "-DCMAKE_BUILD_TYPE=Release",
                f"-DPython3_EXECUTABLE={sys.executable}", "-DCANOPY_PYTHON=ON", "-DCANOPY_TESTS=OFF"]
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        try:  # pybind11 installed as a Python package (pip's, or python3-pybind11): its CMake files
            import pybind11
            args.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass  # Debian's pybind11-dev: CMake finds it in /usr/lib/cmake
        args += shlex.split(env.get("CANOPY_CMAKE_ARGS", ""))
        if not shutil.which("nvcc") and os.access("/usr/local/cuda/bin/nvcc", os.X_OK):
            env.setdefault("CUDACXX", "/usr/local/cuda/bin/nvcc")  # as scripts/build.sh does
        subprocess.run(["cmake", *args], check=True, env=env)
        return folder


BUILD.mkdir(parents=True, exist_ok=True)
setup(
    version=version(),
    packages=["canopy"],
    package_dir={"canopy": "tools/python/canopy"},
    ext_modules=[Extension("canopy._canopy", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(BUILD / "setuptools")}, "egg_info": {"egg_base": str(BUILD)}},
    zip_safe=False,
)

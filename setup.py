"""Builds the surfgrow Python package: the extension module with the project's CMake (only the
libraries it needs, Release, portable), the pure-Python files from python/surfgrow.

Environment: SURFGROW_CMAKE_ARGS adds CMake arguments (e.g. -DSURFGROW_NATIVE=ON);
CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs (default: every core).
"""

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def version():
    """The version, from project() in CMakeLists.txt: one place for C++ and Python."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(surfgrow VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        build = Path(self.build_temp).resolve() / "cmake"
        args = [
            "-DCMAKE_BUILD_TYPE=Release",
            "-DSURFGROW_BUILD_PYTHON=ON",
            "-DSURFGROW_BUILD_RENDER=OFF",
            "-DSURFGROW_BUILD_VIEW=OFF",
            "-DSURFGROW_BUILD_CLI=OFF",
            "-DSURFGROW_BUILD_TESTS=OFF",
            "-DSURFGROW_BUILD_BENCHMARKS=OFF",
            "-DSURFGROW_BUILD_EXAMPLES=OFF",
            "-DSURFGROW_INSTALL=OFF",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        try:  # pybind11 from the package index (isolated builds); Debian's is found by CMake
            import pybind11

            args.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass
        args += os.environ.get("SURFGROW_CMAKE_ARGS", "").split()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *args], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_surfgrow", "-j", jobs],
                       check=True)
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = build / "python" / "surfgrow" / f"_surfgrow{suffix}"
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(
    version=version(),
    packages=["surfgrow"],
    package_dir={"": "python"},
    package_data={"surfgrow": ["*.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("surfgrow._surfgrow")],
    cmdclass={"build_ext": CMakeBuild},
    # Not build/: that is the CMake build folder of scripts/build.sh.
    options={"build": {"build_base": "build-pip"}},
    zip_safe=False,
)

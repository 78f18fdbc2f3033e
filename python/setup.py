"""Builds wavejets._wavejets with CMake (python/CMakeLists.txt, on its own), so that the module is
built by one description, whether by the project's CMake build or by pip."""

import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent


def version():
    """The package's version, from its one source: include/CGAL/Wavejets/version.h."""
    for line in (HERE.parent / "include" / "CGAL" / "Wavejets" / "version.h").read_text().splitlines():
        if line.startswith("#define CGAL_WAVEJETS_VERSION_STR"):
            return line.split('"')[1]
    raise RuntimeError("no CGAL_WAVEJETS_VERSION_STR in include/CGAL/Wavejets/version.h")


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        output = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        build = Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        import pybind11
        configure = ["cmake", "-S", str(HERE), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython_EXECUTABLE={sys.executable}", f"-Dpybind11_DIR={pybind11.get_cmake_dir()}",
                     f"-DWAVEJETS_PYTHON_OUTPUT_DIR={output}"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "-j", os.environ.get("WAVEJETS_BUILD_JOBS", "2")], check=True)


setup(version=version(), ext_modules=[CMakeExtension("wavejets._wavejets")], cmdclass={"build_ext": CMakeBuild})

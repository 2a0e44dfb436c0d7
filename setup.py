"""pip's build of the package `erpt` (pyproject.toml): the compiled part comes from the project's
CMake build, configured for the interpreter that runs pip.

The CMake build directory is $ERPT_BUILD_DIR, else build-python<major>.<minor> in the source tree
(one per interpreter: the compiled part is specific to it). A directory configured for another
Python is refused rather than reconfigured.
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def cmake_build_dir():
    given = os.environ.get("ERPT_BUILD_DIR")
    if given:
        return pathlib.Path(given).resolve()
    return ROOT / ("build-python%d.%d" % sys.version_info[:2])


def built_for(build):
    """The (major, minor) the build directory's compiled part is for, or None if not built yet."""
    info = build / "python" / "erpt" / "_build_info.py"
    if not info.exists():
        return None
    values = {}
    exec(info.read_text(), values)
    return tuple(values["python"])


class BuildWithCMake(build_ext):
    def run(self):
        build = cmake_build_dir()
        python = built_for(build)
        if python is None:
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                                   "-DPython_EXECUTABLE=" + sys.executable, "-DERPT_BUILD_BENCHMARKS=OFF",
                                   "-DERPT_MPI=OFF"])
        elif python != tuple(sys.version_info[:2]):
            raise SystemExit("erpt: %s holds a build for Python %d.%d, not this Python %d.%d; set ERPT_BUILD_DIR to "
                             "another directory" % (build, *python, *sys.version_info[:2]))
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_erpt"])
        package = pathlib.Path(self.build_lib) / "erpt"
        package.mkdir(parents=True, exist_ok=True)
        for f in (build / "python" / "erpt").iterdir():
            if f.suffix in (".py", ".so"):
                shutil.copy2(f, package / f.name)
        # The renderer's libraries beside the compiled part, which finds them by its $ORIGIN
        # run path (the OpenImageIO module is loaded from beside the core library).
        for name in ("liberpt_core.so", "liberpt_oiio.so"):
            shutil.copy2((build / name).resolve(), package / name)


class CompiledDistribution(Distribution):
    """A wheel for this interpreter and platform: the package holds compiled code (and setuptools
    runs build_ext, which builds it, only for distributions that have some)."""

    def has_ext_modules(self):
        return True


# setuptools' own staging goes to build-setuptools/, apart from the CMake build in build/.
setup(cmdclass={"build_ext": BuildWithCMake}, distclass=CompiledDistribution, packages=[], zip_safe=False,
      options={"build": {"build_base": "build-setuptools"}})

"""pip's build of the package (python/pyproject.toml holds the metadata): records the path of
libperifem.so.0 found now ($PERIFEM_LIBRARY, else the libdir of `pkg-config perifem`) in
perifem/_library_path.py, which the package loads first (perifem/_library.py)."""
import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py


def _library_now():
    path = os.environ.get("PERIFEM_LIBRARY")
    if not path and shutil.which("pkg-config"):
        out = subprocess.run(["pkg-config", "--variable=libdir", "perifem"], capture_output=True, text=True)
        if out.returncode == 0 and out.stdout.strip():
            path = os.path.join(out.stdout.strip(), "libperifem.so.0")
    return os.path.abspath(path) if path and os.path.exists(path) else None


class BuildPy(build_py):
    def run(self):
        super().run()
        path = _library_now()
        target = os.path.join(self.build_lib, "perifem", "_library_path.py")
        if path:
            with open(target, "w") as f:
                f.write("LIBRARY = %r\n" % path)
        elif os.path.exists(target):  # (a stale record from an earlier build)
            os.remove(target)


setup(cmdclass={"build_py": BuildPy})

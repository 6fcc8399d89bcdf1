"""Build hook of the straylight package: the C libraries come from the
repository this folder is in, built by its Makefile (`make shared-libs`,
a no-op when they are up to date) and copied into the wheel as
straylight/_lib/lib*.so.0, where they find each other ($ORIGIN rpath).
The Debian packages they link (scripts/install-deps.sh) are not copied.
STRAYLIGHT_BUILD names another build folder (default: <repo>/build)."""
import os
import shutil
import subprocess
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
LIBS = ["stray", "tracer", "diagnose", "review", "frames", "mission", "straycmd"]


class BinaryDistribution(Distribution):
    """The wheel holds native code: tag it for this platform."""

    def has_ext_modules(self):
        return True


class BuildWithLibs(build_py):
    def run(self):
        build = Path(os.environ.get("STRAYLIGHT_BUILD", REPO / "build"))
        if not (REPO / "Makefile").exists():
            raise SystemExit("straylight: build from the repository's python/ "
                             "folder (the C libraries are built there)")
        jobs = os.environ.get("STRAYLIGHT_JOBS", "2")
        subprocess.check_call(["make", "-C", str(REPO), f"-j{jobs}",
                               f"B={os.path.relpath(build, REPO)}",
                               "shared-libs"])
        super().run()
        dest = Path(self.build_lib) / "straylight" / "_lib"
        dest.mkdir(parents=True, exist_ok=True)
        for name in LIBS:
            so = build / "lib" / f"lib{name}.so.0"
            # the file itself under its soname (no links in a wheel)
            shutil.copyfile(os.path.realpath(so), dest / so.name)


setup(cmdclass={"build_py": BuildWithLibs}, distclass=BinaryDistribution)

"""Puts what the quality matrix imports on sys.path: gauss_core from GAUSS_BUILD_DIR (default build/) and
the measurements and mesh reader the tests share (tests/common). Import it before either."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for folder in (os.path.join(ROOT, "tests", "common"),
               os.path.join(os.environ.get("GAUSS_BUILD_DIR", os.path.join(ROOT, "build")), "python")):
    if folder not in sys.path:
        sys.path.insert(0, folder)

"""Run the add-on's pytest suite inside Blender (headless).

    blender -b --factory-startup --python-exit-code 1 -P tests/blender/run_headless.py -- BUILD_DIR [pytest args]

BUILD_DIR (default: <repo>/build) must hold addon/gauss_stylization with the
compiled gauss_core module, as staged by the CMake build. Exits with pytest's
status, so any failure makes Blender exit non-zero.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    build = os.path.abspath(argv[0] if argv else os.path.join(REPO, "build"))
    os.environ["GAUSS_BUILD_DIR"] = build
    import pytest
    # Neither bytecode nor pytest's cache: the suite must not write into the source tree.
    sys.dont_write_bytecode = True
    return int(pytest.main([HERE, "-p", "no:cacheprovider", "-ra", *argv[1:]]))


sys.exit(main())

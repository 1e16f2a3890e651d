"""Shared fixtures: the program of the same build (for files to compare with) and the sources.

ctest sets SCATTERLAB_PROGRAM, SCATTERLAB_SOURCE_DIR and PYTHONPATH (python/CMakeLists.txt); run
by hand, the defaults are build/ beside these sources:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python
"""

import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("SCATTERLAB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PROGRAM = Path(os.environ.get("SCATTERLAB_PROGRAM", SOURCE_DIR / "build" / "sim" / "scatterlab"))


@pytest.fixture(scope="session")
def scenes() -> Path:
    return SOURCE_DIR / "data" / "scenes"


@pytest.fixture(scope="session")
def run_program():
    """Runs the scatterlab program with these arguments; returns the completed process."""

    def run(*args, check=True):
        done = subprocess.run([str(PROGRAM), *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"scatterlab {' '.join(map(str, args))} failed:\n"
                                 f"{done.stdout}{done.stderr}")
        return done

    return run

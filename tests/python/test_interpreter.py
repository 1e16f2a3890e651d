"""The module under interpreters other than the one it was built with: a virtual environment made
from it with --system-site-packages runs it; one without numpy and h5py, or another version of
Python, is told what is missing and how to get it, in one ImportError."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import scatterlab

PACKAGE = Path(scatterlab.__file__).parent


def run_python(python, code, path):
    # In `path` too: `python -c` looks first in its working directory, which may hold the build's
    # own package.
    env = dict(os.environ, PYTHONPATH=str(path))
    return subprocess.run([str(python), *code], capture_output=True, text=True, env=env,
                          cwd=path, timeout=120)


def test_a_virtual_environment_with_system_packages_runs_it(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", "--system-site-packages",
                    str(venv)], check=True, timeout=120)
    python = venv / "bin" / "python"
    done = run_python(python, ["-c", "import scatterlab, sys; r = scatterlab.simulate(photons=2000,"
                               " batches=2, radiance=False); print(sys.prefix, r.attrs['photons_run'])"],
                      PACKAGE.parent)
    assert done.returncode == 0, done.stderr
    prefix, photons = done.stdout.split()
    assert Path(prefix) == venv and photons == "2000"


def test_without_numpy_and_h5py_it_says_so():
    # -S: no site-packages, so neither numpy nor h5py (Debian's are in dist-packages).
    done = run_python(sys.executable, ["-S", "-c", "import scatterlab"], PACKAGE.parent)
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: scatterlab needs numpy and h5py, which ")
    assert "python3-numpy and python3-h5py" in last and "--system-site-packages" in last


def test_a_module_built_for_another_python_says_so(tmp_path):
    copy = tmp_path / "scatterlab"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    for built in copy.glob("_scatterlab.*.so"):
        built.rename(copy / "_scatterlab.cpython-39-x86_64-linux-gnu.so")
    done = run_python(sys.executable, ["-c", "import scatterlab"], tmp_path)
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert "built for another Python" in last and f"-DPython3_EXECUTABLE={sys.executable}" in last

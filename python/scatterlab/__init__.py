"""scatterlab from Python: run the simulator in this process and read its files as numpy arrays.

    import scatterlab
    r = scatterlab.simulate(albedo=0.9, g=0.5, photons=200000, batches=8, seed=3)
    r.tallies["fluence"].mean, r.tallies["fluence"].stderr, r.tallies["fluence"].units
    r.grid["r"].edges                  # bin edges; Tally.edges["r"] the same for one tally
    r.tallies["fluence"].to_xarray()   # named dimensions, bin centres as coordinates
    scatterlab.open("run.h5")          # any file scatterlab wrote, read the same way
    scene = scatterlab.Scene(geometry="sphere", radius=2.0)  # build, print, change and run

Keywords are the scene's keys (data/scenes/*.toml; _scene.py says how a keyword finds its
table); the scene is checked by the same reader as the command line's, and bad input raises
ValueError (scatterlab.InputError) with the same message, naming the field.
"""

from __future__ import annotations

import copy
import inspect
import math
import os
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable


def _check_interpreter() -> None:
    """Says what this interpreter lacks before an import fails with less to go on: numpy and h5py,
    and a compiled module built for its version of Python."""
    import glob
    import importlib.util

    missing = [name for name in ("numpy", "h5py") if importlib.util.find_spec(name) is None]
    if missing:
        raise ImportError(
            f"scatterlab needs {' and '.join(missing)}, which {sys.executable} cannot import: "
            "use Debian's /usr/bin/python3 with python3-numpy and python3-h5py (or a virtual "
            "environment made with --system-site-packages from it), or install them into this "
            "interpreter")
    here = os.path.dirname(__file__)
    tag = f"cpython-{sys.version_info.major}{sys.version_info.minor}-"
    built = [os.path.basename(p) for p in glob.glob(os.path.join(here, "_scatterlab.*.so"))]
    if built and not any(tag in name for name in built):
        raise ImportError(
            f"scatterlab's compiled module here ({', '.join(built)}) was built for another "
            f"Python than {sys.executable} ({sys.version_info.major}.{sys.version_info.minor}): "
            f"build it for this one with cmake -DPython3_EXECUTABLE={sys.executable}")


_check_interpreter()

from . import _scatterlab, models  # noqa: E402 (after the check that explains a failure)
from ._result import Axis, Fit, Result, Tally, read  # noqa: E402
from ._scene import KEY_TABLES, apply_keys, scene_dict, to_toml  # noqa: E402

__all__ = ["simulate", "searchlight", "open", "fit", "models", "Scene", "scene_text", "Result",
           "Tally", "Axis", "Fit", "Progress", "InputError", "KEY_TABLES", "__version__"]
__version__ = _scatterlab.version
InputError = _scatterlab.InputError
InputError.__doc__ = ("Bad input, found before any work (a ValueError): its message names the "
                      "field and what it accepts, as the command line's does.")


def scene_text(scene: str | Path | None = None, geometry: str | None = None,
               **keys: Any) -> str:
    """The TOML scene that ``simulate`` (``geometry=None``) or ``searchlight``
    (``geometry="half_space"``) would run for these keywords."""
    return to_toml(scene_dict(geometry, scene, keys)[1])


@dataclass(frozen=True)
class Progress:
    """How far a call has got: ``done`` of ``total`` units (batches, or bins for ``fit``), the
    seconds since it started, the rate in units per second and the seconds left (NaN until a
    unit is done)."""

    done: int
    total: int
    elapsed: float
    rate: float
    eta: float

    def __str__(self) -> str:
        def duration(seconds: float) -> str:
            if math.isnan(seconds):
                return "--"
            if seconds < 90:
                return f"{seconds:.0f} s"
            return f"{seconds / 60:.0f} min" if seconds < 5400 else f"{seconds / 3600:.1f} h"

        return (f"{self.done}/{self.total}, {self.rate:.3g}/s, {duration(self.elapsed)} elapsed, "
                f"ETA {duration(self.eta)}")


class _Pace:
    """Turns the compiled module's (done, total) into a Progress, timed from the call's start."""

    def __init__(self):
        self.start = time.monotonic()

    def __call__(self, done: int, total: int) -> Progress:
        elapsed = time.monotonic() - self.start
        rate = done / elapsed if done > 0 and elapsed > 0 else math.nan
        eta = (total - done) / rate if done > 0 and elapsed > 0 else math.nan
        return Progress(done, total, elapsed, rate, eta)


class _ProgressLine:
    """progress=True: one line on stderr from the start, rewritten with the rate and ETA as work
    is done, ended when the call ends."""

    def __init__(self, what: str):
        self.what = what
        self.pace = _Pace()
        print(f"scatterlab: {what}: started", end="", file=sys.stderr, flush=True)

    def __call__(self, done: int, total: int) -> None:
        print(f"\rscatterlab: {self.what} {self.pace(done, total)}   ", end="", file=sys.stderr,
              flush=True)

    def end(self) -> None:
        print(file=sys.stderr, flush=True)


class _TqdmBar:
    """progress="tqdm": a tqdm bar (Debian: python3-tqdm)."""

    def __init__(self, what: str):
        try:
            import tqdm
        except ImportError:
            raise ValueError('progress: "tqdm" needs the tqdm package (Debian: python3-tqdm); '
                             "accepted without it: True, False, None or a callable") from None
        self.bar = tqdm.tqdm(unit={"batches": " batch", "bins": " bin"}.get(what, what))

    def __call__(self, done: int, total: int) -> None:
        self.bar.total = total
        self.bar.update(done - self.bar.n)

    def end(self) -> None:
        self.bar.close()


def _wants_progress(function) -> bool:
    """Whether a callable takes a third positional argument (or ``*args``): then it gets the
    Progress too."""
    try:
        parameters = inspect.signature(function).parameters.values()
    except (TypeError, ValueError):
        return False
    positional = [p for p in parameters if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return len(positional) >= 3 or any(p.kind == p.VAR_POSITIONAL for p in parameters)


def _progress_of(progress, what: str):
    """The callable the compiled module calls, from the ``progress`` argument: True a line on
    stderr, "tqdm" a tqdm bar, a callable ``f(done, total)`` or ``f(done, total, progress)``,
    the last a Progress with the rate and ETA."""
    if progress is True:
        return _ProgressLine(what)
    if progress == "tqdm":
        return _TqdmBar(what)
    if progress is False or progress is None:
        return None
    if not callable(progress):
        raise ValueError(f"progress: got {progress!r}; accepted: True, \"tqdm\", False, None or "
                         f"a callable ({what}_done, {what}[, Progress])")
    if _wants_progress(progress):
        pace = _Pace()
        return lambda done, total: progress(done, total, pace(done, total))
    return progress


def _end(progress) -> None:
    if isinstance(progress, (_ProgressLine, _TqdmBar)):
        progress.end()


def _run(geometry: str | None, scene, out, progress, model_fluence: bool, keys: dict,
         call: str) -> Result:
    geometry, doc, origin = scene_dict(geometry, scene, keys)
    # A file without keywords is read as written, so that its messages point into it.
    text = _scatterlab.read_scene_file(os.fspath(scene)) if scene is not None and not keys \
        else to_toml(doc)
    command = f"python: scatterlab.{call}(" + ", ".join(
        [f"scene={str(scene)!r}"] * (scene is not None)
        + [f"{k}={v!r}" for k, v in keys.items()]) + ")"
    return _run_text(text, origin, geometry, doc, out, progress, model_fluence, command)


def _run_text(text: str, origin: str, geometry: str, doc: dict, out, progress,
              model_fluence: bool, command: str) -> Result:
    progress = _progress_of(progress, "batches")
    # The file goes to out=, else to the scene's output.path, else to a temporary file that is
    # read back whole and removed.
    if out is None:
        out = doc.get("output", {}).get("path")
    temporary = out is None
    if temporary:
        fd, out = tempfile.mkstemp(suffix=".h5", prefix="scatterlab-")
        os.close(fd)
    try:
        _scatterlab.run_scene(text, origin, geometry, os.fspath(out), command, model_fluence,
                              progress)
        result = read(out)
    finally:
        _end(progress)
        if temporary and os.path.exists(out):
            os.remove(out)
    if temporary:
        result.path = None
    return result


class Scene:
    """A scene to build, print, change and run, of any geometry::

        scene = scatterlab.Scene(geometry="slab", layers=[{"thickness": 1, "albedo": 0.9}])
        print(scene)                       # its TOML, as `scatterlab simulate FILE` reads it
        scene.set(photons=1e6, seed=7)     # keywords as simulate's; returns the scene
        result = scene.run(out="slab.h5")  # as simulate(scene=FILE) would

    ``Scene("file.toml", **keys)`` starts from a scene file. Every change is checked at once by
    the program's reader, and a refused one leaves the scene as it was; ``tables`` is the scene
    as a dict of its tables, ``geometry`` its geometry.type."""

    def __init__(self, scene: str | Path | None = None, **keys: Any):
        geometry, tables, origin = scene_dict(None, scene, keys)
        _scatterlab.check_scene(to_toml(tables), origin, geometry)
        self.geometry, self.tables = geometry, tables

    def set(self, **keys: Any) -> "Scene":
        """Lays keywords over the scene (a dict merges into its table key by key)."""
        tables = copy.deepcopy(self.tables)
        geometry = apply_keys(tables, None, keys)
        _scatterlab.check_scene(to_toml(tables), "keywords", geometry)
        self.geometry, self.tables = geometry, tables
        return self

    def run(self, *, out: str | Path | None = None,
            progress: bool | str | Callable[..., None] | None = None,
            model_fluence: bool = False) -> Result:
        """Runs the scene in this process; ``out`` and ``progress`` as for ``simulate``,
        ``model_fluence`` as for ``searchlight`` (a half-space only)."""
        return _run_text(str(self), "scatterlab.Scene", self.geometry, self.tables, out,
                         progress, model_fluence, "python: scatterlab.Scene(...).run()")

    def __str__(self) -> str:
        return to_toml(self.tables)

    def __repr__(self) -> str:
        return f"scatterlab.Scene of a {self.geometry} geometry:\n{self}"


def simulate(scene: str | Path | None = None, *, out: str | Path | None = None,
             progress: bool | str | Callable[..., None] | None = None,
             **keys: Any) -> Result:
    """Runs a scene as ``scatterlab simulate`` does, in this process, and returns its Result.

    The infinite medium by default (a pencil beam or ``source="point"``); ``geometry="sphere"``
    (the lit sphere) or ``geometry="slab"`` (the layered slab, ``layers=[{...}, ...]``), or a
    scene file of that geometry, runs that; ``geometry="half_space"`` is ``searchlight``.

    scene:    a TOML scene file to start from; keywords override its keys.
    out:      where the HDF5 file goes (default: the scene's output.path, else a temporary file
              that is removed once read, and Result.path is None).
    progress: True prints the batches done to stderr, with the rate and ETA; "tqdm" draws a
              tqdm bar; a callable gets (batches_done, batches) after every round of batches,
              and a scatterlab.Progress (rate, ETA) too when it takes a third argument. Ctrl-C stops the run within a slice of photons and
              raises KeyboardInterrupt (or runs your SIGINT handler); no file is written.
    keys:     the scene's keys: ``albedo=0.9, g=0.5, photons=2e5, batches=8, seed=3,
              r={"max": 2, "bins": 20}``, or whole tables: ``medium={...}``.

    The run releases the GIL; threads=0 (the default) uses every core, as the program does.
    """
    return _run(None, scene, out, progress, False, keys, "simulate")


def searchlight(scene: str | Path | None = None, *, out: str | Path | None = None,
                progress: bool | str | Callable[..., None] | None = None,
                model_fluence: bool = False, **keys: Any) -> Result:
    """Runs the half-space as ``scatterlab searchlight`` does: a pencil beam on z > 0 behind
    an interface of relative index ``eta`` (Bitterli 2013, §2.3); the models' curves are in
    Result.models. ``model_fluence`` also computes each diffusion model's phi(r, z) (slow:
    about 1 ms per cell and model). Other arguments as for ``simulate``."""
    return _run("half_space", scene, out, progress, model_fluence, keys, "searchlight")


def fit(file: str | Path | Result, *,
        models: str = "sg,sg_free,dexp_paper,dexp,adexp,asg,adexp_ridge,adexp2_ridge",
        csv: str | Path | None = None, quadrature: int = 3, threads: int = 0,
        progress: bool | str | Callable[..., None] | None = None) -> Result:
    """Fits lobe models to every spatial bin of a file's radiance (Vavassori 2013, §4.2), as
    ``scatterlab fit FILE`` does: /fits/<model> is added to the file and a summary CSV written
    (default: FILE-fits.csv). Returns the file read again; its ``fits`` hold the parameters.

    file:       a path, or a Result that has one (simulate(..., out=...)), with a radiance tally.
    models:     comma-separated: sg, sg_free, dexp_paper, dexp, adexp, asg, adexp_ridge,
                adexp2_ridge.
    quadrature: Gauss-Legendre points per angular bin and axis, in [1, 8].
    progress:   as for simulate, in bins: True prints the bins done; a callable gets
                (bins_done, bins[, Progress]). The fits cannot be
                stopped part way: Ctrl-C is raised when they end.
    """
    if isinstance(file, Result):
        if file.path is None:
            raise ValueError("file: a Result read from a temporary file, which is gone; "
                             "accepted: a path, or a Result of simulate(..., out=PATH)")
        file = file.path
    progress = _progress_of(progress, "bins")
    try:
        _scatterlab.fit_file(os.fspath(file), "" if csv is None else os.fspath(csv), models,
                             quadrature, threads, progress)
    finally:
        _end(progress)
    return read(file)


def open(path: str | Path) -> Result:  # noqa: A001 (it opens a file, as io.open does)
    """Reads any file scatterlab wrote (simulate, searchlight, sphere, slab, merge, fit) whole:
    the same Result as ``simulate`` returns."""
    return read(path)

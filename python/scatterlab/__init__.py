"""scatterlab from Python: run the simulator in this process and read its files as numpy arrays.

    import scatterlab
    r = scatterlab.simulate(albedo=0.9, g=0.5, photons=200000, batches=8, seed=3)
    r.tallies["fluence"].mean, r.tallies["fluence"].stderr, r.tallies["fluence"].units
    r.grid["r"].edges                  # bin edges; Tally.edges["r"] the same for one tally
    r.tallies["fluence"].to_xarray()   # named dimensions, bin centres as coordinates
    scatterlab.open("run.h5")          # any file scatterlab wrote, read the same way

Keywords are the scene's keys (data/scenes/*.toml; _scene.py says how a keyword finds its
table); the scene is checked by the same reader as the command line's, and bad input raises
ValueError (scatterlab.InputError) with the same message, naming the field.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path
from typing import Any, Callable

from . import _scatterlab, models
from ._result import Axis, Fit, Result, Tally, read
from ._scene import KEY_TABLES, scene_dict, to_toml

__all__ = ["simulate", "searchlight", "open", "fit", "models", "scene_text", "Result", "Tally",
           "Axis", "Fit", "InputError", "KEY_TABLES", "__version__"]
__version__ = _scatterlab.version
InputError = _scatterlab.InputError


def scene_text(scene: str | Path | None = None, geometry: str | None = None,
               **keys: Any) -> str:
    """The TOML scene that ``simulate`` (``geometry=None``) or ``searchlight``
    (``geometry="half_space"``) would run for these keywords."""
    return to_toml(scene_dict(geometry, scene, keys)[1])


class _ProgressLine:
    """progress=True: one line on stderr, rewritten as work is done, ended when the call ends."""

    def __init__(self, what: str):
        self.what = what
        self.shown = False

    def __call__(self, done: int, total: int) -> None:
        print(f"\rscatterlab: {self.what} {done} of {total}", end="", file=sys.stderr,
              flush=True)
        self.shown = True

    def end(self) -> None:
        if self.shown:
            print(file=sys.stderr, flush=True)


def _progress_of(progress, what: str):
    """The callable the compiled module calls, from the ``progress`` argument."""
    if progress is True:
        return _ProgressLine(what)
    if progress is False or progress is None:
        return None
    if not callable(progress):
        raise ValueError(f"progress: got {progress!r}; accepted: True, False, None or a "
                         f"callable ({what}_done, {what})")
    return progress


def _run(geometry: str | None, scene, out, progress, model_fluence: bool, keys: dict,
         call: str) -> Result:
    geometry, doc, origin = scene_dict(geometry, scene, keys)
    # A file without keywords is read as written, so that its messages point into it.
    text = _scatterlab.read_scene_file(os.fspath(scene)) if scene is not None and not keys \
        else to_toml(doc)
    progress = _progress_of(progress, "batches")
    # The file goes to out=, else to the scene's output.path, else to a temporary file that is
    # read back whole and removed.
    if out is None:
        out = doc.get("output", {}).get("path")
    temporary = out is None
    if temporary:
        fd, out = tempfile.mkstemp(suffix=".h5", prefix="scatterlab-")
        os.close(fd)
    command = f"python: scatterlab.{call}(" + ", ".join(
        [f"scene={str(scene)!r}"] * (scene is not None)
        + [f"{k}={v!r}" for k, v in keys.items()]) + ")"
    try:
        _scatterlab.run_scene(text, origin, geometry, os.fspath(out), command, model_fluence,
                              progress)
        result = read(out)
    finally:
        if isinstance(progress, _ProgressLine):
            progress.end()
        if temporary and os.path.exists(out):
            os.remove(out)
    if temporary:
        result.path = None
    return result


def simulate(scene: str | Path | None = None, *, out: str | Path | None = None,
             progress: bool | Callable[[int, int], None] | None = None,
             **keys: Any) -> Result:
    """Runs a scene as ``scatterlab simulate`` does, in this process, and returns its Result.

    The infinite medium by default (a pencil beam or ``source="point"``); ``geometry="sphere"``
    (the lit sphere) or ``geometry="slab"`` (the layered slab, ``layers=[{...}, ...]``), or a
    scene file of that geometry, runs that; ``geometry="half_space"`` is ``searchlight``.

    scene:    a TOML scene file to start from; keywords override its keys.
    out:      where the HDF5 file goes (default: the scene's output.path, else a temporary file
              that is removed once read, and Result.path is None).
    progress: True prints the batches done to stderr; a callable gets (batches_done, batches)
              after every round of batches. Ctrl-C stops the run and raises KeyboardInterrupt.
    keys:     the scene's keys: ``albedo=0.9, g=0.5, photons=2e5, batches=8, seed=3,
              r={"max": 2, "bins": 20}``, or whole tables: ``medium={...}``.

    The run releases the GIL; threads=0 (the default) uses every core, as the program does.
    """
    return _run(None, scene, out, progress, False, keys, "simulate")


def searchlight(scene: str | Path | None = None, *, out: str | Path | None = None,
                progress: bool | Callable[[int, int], None] | None = None,
                model_fluence: bool = False, **keys: Any) -> Result:
    """Runs the half-space as ``scatterlab searchlight`` does: a pencil beam on z > 0 behind
    an interface of relative index ``eta`` (Bitterli 2013, §2.3); the models' curves are in
    Result.models. ``model_fluence`` also computes each diffusion model's phi(r, z) (slow:
    about 1 ms per cell and model). Other arguments as for ``simulate``."""
    return _run("half_space", scene, out, progress, model_fluence, keys, "searchlight")


def fit(file: str | Path | Result, *,
        models: str = "sg,sg_free,dexp_paper,dexp,adexp,asg,adexp_ridge,adexp2_ridge",
        csv: str | Path | None = None, quadrature: int = 3, threads: int = 0,
        progress: bool | Callable[[int, int], None] | None = None) -> Result:
    """Fits lobe models to every spatial bin of a file's radiance (Vavassori 2013, §4.2), as
    ``scatterlab fit FILE`` does: /fits/<model> is added to the file and a summary CSV written
    (default: FILE-fits.csv). Returns the file read again; its ``fits`` hold the parameters.

    file:       a path, or a Result that has one (simulate(..., out=...)), with a radiance tally.
    models:     comma-separated: sg, sg_free, dexp_paper, dexp, adexp, asg, adexp_ridge,
                adexp2_ridge.
    quadrature: Gauss-Legendre points per angular bin and axis, in [1, 8].
    progress:   True prints the bins done; a callable gets (bins_done, bins). The fits cannot be
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
        if isinstance(progress, _ProgressLine):
            progress.end()
    return read(file)


def open(path: str | Path) -> Result:  # noqa: A001 (it opens a file, as io.open does)
    """Reads any file scatterlab wrote (simulate, searchlight, sphere, slab, merge, fit) whole:
    the same Result as ``simulate`` returns."""
    return read(path)

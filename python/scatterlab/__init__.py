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
from ._result import Axis, Result, Tally, read
from ._scene import KEY_TABLES, scene_dict, to_toml

__all__ = ["simulate", "searchlight", "open", "models", "scene_text", "Result", "Tally",
           "Axis", "InputError", "KEY_TABLES", "__version__"]
__version__ = _scatterlab.version
InputError = _scatterlab.InputError


def scene_text(scene: str | Path | None = None, geometry: str | None = None,
               **keys: Any) -> str:
    """The TOML scene that ``simulate`` (``geometry=None``) or ``searchlight``
    (``geometry="half_space"``) would run for these keywords."""
    return to_toml(scene_dict(geometry, scene, keys)[1])


def _progress_printer(done: int, batches: int) -> None:
    print(f"\rscatterlab: batch {done} of {batches}", end="\n" if done == batches else "",
          file=sys.stderr, flush=True)


def _run(geometry: str | None, scene, out, progress, model_fluence: bool, keys: dict,
         call: str) -> Result:
    geometry, doc, origin = scene_dict(geometry, scene, keys)
    text = to_toml(doc)
    if progress is True:
        progress = _progress_printer
    elif progress is False:
        progress = None
    elif progress is not None and not callable(progress):
        raise ValueError(f"progress: got {progress!r}; accepted: True, False, None or a "
                         f"callable (batches_done, batches)")
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


def open(path: str | Path) -> Result:  # noqa: A001 (scatterlab.open, as the issue names it)
    """Reads any file scatterlab wrote (simulate, searchlight, sphere, slab, merge, fit) whole:
    the same Result as ``simulate`` returns."""
    return read(path)

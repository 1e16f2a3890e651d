"""Reading a scatterlab file (include/scatterlab/io/simulation_file.hpp spells out its layout).

Every run's file holds ``/tallies/NAME/{mean,stderr}`` with attributes ``units``,
``description`` and ``dims`` (``"r,z"``), and ``/grid/AXIS``, the bin *edges* of each axis
(N + 1 of them) with their ``units``. A tally a scene declares (``[[tally]]``) brings its own
axes, ``/tallies/NAME/axes/AXIS``, which stand in for ``/grid``'s: its ``t`` (time of flight) is
in seconds. A dimension with no edges (the slab's ``layer``, a scattering ``order``, a vector
``component``) is numbered 0, 1, ...
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._scatterlab import check_file


def _text(value) -> object:
    """An HDF5 attribute as Python: bytes to str, numpy scalars to Python numbers."""
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.ndarray) and value.dtype.kind in "SO":
        return [_text(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value


@dataclass
class Axis:
    """A grid axis: its bin edges and their units."""

    name: str
    edges: np.ndarray
    units: str

    def __repr__(self) -> str:
        return (f"<scatterlab.Axis {self.name}: {self.edges.size - 1} bins over "
                f"[{self.edges[0]:g}, {self.edges[-1]:g}] {self.units}>")

    @property
    def centres(self) -> np.ndarray:
        """The bins' midpoints."""
        return 0.5 * (self.edges[:-1] + self.edges[1:])


@dataclass
class Tally:
    """One tally: the mean per photon and its standard error, over named dimensions."""

    name: str
    mean: np.ndarray
    stderr: np.ndarray | None
    units: str
    description: str
    dims: tuple[str, ...]
    edges: dict[str, np.ndarray] = field(default_factory=dict)
    edge_units: dict[str, str] = field(default_factory=dict)

    def coords(self, dim: str) -> np.ndarray:
        """The coordinate of ``dim``: bin centres where the grid has edges, else 0, 1, ..."""
        if dim in self.edges:
            e = self.edges[dim]
            return 0.5 * (e[:-1] + e[1:])
        return np.arange(self.mean.shape[self.dims.index(dim)])

    def __repr__(self) -> str:
        shape = " x ".join(map(str, self.mean.shape)) or "scalar"
        dims = f" over ({', '.join(self.dims)})" if self.dims else ""
        return f"<scatterlab.Tally {self.name} [{shape}]{dims} in {self.units}: {self.description}>"

    def to_xarray(self):
        """An ``xarray.Dataset`` with ``mean`` and ``stderr`` over the named dimensions, bin
        centres as coordinates (their ``edges`` and ``units`` in the coordinate's attributes)."""
        import xarray as xr

        coords = {}
        for dim in self.dims:
            attrs = {}
            if dim in self.edges:
                attrs = {"units": self.edge_units.get(dim, ""), "edges": self.edges[dim]}
            coords[dim] = xr.Variable(dim, self.coords(dim), attrs)
        attrs = {"units": self.units, "description": self.description}
        data = {"mean": (self.dims, self.mean, attrs)}
        if self.stderr is not None:
            data["stderr"] = (self.dims, self.stderr, attrs)
        return xr.Dataset(data, coords=coords, attrs={"tally": self.name})


@dataclass
class Fit:
    """One lobe model fitted to every spatial bin (/fits/<model>, fit/lobe_fits_file.hpp):
    ``params[r, z, k]`` named by ``names``, the relative L1 ``error`` and ``error_plane``
    (-1 where not fitted), ``noise``, ``chi2_dof``, ``status`` (its ``legend`` in attrs)."""

    model: str
    names: list[str]
    params: np.ndarray
    error: np.ndarray
    error_plane: np.ndarray
    noise: np.ndarray
    chi2_dof: np.ndarray
    status: np.ndarray
    attrs: dict

    def param(self, name: str) -> np.ndarray:
        """The parameter ``name`` over (r, z)."""
        return self.params[..., self.names.index(name)]


@dataclass
class Result:
    """A scatterlab file read whole: ``tallies``, ``grid`` (axes with their edges),
    ``parameters`` (the run's, as /parameters holds them), ``figures_of_merit``, ``models``
    (``models[model][name]``, a Tally without stderr), ``fits`` (``scatterlab.fit``'s lobe fits,
    by model) and ``attrs`` (provenance: version, command, created, wall_seconds, ...)."""

    path: Path | None
    attrs: dict
    parameters: dict
    grid: dict[str, Axis]
    tallies: dict[str, Tally]
    figures_of_merit: dict[str, float]
    models: dict[str, dict[str, Tally]]
    model_notes: dict[str, str]
    fits: dict[str, Fit] = field(default_factory=dict)

    def to_xarray(self):
        """Every tally as an ``xarray.Dataset``: variables ``NAME`` and ``NAME_stderr``, with
        shared coordinates, the parameters and provenance in its attributes."""
        import xarray as xr

        parts = []
        for name, tally in self.tallies.items():
            ds = tally.to_xarray().rename({"mean": name, "stderr": f"{name}_stderr"})
            ds.attrs = {}
            parts.append(ds)
        # Attributes that agree are kept (each variable's units and description, a shared
        # coordinate's units and edges); the tallies' own dataset attributes were cleared above.
        merged = xr.merge(parts, combine_attrs="drop_conflicts") if parts else xr.Dataset()
        merged.attrs.update({k: v for k, v in self.attrs.items() if _plain(v)})
        merged.attrs.update({f"parameters.{k}": v for k, v in self.parameters.items()
                             if _plain(v)})
        return merged

    def __repr__(self) -> str:
        tallies = ", ".join(f"{n}{list(t.mean.shape)}" for n, t in self.tallies.items())
        return f"<scatterlab.Result {self.path or ''}: {tallies}>"


def _plain(value) -> bool:
    return isinstance(value, (str, int, float, bool))


def _tally(name: str, group, grid: dict[str, Axis], stderr: bool = True) -> Tally:
    """A tally group (mean, stderr) or a model curve (a dataset) as a Tally."""
    attrs = {k: _text(v) for k, v in group.attrs.items()}
    mean = np.asarray(group["mean"][()] if stderr else group[()], dtype=float)
    err = np.asarray(group["stderr"][()], dtype=float) if stderr else None
    dims = tuple(d for d in str(attrs.get("dims", "")).split(",") if d)
    edges, units = {}, {}
    own = group["axes"] if stderr and "axes" in group else {}
    for i, dim in enumerate(dims):
        axis = grid.get(dim)
        if dim in own:  # a declared tally's own axis
            axis = Axis(dim, np.asarray(own[dim][()], dtype=float),
                        str(_text(own[dim].attrs.get("units", ""))))
        if axis is not None and axis.edges.size == mean.shape[i] + 1:
            edges[dim], units[dim] = axis.edges, axis.units
    return Tally(name, mean, err, str(attrs.get("units", "")),
                 str(attrs.get("description", "")), dims, edges, units)


def read(path: str | Path) -> Result:
    """Reads a file written by scatterlab (any command, any geometry) whole into a Result."""
    import h5py

    path = Path(path)
    check_file(os.fspath(path))  # as `scatterlab info` checks it, before h5py reads it
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise ValueError(f"FILE: {path} cannot be read as HDF5 ({e}); accepted: a file written "
                         f"by scatterlab") from None
    with f:
        if _text(f.attrs.get("format")) != "scatterlab":
            raise ValueError(f"FILE: {path} is not a scatterlab HDF5 file (no format = "
                             f"\"scatterlab\" attribute); accepted: a file written by scatterlab")
        attrs = {k: _text(v) for k, v in f.attrs.items()}
        parameters = {}
        if "parameters" in f:
            p = f["parameters"]
            parameters = {k: _text(v) for k, v in p.attrs.items()}
            for name, item in p.items():  # the slab's /parameters/layers/{mu_a, ...}
                if isinstance(item, h5py.Group):
                    parameters[name] = {k: np.asarray(d[()]) for k, d in item.items()}
                else:
                    parameters[name] = np.asarray(item[()])
        grid = {}
        if "grid" in f:
            for name, d in f["grid"].items():
                grid[name] = Axis(name, np.asarray(d[()], dtype=float),
                                  str(_text(d.attrs.get("units", ""))))
        tallies = {name: _tally(name, g, grid) for name, g in f.get("tallies", {}).items()}
        foms = {name: float(d[()]) for name, d in f.get("figures_of_merit", {}).items()}
        models, notes = {}, {}
        for model, g in f.get("models", {}).items():
            if "note" in g.attrs:
                notes[model] = str(_text(g.attrs["note"]))
            # Beside the curves: the HDF5 dimension scales of their axes, which are not curves.
            models[model] = {name: _tally(name, d, grid, stderr=False)
                             for name, d in g.items()
                             if _text(d.attrs.get("CLASS")) != "DIMENSION_SCALE"}
        fits = {}
        for model, g in f.get("fits", {}).items():
            fits[model] = Fit(model, str(_text(g["params"].attrs["names"])).split(","),
                              *(np.asarray(g[name][()]) for name in (
                                  "params", "error", "error_plane", "noise", "chi2_dof",
                                  "status")),
                              {k: _text(v) for k, v in g.attrs.items()}
                              | {"legend": _text(g["status"].attrs.get("legend", ""))})
    return Result(path, attrs, parameters, grid, tallies, foms, models, notes, fits)

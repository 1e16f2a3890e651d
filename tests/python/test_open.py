"""scatterlab.open reads every file the program writes the same way."""

from pathlib import Path

import h5py
import numpy as np
import pytest

import scatterlab


def test_open_every_geometry(tmp_path, run_program, scenes):
    run_program("searchlight", "--photons", 4000, "--batches", 4, "--out", tmp_path / "s.h5")
    run_program("simulate", scenes / "lit-sphere.toml", "--photons", 4000, "--batches", 4,
                "--out", tmp_path / "sphere.h5")
    run_program("simulate", scenes / "skin-slab.toml", "--photons", 4000, "--batches", 4,
                "--out", tmp_path / "slab.h5")
    for name in ("s.h5", "sphere.h5", "slab.h5"):
        r = scatterlab.open(tmp_path / name)
        with h5py.File(tmp_path / name) as f:
            assert set(r.tallies) == set(f["tallies"])
            for tally_name, t in r.tallies.items():
                g = f["tallies"][tally_name]
                assert np.array_equal(t.mean, g["mean"][()])
                assert np.array_equal(t.stderr, g["stderr"][()])
                assert t.units == g.attrs["units"]
                assert t.mean.ndim == len(t.dims)
                for dim, edges in t.edges.items():
                    assert edges.size == t.mean.shape[t.dims.index(dim)] + 1
                    assert np.array_equal(edges, f["grid"][dim][()])
            assert r.parameters["photons"] == 4000
        ds = r.to_xarray()
        assert set(r.tallies) <= set(ds.data_vars)
    s = scatterlab.open(tmp_path / "s.h5")
    assert s.tallies["exitant_radiance"].dims == ("r", "theta_o")
    assert s.models["single_scatter"]["reflectance_single"].mean.shape == (
        s.tallies["reflectance_single"].mean.shape)


def test_open_refuses_other_files(tmp_path):
    with pytest.raises(ValueError, match="^FILE: .*missing.h5"):
        scatterlab.open(tmp_path / "missing.h5")
    with h5py.File(tmp_path / "other.h5", "w") as f:
        f["x"] = 1
    with pytest.raises(ValueError, match="not a scatterlab HDF5 file"):
        scatterlab.open(tmp_path / "other.h5")


def test_open_refuses_what_info_refuses(tmp_path, run_program):
    """A file that contradicts itself, or whose damage crashes HDF5 1.10.8 (tests/fuzz/libhdf5),
    is refused as `scatterlab info` refuses it, before h5py reads it."""
    libhdf5 = Path(__file__).resolve().parents[1] / "fuzz" / "libhdf5"
    for damaged in sorted(libhdf5.glob("*.h5")):
        assert run_program("info", damaged, check=False).returncode == 2, damaged
        with pytest.raises(ValueError, match="^FILE: "):
            scatterlab.open(damaged)
    run_program("simulate", "--photons", 2000, "--batches", 2, "--out", tmp_path / "run.h5")
    with h5py.File(tmp_path / "run.h5", "r+") as f:
        edges = f["grid/r"]
        edges[0] = np.nan
    with pytest.raises(ValueError, match="^FILE: .*grid"):
        scatterlab.open(tmp_path / "run.h5")


def test_files_carry_dimension_scales_for_general_tools(tmp_path, run_program):
    """Without this module: xarray (h5netcdf) and h5py find each axis by its HDF5 dimension scale,
    the bin centres of /grid in its units; a model curve's scale is not read as a curve."""
    import xarray as xr

    path = tmp_path / "half.h5"
    run_program("searchlight", "--photons", 2000, "--batches", 4, "--out", path)
    with h5py.File(path, "r") as f:
        edges = f["grid/r"][()]
        mean = f["tallies/exitant_radiance/mean"]
        assert [d.label for d in mean.dims] == ["r", "theta_o"]
        np.testing.assert_array_equal(mean.dims[0][0][()], 0.5 * (edges[1:] + edges[:-1]))
    with xr.open_dataset(path, engine="h5netcdf", group="tallies/fluence") as ds:
        assert ds["mean"].dims == ("r", "z") and ds["stderr"].dims == ("r", "z")
        np.testing.assert_array_equal(ds["r"].values, 0.5 * (edges[1:] + edges[:-1]))
        assert ds["r"].attrs["units"] == "mfp"
    with xr.open_dataset(path, engine="h5netcdf", group="models/dipole") as ds:
        assert ds["reflectance_multiple"].dims == ("r",)
    result = scatterlab.open(path)
    assert "r" not in result.models["dipole"]
    assert set(result.models["dipole"]) == {"reflectance_multiple", "diffuse_reflectance_multiple"}

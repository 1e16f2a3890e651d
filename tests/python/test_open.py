"""scatterlab.open reads every file the program writes the same way."""

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

"""Declared tallies against time in files and in Python: the shipped time-resolved scene, its
t coordinate in seconds, info's listing, and the temporal point-spread figure."""

import subprocess
import sys

import numpy as np

import scatterlab
from conftest import SOURCE_DIR


def test_time_resolved_scene_reads_with_t_in_seconds(tmp_path, scenes, run_program):
    out = tmp_path / "tr.h5"
    run_program("simulate", scenes / "time-resolved.toml", "--photons", 4000, "--batches", 4,
                "--out", out)
    r = scatterlab.read(out)
    rt = r.tallies["reflectance_rt"]
    assert rt.dims == ("r", "t")
    assert rt.units == "W mm^-2 per J incident"
    assert np.allclose(rt.edges["t"], np.linspace(0.0, 2e-9, 201))
    assert rt.edge_units["t"] == "s" and rt.edge_units["r"] == "mm"
    ds = rt.to_xarray()
    assert ds.t.attrs["units"] == "s"
    assert np.allclose(ds.t.values, np.linspace(0.005e-9, 1.995e-9, 200))
    # Summed over its time bins R(r, t) is the run's own R(r), but for the light later than 2 ns
    # (ring by ring), which is little of it (all rings together).
    steady = r.tallies["reflectance"].mean
    summed = (rt.mean * 1e-11).sum(axis=1)
    assert np.all(summed <= steady * (1 + 1e-12))
    area = np.pi * np.diff(np.linspace(0.0, 10.0, 11) ** 2)
    assert (summed * area).sum() >= 0.95 * (steady * area).sum()
    info = run_program("info", out).stdout
    assert "reflectance_rt" in info and "W mm^-2 per J incident" in info

    figure = tmp_path / "tpsf.png"
    done = subprocess.run([sys.executable, SOURCE_DIR / "scripts" / "tpsf_figure.py", out, figure],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert figure.stat().st_size > 10_000


def test_merge_keeps_a_declared_tallys_own_axes(tmp_path, scenes, run_program):
    runs = []
    for seed in (1, 2):
        runs.append(tmp_path / f"seed{seed}.h5")
        run_program("simulate", scenes / "time-resolved.toml", "--photons", 2000, "--batches", 2,
                    "--seed", seed, "--out", runs[-1])
    run_program("merge", *runs, "--out", tmp_path / "merged.h5")
    merged = scatterlab.read(tmp_path / "merged.h5").tallies["absorbed_t"]
    one = scatterlab.read(runs[0]).tallies["absorbed_t"]
    assert np.array_equal(merged.edges["t"], one.edges["t"])
    assert merged.edge_units["t"] == "s"


def test_declared_tally_from_keywords(tmp_path):
    r = scatterlab.simulate(geometry="half_space", sigma_a=0.1, sigma_s=10, g=0.5,
                            length_unit="mm", photons=2000, batches=2,
                            tally=[{"name": "absorbed_z", "score": "absorbed",
                                    "filters": {"z": {"min": 0, "max": 2, "bins": 4}}}])
    a = r.tallies["absorbed_z"]
    assert a.dims == ("z",) and a.units == "W mm^-1 per W incident"
    # All the absorbed power in 0 < z < 2 mm: its share of the total, which is at most 1.
    assert 0 < (a.mean * 0.5).sum() <= r.tallies["absorbed"].mean[()] * (1 + 1e-12)

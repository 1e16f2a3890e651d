"""scatterlab.fit: the program's lobe fits (fit/lobe_fits_file.hpp), from Python."""

import shutil

import h5py
import numpy as np
import pytest

import scatterlab

SMALL_GRID = dict(r={"max": 1.0, "bins": 2}, z={"min": 0.0, "max": 2.0, "bins": 3})


def test_fit_equals_the_program(tmp_path, run_program):
    r = scatterlab.simulate(photons=20000, batches=4, seed=2, out=tmp_path / "a.h5",
                            **SMALL_GRID)
    shutil.copy(tmp_path / "a.h5", tmp_path / "b.h5")
    calls = []
    fitted = scatterlab.fit(r, models="sg,dexp", progress=lambda d, n: calls.append((d, n)))
    assert set(fitted.fits) == {"sg", "dexp"}
    assert calls and all(n == 6 for _, n in calls)
    assert (tmp_path / "a-fits.csv").exists()
    run_program("fit", tmp_path / "b.h5", "--models", "sg,dexp")
    with h5py.File(tmp_path / "b.h5") as f:
        for model in ("sg", "dexp"):
            fit = fitted.fits[model]
            assert fit.params.shape[:2] == (2, 3)
            assert fit.names == f["fits"][model]["params"].attrs["names"].split(",")
            # Bit for bit: the same fits for any thread count (lobe_fits_file.hpp).
            assert np.array_equal(fit.params, f["fits"][model]["params"][()])
            assert np.array_equal(fit.status, f["fits"][model]["status"][()])
    sg = fitted.fits["sg"]
    assert np.all(sg.param("mu") >= 0.0)
    assert (tmp_path / "a-fits.csv").read_text() == (tmp_path / "b-fits.csv").read_text()


def test_fit_refuses_bad_input(tmp_path):
    r = scatterlab.simulate(photons=2000, batches=2, radiance=False, out=tmp_path / "a.h5",
                            **SMALL_GRID)
    with pytest.raises(ValueError, match="^FILE: .*radiance"):
        scatterlab.fit(r, models="sg")
    with pytest.raises(ValueError, match="sgg"):
        scatterlab.fit(tmp_path / "a.h5", models="sgg")
    with pytest.raises(ValueError, match="^quadrature: "):
        scatterlab.fit(tmp_path / "a.h5", models="sg", quadrature=9)
    with pytest.raises(ValueError, match="^file: "):
        scatterlab.fit(scatterlab.simulate(photons=1000, batches=2, **SMALL_GRID))

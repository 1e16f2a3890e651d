"""scatterlab.models: vectorised, the C++ values, and checks against known numbers."""

import math

import numpy as np
import pytest

from scatterlab import models


def test_h_function_known_values():
    # Chandrasekhar 1960, Table XI (conservative isotropic scattering): H(1) = 2.9078,
    # H(0.5) = 2.0128; H = 1 without scattering; H(0) = 1.
    assert models.h_function(1.0, 1.0) == pytest.approx(2.9078, abs=1e-4)
    assert models.h_function(0.5, 1.0) == pytest.approx(2.0128, abs=1e-4)
    assert np.all(models.h_function(np.linspace(0, 1, 5), 0.0) == 1.0)
    assert np.all(models.h_function(0.0, np.linspace(0, 1, 5)) == 1.0)


def test_h_function_moment_identity():
    # Zeroth moment (Chandrasekhar 1960, §26): int_0^1 H(mu) dmu = (2 / w) (1 - sqrt(1 - w)).
    mu = np.linspace(0.0, 1.0, 2001)
    for w in (0.3, 0.9, 0.99):
        h = models.h_function(mu, w)
        h0 = np.sum(0.5 * (h[1:] + h[:-1]) * np.diff(mu))
        assert h0 == pytest.approx(2.0 / w * (1.0 - math.sqrt(1.0 - w)), rel=1e-6)


def test_functions_broadcast_and_equal_the_scalar_values():
    r = np.array([0.1, 0.5, 1.0, 3.0])
    albedo = np.array([[0.5], [0.9], [0.99]])
    grid = models.better_dipole(r, albedo, g=0.3, eta=1.3)
    assert grid.shape == (3, 4)
    for i, a in enumerate(albedo[:, 0]):
        for j, x in enumerate(r):
            assert grid[i, j] == models.better_dipole(float(x), float(a), 0.3, 1.3)
    assert np.ndim(models.h_function(0.5, 0.9)) == 0


def test_point_source_parts():
    rho = np.geomspace(0.05, 10.0, 30)
    un = models.point_source_exact(rho, 0.7, part="uncollided")
    assert np.allclose(un, np.exp(-rho) / (4 * np.pi * rho**2), rtol=1e-14, atol=0)
    total = models.point_source_exact(rho, 0.7)
    assert np.allclose(total, un + models.point_source_exact(rho, 0.7, part="collided"),
                       rtol=1e-13, atol=0)
    # No scattering: the uncollided light only.
    assert np.array_equal(models.point_source_exact(rho, 0.0, part="collided"), 0 * rho)
    # Far away the discrete mode exp(-rho / nu0) dominates: the log-slope tends to -1 / nu0.
    nu0 = models.discrete_eigenvalue(0.9)
    assert nu0 == pytest.approx(1.0 / math.sqrt(3 * 0.1), rel=0.1)
    far = np.array([40.0, 41.0])
    f = models.point_source_exact(far, 0.9) * far
    assert math.log(f[1] / f[0]) == pytest.approx(-1.0 / nu0, rel=1e-3)


def test_dipole_total_is_the_integral_of_its_profile():
    r = np.concatenate([[0.0], np.geomspace(1e-5, 200.0, 20001)])
    for albedo, g, eta in ((0.9, 0.0, 1.0), (0.99, 0.5, 1.3)):
        rd = models.better_dipole(r, albedo, g, eta) * 2 * np.pi * r
        integral = np.sum(0.5 * (rd[1:] + rd[:-1]) * np.diff(r))
        assert integral == pytest.approx(models.better_dipole_total(albedo, g, eta), rel=1e-5)


def test_half_space_reflectance():
    assert models.half_space_diffuse_reflectance(1.0) == pytest.approx(1.0, abs=1e-12)
    w = np.array([0.5, 0.9])
    assert np.allclose(models.half_space_diffuse_reflectance(w),
                       1 - models.h_function(1.0, w) * np.sqrt(1 - w), rtol=1e-15)


def test_single_scatter_index_matched_isotropic():
    """With eta = 1 and g = 0, R1(r) = sigma_s / (4 pi r) int_0^{pi/2} cos t
    exp(-r cot t (1 + sec t)) dt (half_space_single_scatter.hpp with z = r cot t)."""
    t = np.linspace(1e-9, np.pi / 2 - 1e-12, 400001)
    for r, albedo in ((0.2, 0.9), (1.0, 0.5)):
        f = np.cos(t) * np.exp(-r / np.tan(t) * (1 + 1 / np.cos(t)))
        expected = albedo / (4 * np.pi * r) * np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t))
        assert models.single_scatter(r, albedo) == pytest.approx(expected, rel=1e-6)


def test_out_of_range_names_the_argument():
    with pytest.raises(ValueError, match="albedo"):
        models.h_function(0.5, 1.5)
    with pytest.raises(ValueError, match="mu"):
        models.h_function(np.array([0.5, 2.0]), 0.5)
    with pytest.raises(ValueError, match="eta"):
        models.better_dipole(1.0, 0.9, eta=5.0)
    with pytest.raises(ValueError, match="part"):
        models.point_source_exact(1.0, 0.5, part="scattered")

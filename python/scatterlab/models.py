"""The analytic references, vectorised: every argument broadcasts as numpy does, and each
value is the C++ model's own (include/scatterlab/models/, include/scatterlab/refract/), computed
point by point. Lengths are in mean free paths (sigma_t = 1) unless a sigma_t is taken. A value
out of range raises ValueError (scatterlab.InputError) naming the argument, as the C++ does.
"""

from __future__ import annotations

import numpy as np

from . import _scatterlab


def better_dipole(r, albedo, g=0.0, eta=1.0):
    """Diffuse reflectance R_d(r) of the better dipole (d'Eon 2012, "A better dipole", as
    Vavassori §3.2.3 prints it; models/dipole.hpp): the light scattered at least twice, per unit
    area (mfp^-2) per unit power entering a half-space with relative index ``eta``, HG ``g``."""
    return _scatterlab.better_dipole(r, albedo, g, eta)


def classical_dipole(r, albedo, g=0.0, eta=1.0):
    """Diffuse reflectance R_d(r) of the classical dipole (Jensen et al. 2001 §2.3-2.4;
    Bitterli eqs. 2.22, 2.30, 2.37), per unit area per unit power entering."""
    return _scatterlab.classical_dipole(r, albedo, g, eta)


def better_dipole_fluence(r, z, albedo, g=0.0, eta=1.0):
    """Fluence phi(r, z) of the better dipole in the half-space z >= 0 (Bitterli eq. 2.33 times
    the strength alpha'^2), per unit power entering; +inf at the source point (0, z_r)."""
    return _scatterlab.better_dipole_fluence(r, z, albedo, g, eta)


def better_dipole_total(albedo, g=0.0, eta=1.0):
    """R_dr = int R_d 2 pi r dr of the better dipole, in closed form (Bitterli eqs. 3.1-3.2)."""
    return _scatterlab.better_dipole_total(albedo, g, eta)


def point_source_exact(rho, albedo, part="total"):
    """Exact fluence of an isotropic point source of unit power in an infinite medium that
    scatters isotropically (Case, de Hoffmann & Placzek 1953, §4-§6; Case & Zweifel 1967, §2.5,
    §6; models/point_source_exact.hpp), at distance ``rho`` > 0 mfp, albedo in [0, 1), in
    mfp^-2. ``part``: "total", "collided" (light that collided at least once) or
    "uncollided" (exp(-rho) / (4 pi rho^2))."""
    if part == "total":
        return _scatterlab.point_source_fluence(albedo, rho)
    if part == "collided":
        return _scatterlab.point_source_fluence_collided(albedo, rho)
    if part == "uncollided":
        return _scatterlab.point_source_fluence_uncollided(np.broadcast_arrays(rho, albedo)[0])
    raise ValueError(f"part: got {part!r}; accepted: total, collided, uncollided")


def point_source_shell_average(rho0, rho1, albedo):
    """The same fluence averaged over the shell rho0 <= rho < rho1 (what a Monte Carlo tally
    on spherical shells estimates: fluence_spherical of a point-source run)."""
    return _scatterlab.point_source_fluence_shell_average(albedo, rho0, rho1)


def discrete_eigenvalue(albedo):
    """nu0, the root of 1 = c nu0 artanh(1 / nu0): the diffusion mode decays as
    exp(-rho / nu0) (Case & Zweifel 1967, §2.5)."""
    return _scatterlab.discrete_eigenvalue(albedo)


def h_function(mu, albedo):
    """Chandrasekhar's H-function for isotropic scattering (Chandrasekhar 1960, "Radiative
    Transfer", §26 eq. (41); computed by the closed integral form of §39 eq. (36);
    models/chandrasekhar_h.hpp), mu in [0, 1], albedo in [0, 1]. H(1) = 2.9078 at albedo 1."""
    return _scatterlab.chandrasekhar_h(albedo, mu)


def half_space_diffuse_reflectance(albedo, mu0=1.0):
    """Total diffuse reflectance of an index-matched, isotropically scattering half-space lit
    at mu0 = cos(incidence): 1 - H(mu0) sqrt(1 - albedo) (Chandrasekhar 1960, §47, eqs.
    (40)-(41); van de Hulst 1980, §14.4)."""
    return _scatterlab.half_space_diffuse_reflectance(albedo, mu0)


def single_scatter(r, albedo, g=0.0, eta=1.0, sigma_t=1.0):
    """Exact once-scattered exitance R1(r) of the searchlight half-space, r > 0, per unit area
    (1 / length^2) per unit incident power, after the entry and exit Fresnel transmittances
    (refract/half_space_single_scatter.hpp: an adaptive Gauss-Kronrod integral over depth)."""
    return _scatterlab.single_scatter_exitance(r, albedo, g, eta, sigma_t)

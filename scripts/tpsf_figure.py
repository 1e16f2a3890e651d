#!/usr/bin/env python3
"""The temporal point-spread function R(r, t) of a run, at a few radii, on a log scale.

Usage: scripts/tpsf_figure.py FILE.h5 FIGURE.png [TALLY]

Reads the declared tally TALLY (default "reflectance_rt": score "exitance", filters r and t;
data/scenes/time-resolved.toml) with the Python module and draws four of its rings against the
time of flight, each with its standard error, beside diffusion theory where the file's parameters
give the medium's coefficients: Patterson, Chance & Wilson (1989, Eq. 7: a semi-infinite medium,
source at z0 = 1 / mu_s'), its image source moved to the extrapolated boundary z_b = 2 A D of a
surface of relative index eta, A = (1 + F_dr) / (1 - F_dr) with Egan & Hilgeman's F_dr, as the
classical dipole has it (include/scatterlab/models/boundary_reflection.hpp). Time is in
picoseconds, R in mm^-2 ns^-1 per joule of the pulse.
"""

import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import scatterlab  # noqa: E402

SPEED_OF_LIGHT_MM_PER_S = 299_792_458e3


def patterson(rho, t, mu_a, mu_s_prime, n):
    """Reflectance per mm^2 and per second after a unit impulse: the flux D dphi/dz through the
    surface of the time-resolved dipole, source at z0, image at -(z0 + 2 z_b). With z_b = 0 it is
    Patterson et al. 1989, Eq. 7:
      R = (4 pi D v)^-3/2 t^-5/2 exp(-mu_a v t) (z0 e1 + (z0 + 2 z_b) e2) / 2,
      e_i = exp(-(rho^2 + z_i^2) / (4 D v t))."""
    v = SPEED_OF_LIGHT_MM_PER_S / n
    d = 1.0 / (3.0 * (mu_a + mu_s_prime))
    z0 = 1.0 / mu_s_prime
    f_dr = -1.440 / n ** 2 + 0.710 / n + 0.668 + 0.0636 * n if n > 1.0 else 0.0
    z_image = z0 + 4.0 * (1.0 + f_dr) / (1.0 - f_dr) * d
    spread = 4.0 * d * v * t
    return ((4.0 * math.pi * d * v) ** -1.5 * t ** -2.5 * np.exp(-mu_a * v * t) * 0.5
            * (z0 * np.exp(-(rho ** 2 + z0 ** 2) / spread)
               + z_image * np.exp(-(rho ** 2 + z_image ** 2) / spread)))


def main(argv):
    if len(argv) not in (3, 4):
        sys.exit(__doc__.strip().splitlines()[2])
    result = scatterlab.read(argv[1])
    name = argv[3] if len(argv) == 4 else "reflectance_rt"
    tally = result.tallies[name].to_xarray()
    if tally.t.attrs.get("units") != "s":
        sys.exit(f"{name}: its t is in {tally.t.attrs.get('units')!r}, not seconds")
    length = tally.r.attrs["units"]
    p = result.parameters
    medium = None
    if "sigma_a" in p and "sigma_s" in p and "g" in p:
        medium = (p["sigma_a"], p["sigma_s"] * (1.0 - p["g"]), p.get("eta", 1.0))
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=150)
    t_ps = tally.t.values * 1e12
    for i in np.linspace(0, tally.sizes["r"] - 1, 4).round().astype(int):
        ring = tally.isel(r=i)
        rho = float(ring.r)
        mean = ring["mean"].values * 1e-9  # per ns
        err = ring["stderr"].values * 1e-9
        line = ax.errorbar(t_ps, mean, yerr=err, fmt=".", ms=3, elinewidth=0.6,
                           label=f"Monte Carlo, r = {rho:g} {length}")
        if medium is not None:
            t = np.linspace(t_ps[0], t_ps[-1], 400)[1:] * 1e-12
            ax.plot(t * 1e12, patterson(rho, t, *medium) * 1e-9, color=line[0].get_color(),
                    lw=1, label=f"diffusion, r = {rho:g} {length}")
    ax.set_yscale("log")
    ax.set_xlabel("time of flight t (ps)")
    ax.set_ylabel(f"R(r, t) ({length}$^{{-2}}$ ns$^{{-1}}$ per J incident)")
    ax.set_title(f"Temporal point-spread function ({name}): Monte Carlo ring averages with one\n"
                 "standard error, and diffusion (Patterson et al. 1989, extrapolated boundary)",
                 fontsize=9)
    ax.legend(fontsize=6, ncol=2)
    positive = tally["mean"].values[tally["mean"].values > 0] * 1e-9
    if positive.size:
        ax.set_ylim(positive.min() * 0.5, positive.max() * 2)
    fig.tight_layout()
    fig.savefig(argv[2])
    print(f"wrote {argv[2]}")


if __name__ == "__main__":
    main(sys.argv)

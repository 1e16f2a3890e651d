#!/usr/bin/env python3
"""Figures of scatterlab_bssrdf_comparison's file (bench/bssrdf_comparison/bssrdf_comparison.cpp).

    python3 bench/bssrdf_comparison/plot_comparison.py OUT_DIR

reads OUT_DIR/bssrdf_comparison.h5 and writes, into OUT_DIR:
  bssrdf_images.png   the reference's multiple scattering beside each model's point-cloud image,
                      one exposure for all (sRGB-like display: value x 2^stops, then ^(1/2.2))
  bssrdf_error.png    each model's relative error (model / reference - 1) per pixel, green
                      channel, with the pixels left out (background, the light's reflection) grey
  bssrdf_sweep.png    the second pass's seconds against its relative error, per point count and
                      cluster angle: to the converged cloud (left) and to the reference (right)
and prints the speed-up of clustering at equal error (Bitterli 2013, Fig. 2.9).
"""
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "bssrdf-comparison"
f = h5py.File(os.path.join(out, "bssrdf_comparison.h5"), "r")["comparison"]
ref = f["reference/multiple"][...]  # [channel, y, x]
units = f["reference/multiple"].attrs["units"]
mask = f["reference/mask"][...] > 0
models = ["dipole", "better_dipole", "quantized_diffusion"]
names = {"dipole": "classical dipole", "better_dipole": "better dipole",
         "quantized_diffusion": "quantized diffusion"}
images = {m: f[f"models/{m}/image"][...] for m in models}

# One exposure: the 99th percentile of the reference's largest channel maps to white.
peak = np.percentile(ref.max(axis=0)[mask], 99)


def display(img):
    rgb = np.clip(np.moveaxis(img, 0, -1) / peak, 0, 1) ** (1 / 2.2)
    return rgb


fig, axes = plt.subplots(1, 4, figsize=(13, 3.8))
panels = [("volumetric path tracing\nall orders - order 1, %d paths/pixel" % f.attrs["samples"],
           ref)] + [("point cloud, %s\n%d points, $\\epsilon$ = %g sr" % (
               names[m], f[f"models/{m}"].attrs["points"], f[f"models/{m}"].attrs["cluster_angle"]),
               images[m]) for m in models]
for ax, (title, img) in zip(axes, panels):
    ax.imshow(display(img), interpolation="nearest")
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])
fig.suptitle("%s: multiple scattering; white = %.3g %s" % (
    os.path.basename(f.attrs["scene"]), peak, units),
             fontsize=10)
fig.tight_layout(rect=(0, 0, 1, 0.93))
fig.savefig(os.path.join(out, "bssrdf_images.png"), dpi=120)

fig, axes = plt.subplots(1, 3, figsize=(12, 4.2))
for ax, m in zip(axes, models):
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = images[m][1] / ref[1] - 1.0
    shown = np.ma.masked_where(~mask | ~np.isfinite(rel), rel)
    cmap = plt.get_cmap("RdBu_r").copy()
    cmap.set_bad("0.8")
    im = ax.imshow(shown, cmap=cmap, vmin=-0.5, vmax=0.5, interpolation="nearest")
    a = f[f"models/{m}"].attrs
    ax.set_title("%s\nper pixel |err|: median %.2f, 90th pct %.2f\n4x4 blocks: median %.2f, "
                 "mean signed %+.2f" % (names[m], a["error_median"], a["error_p90"],
                                        a["error_block4_median"], a["error_block4_mean_signed"]),
                 fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])
    fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04, label="model / reference - 1 (green)")
fig.suptitle("Relative error of the point-cloud BSSRDF against volumetric path tracing "
             "(grey: background and the light's reflection, left out)", fontsize=10)
fig.tight_layout()
fig.savefig(os.path.join(out, "bssrdf_error.png"), dpi=120)

s = f["sweep"]
points = s["points"][...]
angle = s["cluster_angle"][...]
seconds = s["seconds_image"][...]
conv = s["converged_median"][...]
refm = s["reference_median"][...]
fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
for ax, err, label in [(axes[0], conv, "median relative error to the converged cloud\n"
                        "(most points, no clustering)"),
                       (axes[1], refm, "median relative error to the reference\n"
                        "(4 x 4 pixel blocks)")]:
    for n in sorted(set(points)):
        sel = (points == n) & (err > 0)
        order = np.argsort(angle[sel])
        ax.plot(seconds[sel][order], err[sel][order], "o-", label="%d points, $\\epsilon$ "
                "from 0 (right) to 1 sr (left)" % n)
    un = (angle == 0) & (err > 0)  # the converged run is 0 against itself
    order = np.argsort(points[un])
    ax.plot(seconds[un][order], err[un][order], "k--", lw=1, label="no clustering ($\\epsilon$ = 0)")
    if ax is axes[0]:
        k = np.flatnonzero((angle == 0) & (points == points.max()))[0]
        ax.axvline(seconds[k], color="0.5", lw=1, ls=":")
        ax.text(seconds[k], ax.get_ylim()[1], " converged:\n %d points,\n $\\epsilon$ = 0" %
                points[k], va="top", fontsize=8, color="0.3")
    ax.set_xscale("log")
    ax.set_yscale("log" if ax is axes[0] else "linear")
    ax.set_xlabel("second pass (image), seconds")
    ax.set_ylabel(label)
    ax.grid(True, which="both", alpha=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("Point-cloud BSSRDF (better dipole): error against run time", fontsize=10)
fig.tight_layout()
fig.savefig(os.path.join(out, "bssrdf_sweep.png"), dpi=120)

# Speed-up at equal error (Fig. 2.9): for each clustered run, the unclustered run time that
# reaches the same error to the converged cloud, interpolated in log-log along the unclustered
# points, over the clustered run's time.
un = (angle == 0) & (conv > 0)
order = np.argsort(points[un])
un_pts = points[un][order]
un_sec = seconds[un][order]
un_err = conv[un][order]
ok = un_err > 0
print("speed-up of clustering at equal error to the converged cloud:")
for k in np.argsort(seconds):
    if angle[k] == 0 or not conv[k] > 0:
        continue
    e = conv[k]
    lx, ly = np.log(un_err[ok])[::-1], np.log(un_sec[ok])[::-1]  # error increasing
    if not (lx[0] <= np.log(e) <= lx[-1]):
        continue
    t_equal = np.exp(np.interp(np.log(e), lx, ly))
    print("  %6d points, eps %5g sr: %.3g s, error %.2e; unclustered at that error %.3g s: "
          "speed-up %.1f" % (points[k], angle[k], seconds[k], e, t_equal, t_equal / seconds[k]))
# Bitterli's Fig. 2.9 (a) against (b): the same points, clustered and not.
n = points.max()
t0 = seconds[(points == n) & (angle == 0)][0]
print("the same %d points, clustered against summed one by one (%.3g s):" % (n, t0))
for k in np.flatnonzero((points == n) & (angle > 0)):
    print("  eps %5g sr: %.3g s, speed-up %.1f, median error to the unclustered image %.1e" % (
        angle[k], seconds[k], t0 / seconds[k], conv[k]))
print("wrote", ", ".join(os.path.join(out, n) for n in
                         ("bssrdf_images.png", "bssrdf_error.png", "bssrdf_sweep.png")))

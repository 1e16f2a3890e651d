#!/usr/bin/env python3
"""An independent Monte Carlo of a layered slab, to hold scatterlab's against.

Usage: independent_slab.py FILE.h5 PHOTONS SEED

Reads the stack of a scatterlab slab file (/parameters/layers, n_above, n_below), runs its own
analog walk in numpy, written from the physics and not from scatterlab's code: free paths in
optical depth carried across interfaces, Fresnel reflection by Born & Wolf's angle form (as MCML's
RFresnel writes it) at every interface whose indices differ, Snell refraction, Henyey-Greenstein
by its textbook inversion and MCML's direction update (Wang, Jacques & Zheng 1995). Prints
R_d, T_t and A per unit incident power with their standard errors, one per line, as
"name value error". Exits 2 on a file that is not a slab.
"""
import sys

import h5py
import numpy as np


def fresnel(cos_i, n1, n2):
    """Unpolarised reflectance and cos of the refracted angle, from n1 into n2."""
    sin_i = np.sqrt(np.maximum(0.0, 1.0 - cos_i * cos_i))
    sin_t = n1 / n2 * sin_i
    r = np.ones_like(cos_i)
    cos_t = np.zeros_like(cos_i)
    ok = sin_t < 1.0
    cos_t[ok] = np.sqrt(1.0 - sin_t[ok] ** 2)
    cap, cam = cos_i * cos_t - sin_i * sin_t, cos_i * cos_t + sin_i * sin_t
    sap, sam = sin_i * cos_t + cos_i * sin_t, sin_i * cos_t - cos_i * sin_t
    with np.errstate(divide="ignore", invalid="ignore"):
        angle_form = 0.5 * sam * sam * (cam * cam + cap * cap) / (sap * sap * cam * cam)
    r[ok] = angle_form[ok]
    normal = ok & (cos_i > 1.0 - 1e-12)
    r[normal] = (((n1 - n2) / (n1 + n2)) ** 2 * np.ones_like(cos_i))[normal]
    return r, cos_t


def run(path, photons, seed):
    with h5py.File(path, "r") as f:
        p = f["parameters"]
        if p.attrs.get("geometry") not in (b"slab", "slab"):
            sys.exit(2)
        stack = p["layers"]
        mu_a, mu_s = stack["mu_a"][:], stack["mu_s"][:]
        g, n, thick = stack["g"][:], stack["n"][:], stack["thickness"][:]
        n_above, n_below = float(p.attrs["n_above"]), float(p.attrs["n_below"])
    count = len(mu_a)
    mu_t = mu_a + mu_s
    albedo = np.where(mu_t > 0, mu_s / np.where(mu_t > 0, mu_t, 1.0), 0.0)
    top = np.concatenate([[0.0], np.cumsum(thick)[:-1]])
    bottom = np.cumsum(thick)
    index = np.concatenate([[n_above], n, [n_below]])  # index[l + 1] is layer l's
    r1 = ((n_above - n[0]) / (n_above + n[0])) ** 2
    rsp, start = r1, 0
    if mu_t[0] == 0 and count > 1:  # a clear first layer, as MCML treats it
        r2 = ((n[0] - n[1]) / (n[0] + n[1])) ** 2
        rsp, start = r1 + (1 - r1) ** 2 * r2 / (1 - r1 * r2), 1

    rng = np.random.default_rng(seed)
    z = np.full(photons, top[start])
    ux, uy, uz = np.zeros(photons), np.zeros(photons), np.ones(photons)
    layer = np.full(photons, start)
    reflected = transmitted = absorbed = 0
    alive = np.arange(photons)
    while alive.size:
        tau = -np.log(1.0 - rng.random(alive.size))
        moving = np.arange(alive.size)
        while moving.size:
            p = alive[moving]
            l, w = layer[p], uz[p]
            ahead = np.where(w > 0, bottom[l], top[l])
            with np.errstate(divide="ignore", invalid="ignore"):
                dist = np.where(w != 0, (ahead - z[p]) / w, np.inf)
                step = np.where(mu_t[l] > 0, tau[moving] / mu_t[l], np.inf)
            collide = step <= dist
            z[p[collide]] += step[collide] * uz[p[collide]]
            p, m, d, l = p[~collide], moving[~collide], dist[~collide], l[~collide]
            tau[m] -= d * mu_t[l]
            down = uz[p] > 0
            z[p] = np.where(down, bottom[l], top[l])
            beyond = l + np.where(down, 1, -1)
            r, cos_t = fresnel(np.abs(uz[p]), index[l + 1], index[beyond + 1])
            bounce = rng.random(p.size) < r
            uz[p[bounce]] *= -1.0
            go = ~bounce
            q, ratio = p[go], index[l[go] + 1] / index[beyond[go] + 1]
            ux[q] *= ratio
            uy[q] *= ratio
            uz[q] = np.copysign(cos_t[go], uz[q])
            out = go & ((beyond < 0) | (beyond == count))
            reflected += np.count_nonzero(out & ~down)
            transmitted += np.count_nonzero(out & down)
            layer[p[go]] = beyond[go]
            moving = m[~out]
        alive = alive[(layer[alive] >= 0) & (layer[alive] < count)]
        l = layer[alive]
        dies = rng.random(alive.size) >= albedo[l]
        absorbed += np.count_nonzero(dies)
        alive, l = alive[~dies], l[~dies]
        gl, xi = g[l], rng.random(alive.size)
        safe = np.where(gl == 0, 1.0, gl)
        temp = (1 - gl * gl) / (1 - gl + 2 * gl * xi)
        cos_theta = np.where(gl == 0, 2 * xi - 1,
                             np.clip((1 + gl * gl - temp * temp) / (2 * safe), -1, 1))
        sin_theta = np.sqrt(1 - cos_theta ** 2)
        psi = 2 * np.pi * rng.random(alive.size)
        cp, sp = np.cos(psi), np.sin(psi)
        x, y, w = ux[alive], uy[alive], uz[alive]
        near = np.abs(w) > 1 - 1e-12
        s = np.sqrt(np.maximum(1 - w * w, 1e-300))
        ux[alive] = np.where(near, sin_theta * cp, sin_theta * (x * w * cp - y * sp) / s + x * cos_theta)
        uy[alive] = np.where(near, sin_theta * sp, sin_theta * (y * w * cp + x * sp) / s + y * cos_theta)
        uz[alive] = np.where(near, cos_theta * np.sign(w), -sin_theta * cp * s + w * cos_theta)
    for name, hits in (("diffuse_reflectance", reflected), ("total_transmittance", transmitted),
                       ("absorbed", absorbed)):
        f = hits / photons
        print(name, (1 - rsp) * f, (1 - rsp) * np.sqrt(f * (1 - f) / photons))


if __name__ == "__main__":
    run(sys.argv[1], int(float(sys.argv[2])), int(sys.argv[3]))

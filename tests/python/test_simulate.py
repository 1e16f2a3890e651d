"""scatterlab.simulate and scatterlab.searchlight: the same files as the program's, the same
errors, and the physics against the exact references."""

import math
import tomllib

import numpy as np
import pytest

import scatterlab
from scatterlab import models


def assert_same_tallies(a, b):
    assert a.tallies.keys() == b.tallies.keys()
    for name, t in a.tallies.items():
        u = b.tallies[name]
        assert t.dims == u.dims and t.units == u.units, name
        # Bit for bit: the run is the program's, on the same seed (batch_runner.hpp).
        assert np.array_equal(t.mean, u.mean), name
        assert np.array_equal(t.stderr, u.stderr), name
    assert a.grid.keys() == b.grid.keys()
    for name, axis in a.grid.items():
        assert np.array_equal(axis.edges, b.grid[name].edges), name


def test_simulate_equals_program_bit_for_bit(tmp_path, run_program):
    run_program("simulate", "--albedo", 0.9, "--g", 0.5, "--photons", 20000, "--batches", 4,
                "--seed", 3, "--out", tmp_path / "cli.h5")
    r = scatterlab.simulate(albedo=0.9, g=0.5, photons=20000, batches=4, seed=3)
    assert r.path is None  # a temporary file, read and removed
    assert_same_tallies(r, scatterlab.open(tmp_path / "cli.h5"))
    fluence = r.tallies["fluence"]
    assert fluence.dims == ("r", "z")
    assert fluence.mean.shape == (15, 40) == fluence.stderr.shape
    assert np.allclose(fluence.edges["r"], np.linspace(0.0, 1.5, 16))
    assert r.parameters["albedo"] == 0.9 and r.parameters["seed"] == 3
    assert r.attrs["command"].startswith("python: scatterlab.simulate(albedo=0.9")


def test_searchlight_equals_program_bit_for_bit(tmp_path, run_program):
    run_program("searchlight", "--albedo", 0.95, "--eta", 1.4, "--photons", 20000,
                "--batches", 4, "--seed", 5, "--out", tmp_path / "cli.h5")
    r = scatterlab.searchlight(albedo=0.95, eta=1.4, photons=20000, batches=4, seed=5,
                               out=tmp_path / "py.h5")
    assert r.path == tmp_path / "py.h5" and r.path.exists()
    assert_same_tallies(r, scatterlab.open(tmp_path / "cli.h5"))
    assert r.parameters["geometry"] == "half_space" and r.parameters["eta"] == 1.4
    assert "better_dipole" in r.models


def test_scene_files_of_every_geometry_equal_the_program(tmp_path, run_program, scenes):
    for scene in ("lit-sphere.toml", "skin-slab.toml", "point-source.toml"):
        run_program("simulate", scenes / scene, "--photons", 4000, "--batches", 4,
                    "--out", tmp_path / f"cli-{scene}.h5")
        r = scatterlab.simulate(scenes / scene, photons=4000, batches=4,
                                out=tmp_path / f"py-{scene}.h5")
        assert_same_tallies(r, scatterlab.open(tmp_path / f"cli-{scene}.h5"))


def test_keywords_run_the_sphere_and_the_slab(tmp_path, run_program):
    sphere = scatterlab.simulate(geometry="sphere", radius=2.0, eta=1.3, albedo=0.8, g=0.3,
                                 source="directional", psi={"bins": 12}, photons=8000,
                                 batches=4, seed=2)
    assert sphere.parameters["geometry"] == "sphere" and sphere.parameters["radius"] == 2.0
    # Each photon ends reflected at entry, exited or absorbed (transport/lit_object.hpp).
    total = sum(float(sphere.tallies[n].mean)
                for n in ("reflected_at_entry", "exited", "absorbed"))
    assert total == pytest.approx(1.0, abs=1e-12)
    assert sphere.tallies["exitance"].dims[0] == "psi"
    assert sphere.tallies["exitance"].edges["psi"].size == 13

    layers = [{"mu_a": 0.1, "mu_s": 10.0, "g": 0.8, "n": 1.4, "thickness": 0.1},
              {"mu_a": 0.5, "mu_s": 20.0, "g": 0.9, "n": 1.4, "thickness": math.inf}]
    slab = scatterlab.simulate(geometry="slab", layers=layers, n_above=1.0, n_below=1.0,
                               photons=4000, batches=4, seed=1, out=tmp_path / "slab.h5")
    assert slab.parameters["geometry"] == "slab"
    scene = tmp_path / "slab.toml"
    scene.write_text(scatterlab.scene_text(geometry="slab", layers=layers, n_above=1.0,
                                           n_below=1.0, photons=4000, batches=4, seed=1))
    run_program("simulate", scene, "--out", tmp_path / "cli.h5")
    assert_same_tallies(slab, scatterlab.open(tmp_path / "cli.h5"))


def test_a_scene_is_built_printed_changed_and_run(tmp_path, run_program):
    layers = [{"mu_a": 0.1, "mu_s": 10.0, "g": 0.8, "n": 1.4, "thickness": 0.1},
              {"mu_a": 0.5, "mu_s": 20.0, "g": 0.9, "n": 1.4, "thickness": math.inf}]
    scene = scatterlab.Scene(geometry="slab", layers=layers, photons=4000, batches=4)
    assert scene.geometry == "slab" and "[[layers]]" in str(scene)
    assert scene.set(seed=1, n_above=1.0) is scene
    assert scene.tables["run"] == {"photons": 4000, "batches": 4, "seed": 1}
    assert tomllib.loads(str(scene)) == scene.tables
    # A refused change names its field and leaves the scene as it was.
    before = str(scene)
    with pytest.raises(ValueError, match=r"^layers\[1\]\.g: "):
        scene.set(layers=[{**layers[0], "g": 1.5}])
    with pytest.raises(ValueError, match=r"^radius: unknown keyword for the geometry 'slab'"):
        scene.set(radius=2.0)
    assert str(scene) == before
    # Its text is the file the program runs, to the same bits.
    (tmp_path / "slab.toml").write_text(str(scene))
    run_program("simulate", tmp_path / "slab.toml", "--out", tmp_path / "cli.h5")
    result = scene.run(out=tmp_path / "py.h5")
    assert_same_tallies(result, scatterlab.open(tmp_path / "cli.h5"))
    # Any geometry: a sphere from keywords alone.
    sphere = scatterlab.Scene(geometry="sphere", radius=2.0, albedo=0.8, photons=2000,
                              batches=2, seed=4)
    assert sphere.run().parameters["radius"] == 2.0
    assert scatterlab.Scene(tmp_path / "slab.toml").tables == scene.tables


def test_bad_input_is_a_value_error_naming_the_field(tmp_path, run_program):
    with pytest.raises(ValueError, match=r"^medium\.albedo: .*accepted"):
        scatterlab.simulate(albedo=1.5, photons=100)
    # The same message as the program's for the same scene.
    scene = tmp_path / "bad.toml"
    scene.write_text("[medium]\nalbedo = 1.5\n")
    program = run_program("simulate", scene, "--out", tmp_path / "x.h5", check=False)
    assert program.returncode != 0
    with pytest.raises(scatterlab.InputError) as raised:
        scatterlab.simulate(scene)
    assert str(raised.value) in program.stderr
    # A file's syntax error too, with its position in the file.
    scene.write_text("[medium]\nalbedo = = 0.5\n")
    program = run_program("simulate", scene, "--out", tmp_path / "x.h5", check=False)
    with pytest.raises(ValueError, match=r"^scene: .*bad\.toml:2:") as raised:
        scatterlab.simulate(scene)
    assert str(raised.value) in program.stderr
    with pytest.raises(ValueError, match=r"^medium\.albdo: "):
        scatterlab.simulate(medium={"albdo": 0.9})
    with pytest.raises(ValueError, match=r"^grid\.r\.bins: "):
        scatterlab.simulate(r={"max": 2, "bins": -3})
    with pytest.raises(ValueError, match=r'^albdo: unknown keyword .*did you mean "albedo"\?'):
        scatterlab.simulate(albdo=0.9)
    # The half-space's reader names the index surface.eta, whichever table gave it.
    with pytest.raises(ValueError, match=r"^surface\.eta: got 50"):
        scatterlab.searchlight(eta=50.0, photons=100)
    with pytest.raises(ValueError, match=r"^incidence_deg: unknown keyword"):
        scatterlab.simulate(incidence_deg=10)  # a searchlight key, not the infinite medium's
    assert not list(tmp_path.glob("*.h5"))


def test_progress_is_called_after_every_round():
    calls = []
    scatterlab.simulate(photons=2000, batches=6, threads=1, radiance=False,
                        progress=lambda done, batches: calls.append((done, batches)))
    assert calls == [(b, 6) for b in range(1, 7)]


def test_progress_gets_the_rate_and_eta_when_it_asks(capsys):
    seen = []
    scatterlab.simulate(photons=20000, batches=4, threads=1, radiance=False,
                        progress=lambda done, total, info: seen.append(info))
    assert [p.done for p in seen] == [1, 2, 3, 4] and all(p.total == 4 for p in seen)
    last = seen[-1]
    assert last.eta == 0 and last.rate > 0 and last.elapsed > 0
    assert abs(last.rate * last.elapsed - 4) < 1e-9  # batches per second over the whole call
    assert str(last).startswith("4/4, ") and "ETA 0 s" in str(last)
    # progress=True: a line at once, then the same figures, on stderr only.
    scatterlab.simulate(photons=20000, batches=4, threads=1, radiance=False, progress=True)
    out, err = capsys.readouterr()
    assert out == "" and err.startswith("scatterlab: batches: started")
    assert err.rstrip().endswith("ETA 0 s") and "scatterlab: batches 4/4, " in err


def test_tqdm_is_named_when_missing_or_drawn():
    try:
        import tqdm  # noqa: F401
    except ImportError:
        with pytest.raises(ValueError, match="python3-tqdm"):
            scatterlab.simulate(photons=2000, batches=2, radiance=False, progress="tqdm")
    else:
        r = scatterlab.simulate(photons=2000, batches=2, radiance=False, progress="tqdm")
        assert r.attrs["batches_done"] == 2


def test_an_exception_in_progress_stops_the_run(tmp_path):
    def fail(done, batches):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        scatterlab.simulate(photons=2000, batches=6, threads=1, progress=fail,
                            out=tmp_path / "x.h5")
    assert not (tmp_path / "x.h5").exists()


def test_point_source_matches_the_exact_solution():
    """Isotropic point source, isotropic scattering: the shell averages of the fluence against
    the exact transport solution (point_source_exact.hpp), within 4.5 sigma everywhere and
    within 2 sigma for most shells (fixed seed)."""
    albedo = 0.8
    r = scatterlab.simulate(source="point", albedo=albedo, g=0.0, radiance=False,
                            fluence=False, flux=False, rho={"max": 4.0, "bins": 20},
                            photons=100000, batches=16, seed=11)
    t = r.tallies["fluence_spherical"]
    e = t.edges["rho"]
    exact = models.point_source_shell_average(e[:-1], e[1:], albedo)
    z = (t.mean - exact) / t.stderr
    assert np.all(np.abs(z) < 4.5), z
    assert np.mean(np.abs(z) < 2.0) > 0.8, z


def test_searchlight_total_matches_chandrasekhar():
    """Index-matched isotropic half-space: total diffuse reflectance 1 - H(1) sqrt(1 - albedo)
    (Chandrasekhar 1960, §47)."""
    albedo = 0.9
    r = scatterlab.searchlight(albedo=albedo, g=0.0, eta=1.0, fluence=False, photons=100000,
                               batches=16, seed=4)
    t = r.tallies["diffuse_reflectance"]
    exact = models.half_space_diffuse_reflectance(albedo, 1.0)
    assert abs(float(t.mean) - exact) < 4.0 * float(t.stderr)


def test_xarray_has_named_dimensions_and_bin_centres():
    r = scatterlab.simulate(photons=2000, batches=4, seed=1)
    ds = r.tallies["fluence"].to_xarray()
    assert ds["mean"].dims == ("r", "z")
    edges = r.grid["z"].edges
    assert np.allclose(ds["z"].values, 0.5 * (edges[1:] + edges[:-1]))
    assert np.array_equal(ds["z"].attrs["edges"], edges)
    assert ds["mean"].attrs["units"] == r.tallies["fluence"].units
    assert np.array_equal(ds["stderr"].values, r.tallies["fluence"].stderr)
    flux = r.tallies["flux"].to_xarray()
    assert flux["mean"].dims[-1] not in r.grid  # the component: numbered, no edges
    whole = r.to_xarray()
    assert np.array_equal(whole["radiance"].values, r.tallies["radiance"].mean)
    assert whole["radiance"].dims == ("r", "z", "theta", "phi")
    assert whole.attrs["parameters.albedo"] == r.parameters["albedo"]
    assert repr(r.tallies["fluence"]) == (
        f"<scatterlab.Tally fluence [15 x 40] over (r, z) in {r.tallies['fluence'].units}: "
        f"{r.tallies['fluence'].description}>")
    assert repr(r.grid["z"]).startswith("<scatterlab.Axis z: 40 bins over [")
    # Each variable keeps its units and description, each coordinate its units and edges.
    for name, tally in r.tallies.items():
        assert whole[name].attrs["units"] == tally.units, name
        assert whole[name].attrs["description"] == tally.description, name
    assert whole["z"].attrs["units"] == r.grid["z"].units
    assert np.array_equal(whole["z"].attrs["edges"], edges)


def test_the_run_releases_the_gil():
    """Another Python thread runs while the simulator does: it could not with the GIL held."""
    import threading

    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1

    # The ticks counted at each round's end (threads=1: a round is one batch). Between two
    # rounds the run holds the GIL only if it never released it.
    at_round = []
    counter = threading.Thread(target=count)
    counter.start()
    try:
        scatterlab.simulate(photons=400000, batches=4, threads=1, radiance=False, seed=1,
                            progress=lambda done, batches: at_round.append(ticks))
    finally:
        done.set()
        counter.join()
    assert len(at_round) == 4
    assert at_round[-1] - at_round[0] > 10000


def test_ctrl_c_stops_the_run(tmp_path):
    import os
    import signal
    import threading
    import time

    # Two batches of 5e8 photons: minutes each. Ctrl-C stops the run within a slice of photons,
    # as on the command line, not at the end of a batch.
    sent = []
    timer = threading.Timer(0.5, lambda: (sent.append(time.monotonic()),
                                          os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            scatterlab.simulate(photons=1e9, batches=2, radiance=False, out=tmp_path / "x.h5")
    finally:
        timer.cancel()
    assert sent and time.monotonic() - sent[0] < 2.0
    assert not (tmp_path / "x.h5").exists()


def test_ctrl_c_runs_the_users_handler(tmp_path):
    import os
    import signal
    import threading

    # A handler of the user's own (a notebook's, a batch system's) gets the signal, and the run,
    # stopped all the same, writes no file.
    calls = []

    def handler(signum, frame):
        calls.append(signum)
        raise RuntimeError("the user's handler")

    previous = signal.signal(signal.SIGINT, handler)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(RuntimeError, match="the user's handler"):
            scatterlab.simulate(photons=1e9, batches=2, radiance=False, out=tmp_path / "x.h5")
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert calls == [signal.SIGINT]
    assert not (tmp_path / "x.h5").exists()


def test_keywords_override_a_scene_file(scenes, tmp_path):
    import tomllib

    text = scatterlab.scene_text(scenes / "point-source.toml", albedo=0.7,
                                 rho={"bins": 50}, photons=2000, batches=2)
    doc = tomllib.loads(text)
    assert doc["medium"] == {"albedo": 0.7, "g": 0.0}
    assert doc["grid"]["rho"] == {"max": 10.0, "bins": 50}  # merged into the file's table
    assert doc["source"]["type"] == "point" and doc["geometry"]["type"] == "infinite"
    r = scatterlab.simulate(scenes / "point-source.toml", albedo=0.7, rho={"bins": 50},
                            photons=2000, batches=2, out=tmp_path / "p.h5")
    assert r.parameters["albedo"] == 0.7 and r.parameters["source"] == "point"
    assert r.tallies["fluence_spherical"].mean.shape == (50,)
    # Without out=, the file goes where the scene's output.path says, as the program's does.
    assert doc["output"]["path"] == "point-source.h5"


def test_sphere_and_slab_without_scattering_match_beer_lambert():
    """No scattering, no interface: what the sphere absorbs is Beer-Lambert along each chord
    averaged over the lit disk, 1 - (2 / R^2) int_0^R u exp(-2 sigma_t u) du; a slab of
    thickness d transmits exp(-mu_a d). Within 4 sigma (fixed seeds)."""
    radius, a = 1.5, 2.0  # a = 2 sigma_t, sigma_t = 1 mfp^-1
    sphere = scatterlab.simulate(geometry="sphere", radius=radius, eta=1.0, albedo=0.0,
                                 source="directional", photons=40000, batches=8, seed=9)
    integral = (1 - math.exp(-a * radius) * (1 + a * radius)) / a**2
    expected = 1 - 2 / radius**2 * integral
    absorbed = sphere.tallies["absorbed"]
    assert float(sphere.tallies["reflected_at_entry"].mean) == 0.0
    assert abs(float(absorbed.mean) - expected) < 4 * float(absorbed.stderr)

    slab = scatterlab.simulate(geometry="slab", n_above=1.0, n_below=1.0,
                               layers=[{"mu_a": 2.0, "mu_s": 0.0, "g": 0.0, "n": 1.0,
                                        "thickness": 0.5}],
                               weighting="analog", photons=40000, batches=8, seed=9)
    t = slab.tallies["total_transmittance"]
    assert abs(float(t.mean) - math.exp(-1.0)) < 4 * float(t.stderr)
    assert float(slab.tallies["diffuse_reflectance"].mean) == 0.0


def test_a_device_or_huge_file_is_refused_before_it_is_read(tmp_path):
    import time

    start = time.monotonic()
    for device in ("/dev/zero", "/dev/urandom", tmp_path):
        with pytest.raises(ValueError, match=r"^scene: "):
            scatterlab.simulate(device)
        with pytest.raises(ValueError, match=r"^scene: "):
            scatterlab.simulate(device, albedo=0.9)  # read in Python, to merge the keywords
    huge = tmp_path / "huge.toml"
    huge.write_text("# padding\n" * 200_000)  # 2 MB, over the 1 MiB a scene may hold
    with pytest.raises(ValueError, match=r"^scene: .*huge\.toml"):
        scatterlab.simulate(huge)
    assert time.monotonic() - start < 10.0


@pytest.mark.parametrize("environment", [{"OMP_THREAD_LIMIT": "1"}, {"OMP_DYNAMIC": "true"}])
def test_threads_that_openmp_withholds_still_run(environment):
    import os
    import subprocess
    import sys

    # A child interpreter: OpenMP reads these variables once, when it starts.
    code = ("import scatterlab\n"
            "r = scatterlab.simulate(photons=4000, batches=8, threads=2, radiance=False)\n"
            "print(r.tallies['absorbed'].mean)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, **environment}, timeout=120)
    assert done.returncode == 0, done.stderr
    assert 0.0 < float(done.stdout) <= 1.0

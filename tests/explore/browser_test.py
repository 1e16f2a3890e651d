#!/usr/bin/env python3
"""The explorer's page in a real browser: headless Chromium (Debian's chromium, chromium-driver and
python3-selenium) against a server this test starts on a free loopback port.

It changes parameters as a user does (typing into the fields, choosing the plot mode), checks that
the values Plotly plots equal the C++ models' within 1e-9 (the dipoles and the exact single
scattering through the Python module `import scatterlab`, quantized diffusion through an API call
of its own), loads a text-file model by dropping a file into the --models folder and pressing
"Reload text models", refuses a bad one with a message naming the file and line, shows a
searchlight file with error bars, shows a refused field's message beside it with the field marked,
the status in error and the plots greyed as stale (and all of it gone once the field is fixed),
checks that the plots' titles name the channel drawn (or none, when "use this medium" made the
three one), and saves screenshots, checked against the expected layout (elements present and
visible, each plot's image not blank), not pixel by pixel.

    browser_test.py SCATTERLAB_PROGRAM SOURCE_DIR SCREENSHOT_DIR   (PYTHONPATH: the build's python/)
"""

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import scatterlab._scatterlab as core  # the compiled models, not the page or the server
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

PROGRAM, SOURCE, SHOTS = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
TOLERANCE = 1e-9
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message, flush=True)


def relative_error(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def start_server(models, open_folder):
    server = subprocess.Popen(
        [str(PROGRAM), "explore", "--port", "0", "--models", str(models), "--open", str(open_folder)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = server.stdout.readline()
    if "http://" not in line:
        server.kill()
        raise SystemExit(f"the server did not start: {line}{server.stderr.read()}")
    url = line.split()[2].rstrip("/") + "/"
    print("server:", url, flush=True)
    return server, url


def post(url, path, body):
    request = urllib.request.Request(url + path.lstrip("/"), data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(request, timeout=30) as answer:
        return json.load(answer)


def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                 "--window-size=1500,1250", "--force-device-scale-factor=1",
                 # WebGL without a GPU (the mesh view): SwiftShader.
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader"):
        options.add_argument(flag)
    driver_path = shutil.which("chromedriver") or "/usr/bin/chromedriver"
    return webdriver.Chrome(service=Service(driver_path), options=options)


def wait_for(driver, script, what, timeout=30):
    try:
        return WebDriverWait(driver, timeout, poll_frequency=0.05).until(
            lambda d: d.execute_script(script))
    except Exception:
        raise SystemExit(f"timed out waiting for {what}; page errors: "
                         f"{driver.execute_script('return window.explore && window.explore.errors')}")


def set_field(driver, element_id, value):
    field = driver.find_element(By.ID, element_id)
    field.clear()
    field.send_keys(str(value))


def plotted(driver, trace_name):
    """The y values Plotly holds for the trace named trace_name (as plotted, after the mode's
    transform), and its x."""
    return driver.execute_script(
        "const t = document.getElementById('profile-plot').data.find(t => t.name === arguments[0]);"
        "return t ? {x: t.x, y: t.y} : null;", trace_name)


# Not blank: the plot drawn to an image by Plotly, in the browser, and the share of its pixels
# that are not background.
INK = """
const done = arguments[arguments.length - 1];
Plotly.toImage(document.getElementById(arguments[0]), {format: 'png', width: 800, height: 400})
  .then(url => { const image = new Image(); image.onload = () => {
    const canvas = document.createElement('canvas'); canvas.width = 800; canvas.height = 400;
    const context = canvas.getContext('2d'); context.drawImage(image, 0, 0);
    const pixels = context.getImageData(0, 0, 800, 400).data; let ink = 0;
    for (let i = 0; i < pixels.length; i += 4) if (pixels[i] + pixels[i + 1] + pixels[i + 2] < 600) ++ink;
    done(ink / (800 * 400)); }; image.src = url; });
"""


def check_layout(driver, name, plots):
    path = SHOTS / f"{name}.png"
    driver.save_screenshot(str(path))
    print("screenshot:", path, flush=True)
    for element_id in ("controls", "preset", "channel-rows", "plot-mode", "models", "timing", *plots):
        element = driver.find_element(By.ID, element_id)
        check(element.is_displayed() and element.size["width"] > 50,
              f"{name}: #{element_id} not visible")
    for plot in plots:
        ink = driver.execute_async_script(INK, plot)
        check(0.005 < ink < 0.6, f"{name}: #{plot} looks blank or filled (ink {ink:.4f})")
        legend = driver.find_elements(By.CSS_SELECTOR, f"#{plot} .legend .traces")
        check(len(legend) >= 1, f"{name}: #{plot} has no legend")
        titles = [e.text for e in driver.find_elements(By.CSS_SELECTOR, f"#{plot} .g-xtitle, #{plot} .g-ytitle")]
        check(len(titles) == 2 and all(titles), f"{name}: #{plot} axis titles {titles}")
    check(not driver.find_element(By.ID, "error").is_displayed(),
          f"{name}: error shown: {driver.find_element(By.ID, 'error').text}")


# The mesh view's WebGL canvas, scaled down: the share of pixels unlike the background, and the
# pixels themselves.
CANVAS = """
const source = document.getElementById('mesh-canvas');
const copy = document.createElement('canvas'); copy.width = 200; copy.height = 120;
const context = copy.getContext('2d'); context.drawImage(source, 0, 0, 200, 120);
const pixels = context.getImageData(0, 0, 200, 120).data; let ink = 0; const values = [];
for (let i = 0; i < pixels.length; i += 4) {
  values.push(pixels[i], pixels[i + 1], pixels[i + 2]);
  if (Math.abs(pixels[i] - 0x1d) + Math.abs(pixels[i + 1] - 0x22) + Math.abs(pixels[i + 2] - 0x29) > 30) ++ink;
}
return [ink / (200 * 120), values];
"""


def plot_titles(driver):
    return driver.execute_script(
        "return ['profile-plot', 'sphere-plot'].map(id => document.getElementById(id).layout.title.text)")


# The state a refused field leaves: the fields marked, their messages, the status, the stale views.
PROBLEMS = """
const marked = [...document.querySelectorAll('[aria-invalid=true]')].map(e => e.id);
const stale = [...document.querySelectorAll('.stale')].map(e => e.id);
const status = document.getElementById('status');
return {marked, stale, messages: document.querySelectorAll('.field-error').length,
        status: status.textContent, statusError: status.classList.contains('error')};
"""


def check_refused_field(driver):
    """sigma_a = -1 typed for the red channel: the server's refusal shown beside the field and in
    view (in the issue's 857 px tall window too), the field marked, the status in error, the views
    greyed as stale; the field fixed, all of it gone."""
    set_field(driver, "sigma_a-red", -1)
    wait_for(driver, "const s = id => document.getElementById(id).classList.contains('stale');"
             "return document.getElementById('status').classList.contains('error') &&"
             " s('profile-plot') && s('sphere-plot') && (!window.meshView || s('mesh-view'))",
             "the refusal of sigma_a = -1")
    field = driver.find_element(By.ID, "sigma_a-red")
    check(field.get_attribute("aria-invalid") == "true" and "invalid" in field.get_attribute("class"),
          "refused field: sigma_a-red is not marked")
    outline = driver.execute_script("return getComputedStyle(arguments[0]).outlineStyle", field)
    check(outline == "solid", f"refused field: no outline ({outline})")
    message = driver.find_element(By.ID, field.get_attribute("aria-describedby") or "sigma_a-red-error")
    check(message.is_displayed() and message.text.startswith("sigma_a: got -1"),
          f"refused field: message {message.text!r}")
    at, box, height = driver.execute_script(
        "return [arguments[0].getBoundingClientRect(), arguments[1].getBoundingClientRect(), window.innerHeight]",
        field, message)
    check(0 <= box["top"] and box["bottom"] <= min(height, 857),
          f"refused field: message not in view (at {box['top']:.0f}-{box['bottom']:.0f} px of {height})")
    check(0 <= box["top"] - at["bottom"] < 30 and box["left"] <= at["right"] and box["right"] >= at["left"],
          f"refused field: message not beside the field (field {at}, message {box})")
    status = driver.find_element(By.ID, "status")
    check(status.text.startswith("error") and "σa (red)" in status.text and "ready" not in status.text,
          f"refused field: status {status.text!r}")
    colour = driver.execute_script("return getComputedStyle(arguments[0]).backgroundColor", status)
    check(colour == "rgb(198, 40, 40)", f"refused field: status background {colour}")
    banner = driver.execute_script(
        "return getComputedStyle(document.getElementById('profile-plot'), '::after').content")
    check("stale: inputs rejected" in banner, f"refused field: stale banner {banner!r}")
    check(not driver.find_element(By.ID, "error").is_displayed(),
          "refused field: the message was shown above the plots, not only beside its field")
    driver.save_screenshot(str(SHOTS / "1b-refused-field.png"))

    set_field(driver, "sigma_a-red", 0.0021)
    wait_for(driver, "const p = window.explore.lastProfile; return p.medium.sigma_a === 0.0021 &&"
             " document.getElementById('status').textContent === 'ready' &&"
             " !document.querySelector('.stale, .invalid, .field-error')", "the fixed field", 60)
    problems = driver.execute_script(PROBLEMS)
    check(problems == {"marked": [], "stale": [], "messages": 0, "status": "ready", "statusError": False},
          f"fixed field: {problems}")
    driver.save_screenshot(str(SHOTS / "1c-field-fixed.png"))


def check_mesh_view(driver, runs):
    """The BSSRDF on a mesh: drawn, changed by the light, and an OBJ file of the open folder."""
    driver.execute_script("document.getElementById('mesh-controls').scrollIntoView()")
    wait_for(driver, "return (window.explore.meshUpdates || 0) > 0", "the mesh view's first exitance", 120)
    time.sleep(0.3)
    ink, before = driver.execute_script(CANVAS)
    check(0.05 < ink < 0.9, f"mesh view looks blank or filled (ink {ink:.3f})")
    driver.save_screenshot(str(SHOTS / "6-mesh.png"))
    updates = driver.execute_script("return window.explore.meshUpdates")
    driver.execute_script("const s = document.getElementById('light-azimuth'); s.value = 120;"
                          "s.dispatchEvent(new Event('input'));")
    wait_for(driver, f"return window.explore.meshUpdates > {updates} && "
             "window.explore.mesh.light.azimuth === 120", "the exitance for the moved light")
    time.sleep(0.3)
    _, after = driver.execute_script(CANVAS)
    change = sum(abs(a - b) for a, b in zip(before, after)) / len(before)
    check(change > 2.0, f"the mesh view did not change with the light (mean change {change:.2f})")
    ms = driver.execute_script("return window.explore.mesh.ms")
    print(f"mesh view: light moved, server ms {ms}", flush=True)
    check("server ms" in driver.find_element(By.ID, "mesh-timing").text, "no mesh timing line")
    driver.save_screenshot(str(SHOTS / "7-mesh-light-moved.png"))
    # An OBJ file of the open folder, in the chooser.
    options = [o.get_attribute("value") for o in driver.find_elements(By.CSS_SELECTOR, "#mesh-shape option")]
    check("obj:0/cube.obj" in options, f"the OBJ file is not offered: {options}")
    updates = driver.execute_script("return window.explore.meshUpdates")
    Select(driver.find_element(By.ID, "mesh-shape")).select_by_value("obj:0/cube.obj")
    wait_for(driver, f"return window.explore.meshUpdates > {updates}", "the OBJ mesh", 60)
    # A cube's edges are sharp: with smoothed normals its faces would shade as if rounded.
    updates = driver.execute_script("return window.explore.meshUpdates")
    driver.find_element(By.ID, "mesh-flat").click()
    wait_for(driver, f"return window.explore.meshUpdates > {updates}", "the flat cube", 60)
    driver.execute_script("document.getElementById('mesh-controls').scrollIntoView()")
    time.sleep(0.3)
    ink, _ = driver.execute_script(CANVAS)
    check(0.02 < ink < 0.9, f"OBJ mesh view looks blank or filled (ink {ink:.3f})")
    check(not driver.find_element(By.ID, "error").is_displayed(),
          f"mesh view: error shown: {driver.find_element(By.ID, 'error').text}")
    driver.save_screenshot(str(SHOTS / "8-mesh-obj.png"))
    # A text model renders on the mesh beside the built-in ones.
    options = [o.get_attribute("value") for o in driver.find_elements(By.CSS_SELECTOR, "#mesh-model option")]
    check("dipole_text" in options, f"the text model is not offered for the mesh: {options}")
    updates = driver.execute_script("return window.explore.meshUpdates")
    Select(driver.find_element(By.ID, "mesh-model")).select_by_value("dipole_text")
    wait_for(driver, f"return window.explore.meshUpdates > {updates}", "the text model on the mesh", 60)
    check(driver.execute_script("return window.explore.mesh.model") == "dipole_text",
          "the mesh was not drawn with the text model")
    ink, _ = driver.execute_script(CANVAS)
    check(0.02 < ink < 0.9, f"text model on the mesh looks blank or filled (ink {ink:.3f})")
    check(not driver.find_element(By.ID, "error").is_displayed(),
          f"text model on the mesh: error shown: {driver.find_element(By.ID, 'error').text}")


def check_path_traced_sphere(driver):
    """The lit sphere panel with a path-traced sphere beside the models (Bitterli §3.1.3): the
    file's medium and radius taken over, its points drawn with their error bars."""
    driver.find_element(By.CSS_SELECTOR, "#files input[data-path='0/sphere.h5']").click()
    button = "//input[@data-path='0/sphere.h5']/ancestor::div[contains(@class,'file-row')]//button"
    wait_for(driver, "return !!window.explore.sphere", "the lit sphere")
    WebDriverWait(driver, 30).until(lambda d: d.find_elements(By.XPATH, button))
    check(all("red channel" in t for t in plot_titles(driver)), f"titles before: {plot_titles(driver)}")
    before = driver.execute_script("return window.explore.sphereUpdates")
    driver.find_element(By.XPATH, button).click()
    wait_for(driver, f"return window.explore.sphereUpdates > {before}", "the lit sphere of the file's medium", 60)
    # One medium in all three channels now: no title may name the red channel.
    wait_for(driver, "return ['profile-plot', 'sphere-plot'].every(id =>"
             " document.getElementById(id).layout.title.text.includes('all channels equal'))",
             "titles saying that all channels are equal")
    check(not any("red" in t for t in plot_titles(driver)), f"titles after 'use this medium': {plot_titles(driver)}")
    radius = driver.find_element(By.ID, "sphere-radius").get_attribute("value")
    check(float(radius) == 1.0, f"the file's radius was not taken over: {radius}")
    points = driver.execute_script(
        "const t = document.getElementById('sphere-plot').data.find(t => t.name.startsWith('path traced'));"
        "return t && t.error_y.array.filter(e => e > 0).length;")
    check(points and points > 20, f"path-traced lit sphere points with error bars: {points}")
    driver.execute_script("document.getElementById('sphere-plot').scrollIntoView()")
    check_layout(driver, "9-lit-sphere-path-traced", ["sphere-plot"])


def main():
    SHOTS.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="scatterlab-browser-"))
    models, runs = work / "models", work / "runs"
    models.mkdir()
    runs.mkdir()
    shutil.copy(SOURCE / "data/models/dipole_text.toml", models)
    subprocess.run([str(PROGRAM), "searchlight", "--photons", "20000", "--batches", "4",
                    "--threads", "1", "--r-bins", "40", "--out", str(runs / "albedo099.h5")],
                   check=True, capture_output=True)
    # A path-traced lit sphere (R = 1 mfp, directional light) for the lit sphere panel.
    subprocess.run([str(PROGRAM), "simulate", str(SOURCE / "data/scenes/lit-sphere.toml"),
                    "--photons", "20000", "--batches", "4", "--threads", "1",
                    "--out", str(runs / "sphere.h5")], check=True, capture_output=True)
    # A cube (counter-clockwise seen from outside) for the mesh view's OBJ chooser.
    (runs / "cube.obj").write_text(
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
        "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n")
    server, url = start_server(models, runs)
    driver = browser()
    try:
        driver.get(url)
        wait_for(driver, "return window.explore && window.explore.ready && window.explore.updates > 0",
                 "the page's first profiles")
        check(driver.title == "scatterlab explore", f"title {driver.title!r}")
        wait_for(driver, "return window.explore.sphereUpdates > 0", "the lit sphere")
        check_layout(driver, "1-marble-log", ["profile-plot", "sphere-plot"])
        check(all("red channel" in t for t in plot_titles(driver)), f"marble's titles: {plot_titles(driver)}")
        check(driver.find_element(By.ID, "status").text == "ready", "status not ready")
        check_refused_field(driver)

        # A user's change: the red channel to sigma_a = 0.01, sigma_s' = 0.99 per mm (sigma_t' = 1,
        # albedo 0.99), g = 0, eta 1.3, and the square-root mode.
        before = driver.execute_script("return window.explore.updates")
        set_field(driver, "sigma_a-red", 0.01)
        set_field(driver, "sigma_s_reduced-red", 0.99)
        set_field(driver, "g-red", 0)
        set_field(driver, "eta", 1.3)
        Select(driver.find_element(By.ID, "plot-mode")).select_by_value("sqrt")
        wait_for(driver, f"const p = window.explore.lastProfile; return window.explore.updates > {before} &&"
                 " p.medium.sigma_a === 0.01 && p.medium.sigma_s_reduced === 0.99 && "
                 " window.explore.plotMode === 'sqrt'", "the profiles of the new parameters")
        series = driver.execute_script("return window.explore.series")
        labels = {"dipole": "classical dipole", "better_dipole": "better dipole",
                  "quantized_diffusion": "quantized diffusion", "single_scatter": "exact single scattering",
                  "dipole_text": "dipole_text (text)"}
        for model, label in labels.items():
            trace = plotted(driver, label)
            check(trace is not None, f"no trace {label}")
            if trace is None:
                continue
            values = series[model]["values"]
            check(trace["x"] == series[model]["r"], f"{label}: plotted r differ from the answer's")
            worst = max(relative_error(y, math.sqrt(v)) for y, v in zip(trace["y"], values))
            check(worst < 1e-15, f"{label}: plotted sqrt differs by {worst:.3g}")
        r = series["dipole"]["r"]
        t_in = 1.0 - ((1.3 - 1.0) / (1.3 + 1.0)) ** 2
        references = {
            "dipole": [float(core.classical_dipole(x, 0.99, 0.0, 1.3)) for x in r],
            "better_dipole": [float(core.better_dipole(x, 0.99, 0.0, 1.3)) for x in r],
            "dipole_text": [float(core.classical_dipole(x, 0.99, 0.0, 1.3)) for x in r],
            "single_scatter": [float(core.single_scatter_exitance(x, 0.99, 0.0, 1.3, 1.0)) / t_in for x in r],
        }
        qd = post(url, "/api/profiles", {
            "medium": {"sigma_a": 0.01, "sigma_s_reduced": 0.99, "g": 0.0, "eta": 1.3},
            "scale": 1, "points": len(r), "models": ["quantized_diffusion"]})
        check(qd["r"] == r, "the test's own request got other radii")
        references["quantized_diffusion"] = qd["curves"][0]["values"]
        for model, expected in references.items():
            worst = max(relative_error(v, e) for v, e in zip(series[model]["values"], expected))
            print(f"{model}: {len(r)} points, largest relative difference {worst:.3g}", flush=True)
            check(worst <= TOLERANCE, f"{model}: differs from the C++ model by {worst:.3g}")
        timing = driver.find_element(By.ID, "timing").text
        print("timing:", timing, flush=True)
        before = driver.execute_script("return window.explore.sphereUpdates")
        wait_for(driver, f"return window.explore.sphereUpdates > {before} || "
                 "window.explore.sphere && window.explore.lastProfile", "the lit sphere")
        check_layout(driver, "2-albedo099-sqrt", ["profile-plot", "sphere-plot"])

        # Every plot mode draws.
        for mode in ("linear", "r", "log"):
            before = driver.execute_script("return window.explore.updates")
            Select(driver.find_element(By.ID, "plot-mode")).select_by_value(mode)
            wait_for(driver, f"return window.explore.updates > {before} && window.explore.plotMode === '{mode}'",
                     f"the {mode} plot")
            trace = plotted(driver, "classical dipole")
            values = driver.execute_script("return window.explore.series.dipole")
            expected = [x * v for x, v in zip(values["r"], values["values"])] if mode == "r" else values["values"]
            check(max(relative_error(a, b) for a, b in zip(trace["y"], expected)) < 1e-15,
                  f"{mode}: plotted values are not the series'")

        # A text model dropped into the folder, then the reload button.
        (models / "exponential.toml").write_text(
            'name = "exponential"\n'
            'description = "A test profile: k alpha\' sigma_t\'^2 exp(-sigma_t\' r) / (2 pi)"\n'
            'R_d = "k * alpha_reduced * sigma_t_reduced^2 * exp(-sigma_t_reduced * r) / (2 * pi)"\n'
            '[[parameter]]\nname = "k"\nmin = 0\nmax = 4\ndefault = 2\n')
        before = driver.execute_script("return window.explore.updates")
        driver.find_element(By.ID, "reload-models").click()
        wait_for(driver, f"return window.explore.updates > {before} && window.explore.series.exponential",
                 "the text model's curve")
        exponential = driver.execute_script("return window.explore.series.exponential")
        expected = [2 * 0.99 * math.exp(-x) / (2 * math.pi) for x in exponential["r"]]
        worst = max(relative_error(v, e) for v, e in zip(exponential["values"], expected))
        check(worst <= TOLERANCE, f"the text model differs from its formula by {worst:.3g}")
        check(driver.find_element(By.ID, "param-exponential-k").is_displayed(), "no slider for k")

        # A Monte Carlo file with its error bars.
        before = driver.execute_script("return window.explore.updates")
        driver.find_element(By.CSS_SELECTOR, "#files input[data-path='0/albedo099.h5']").click()
        wait_for(driver, f"return window.explore.updates > {before} && "
                 "window.explore.series['mc:0/albedo099.h5:reflectance']", "the Monte Carlo curve")
        error_bars = driver.execute_script(
            "const t = document.getElementById('profile-plot').data.find(t => t.name.startsWith('MC'));"
            "return t && t.error_y && t.error_y.array.filter(e => e > 0).length;")
        check(error_bars and error_bars > 10, f"Monte Carlo error bars: {error_bars}")
        check_layout(driver, "3-text-model-and-monte-carlo", ["profile-plot", "sphere-plot"])

        # A bad text model: the reload answers with its file and line, the old models stay.
        (models / "broken.toml").write_text('name = "broken"\nR_d = "exp(-r"\n')
        driver.find_element(By.ID, "reload-models").click()
        wait_for(driver, "return !document.getElementById('models-error').hidden", "the bad model's error")
        message = driver.find_element(By.ID, "models-error").text
        check("broken.toml:2: R_d" in message, f"bad model message: {message!r}")
        check(driver.execute_script("return !!window.explore.series.exponential"), "the good models went away")
        driver.save_screenshot(str(SHOTS / "4-bad-model.png"))

        # The inversion: R_dr, l_d typed for the red channel give the coefficients the API gives.
        driver.find_element(By.CSS_SELECTOR, "input[name=mode][value=appearance]").click()
        before = driver.execute_script("return window.explore.updates")
        set_field(driver, "R_dr-red", 0.5)
        set_field(driver, "l_d-red", 2)
        wait_for(driver, f"return window.explore.updates > {before} && "
                 "Math.abs(window.explore.lastProfile.medium.sigma_a - 0.01) > 1e-6", "the inverted medium")
        inverted = post(url, "/api/invert", {"model": "dipole", "R_dr": 0.5, "l_d": 2, "eta": 1.3, "g": 0})
        time.sleep(0.3)
        medium = driver.execute_script("return window.explore.lastProfile.medium")
        check(relative_error(medium["sigma_a"], inverted["sigma_a"]) < 1e-12,
              f"inverted sigma_a {medium['sigma_a']} against {inverted['sigma_a']}")
        driver.save_screenshot(str(SHOTS / "5-inversion.png"))

        check_mesh_view(driver, runs)
        check_path_traced_sphere(driver)
    finally:
        driver.quit()
        server.send_signal(2)  # SIGINT: the server stops cleanly
        try:
            code = server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            code = "killed"
        check(code == 0, f"the server ended with {code} on SIGINT")
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print(f"{len(failures)} failures", flush=True)
        sys.exit(1)
    print("browser test passed", flush=True)


if __name__ == "__main__":
    main()

# Draws the line plots and image figures of io/plot.hpp with matplotlib (Agg backend). Compiled
# into the library as a string (sim/CMakeLists.txt) and run as `python3 -c <this> <figures.json>`
# by write_png, which writes the JSON (figure_json in sim/io/plot.cpp gives its fields) and reads
# back the PNG files drawn here.
#
# What a figure for a paper needs, and where it is done:
#  - one colour, line style and marker per model in every figure (STYLES, by the series' model
#    key), the colour-blind-safe palette of Okabe & Ito (2008, "Color universal design");
#  - the exact reference on top of every curve (drawing order), black and dashed, so that no
#    curve hides it and it shows through the Monte Carlo points;
#  - Monte Carlo as points with their +-1 standard error bars;
#  - the legend outside the axes, where it covers no data;
#  - log axes with major and minor ticks, labelled; a sqrt axis labelled in the plotted quantity.
# Exit status 3 when matplotlib cannot be imported: write_png turns it into a message that says
# what to install. Without a request it only imports matplotlib (require_plotting).
import json
import math
import re
import sys
import textwrap

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import ticker
except ImportError as error:
    sys.stderr.write(f"matplotlib cannot be imported: {error}\n")
    sys.exit(3)

OKABE_ITO = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky_blue": "#56B4E9",
    "green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "purple": "#CC79A7",
}

# model key -> (colour, line style, marker, drawing order: higher on top). A series with markers
# (Monte Carlo) is drawn as points, with the key's marker or a circle.
STYLES = {
    # references
    "exact": (OKABE_ITO["black"], (0, (5, 2.5)), None, 10),
    "single_scatter": (OKABE_ITO["black"], (0, (5, 2.5)), None, 10),
    # Monte Carlo and its estimators
    "monte_carlo": (OKABE_ITO["blue"], "-", "o", 4),
    "collision": (OKABE_ITO["blue"], "-", "o", 4),
    "track_length": (OKABE_ITO["sky_blue"], "-", "s", 4),
    "monte_carlo_all_orders": (OKABE_ITO["sky_blue"], "-", "s", 4),
    "standard_error": ("#777777", ":", None, 3),
    # diffusion models; a model plus the exact single scattering keeps the model's style
    "diffusion": (OKABE_ITO["vermillion"], "-", None, 2),
    "dipole": (OKABE_ITO["vermillion"], "-", None, 2),
    "grosjean": (OKABE_ITO["orange"], "-.", None, 2),
    "grosjean_beam": (OKABE_ITO["orange"], "-.", None, 2),
    "better_dipole": (OKABE_ITO["green"], "-", None, 2),
    "quantized_diffusion": (OKABE_ITO["purple"], (0, (3, 1, 1, 1, 1, 1)), None, 2),
    "photon_beam_diffusion": (OKABE_ITO["green"], "--", None, 2),  # the better dipole, spread
    # a BSSRDF on the Monte Carlo's own half-space profile (validate litsphere)
    "measured": (OKABE_ITO["black"], "-", None, 9),
    # single-scatter rendering methods (render --study)
    "straight": (OKABE_ITO["vermillion"], "-", "v", 3),
    "walter": (OKABE_ITO["green"], "-", "^", 3),
    "holzschuch": (OKABE_ITO["purple"], "-", "D", 3),
    "pathtrace": (OKABE_ITO["blue"], "-", "o", 3),
}
# Series without a known key take these in turn; series that share an unknown key share one.
FALLBACK = [
    OKABE_ITO[c] for c in ("sky_blue", "orange", "green", "purple", "vermillion", "yellow", "blue")
]

DPI = 150
LEGEND_WRAP = 32  # characters per legend line


def style_of(series, fallback_index):
    key = series.get("model", "")
    if key.endswith("+single_scatter"):
        key = key[: -len("+single_scatter")]
    if key in STYLES:
        return STYLES[key]
    return (FALLBACK[fallback_index % len(FALLBACK)], "-", None, 2)


def values(array):
    return [float("nan") if v is None else v for v in array]


def shown_length(text):
    """Characters a text shows: a mathtext command (\\sigma) is one, $ { } ^ _ are none."""
    return len(re.sub(r"[${}^_]", "", re.sub(r"\\[A-Za-z]+", "x", text)))


def wrap(line, width):
    """Lines of at most `width` shown characters, broken at spaces (mathtext has none inside)."""
    lines, current = [], ""
    for word in line.split(" "):
        candidate = f"{current} {word}" if current else word
        if current and shown_length(candidate) > width:
            lines.append(current)
            current = word
        else:
            current = candidate
    return lines + [current] if current else lines


def titled(figure):
    """The title, centred over the whole figure (the legend included, so that a long title has
    the figure's width), its lines wrapped to that width: 10.5 pt characters, ~5.8 pt each."""
    chars = int(figure["width"] / DPI * 72 / 5.8 * 0.95)
    return "\n".join(w for line in figure["title"].split("\n") for w in wrap(line, chars))


def set_scale(axis_setter, scale):
    if scale == "log":
        axis_setter("log", nonpositive="clip")
    elif scale == "sqrt":
        axis_setter("function", functions=(lambda v: v**0.5, lambda v: v**2))


class LogLabels(ticker.Formatter):
    """Labels of a log axis: every decade; 2 and 5 times a decade when two decades or less are
    shown, every minor tick below one decade. Plain numbers (0.02, 50) when the whole axis lies in
    [0.001, 10^4], powers of ten (2 x 10^-5) otherwise."""

    def __call__(self, x, pos=None):
        if not x > 0:
            return ""
        lo, hi = sorted(self.axis.get_view_interval())
        decades = math.log10(hi / lo) if lo > 0 else float("inf")
        exponent = math.floor(math.log10(x) + 1e-9)
        mantissa = round(x / 10**exponent, 6)
        if mantissa != 1:
            if decades > 2.2 or (decades > 1.0 and mantissa not in (2, 5)):
                return ""
        if lo >= 0.999e-3 and hi < 1e4:
            return f"{x:g}"
        power = f"10^{{{exponent}}}"
        return f"${power}$" if mantissa == 1 else f"${mantissa:g}\\times{power}$"


def log_ticks(axis):
    axis.set_major_locator(ticker.LogLocator(base=10, numticks=12))
    axis.set_minor_locator(ticker.LogLocator(base=10, subs=tuple(range(2, 10)), numticks=12))
    axis.set_major_formatter(LogLabels())
    axis.set_minor_formatter(LogLabels())


def sqrt_ticks(ax):
    """Ticks about evenly spaced in sqrt(y), where the axis is linear, at 1, 2 or 5 times a power
    of ten."""
    ax.set_ylim(bottom=0)
    top = ax.get_ylim()[1]
    ticks = {0.0}
    for k in range(1, 6):
        v = (k / 5 * top**0.5) ** 2
        scale = 10 ** math.floor(math.log10(v))
        ticks.add(scale * min((1, 2, 5, 10), key=lambda m: abs(math.log(m * scale / v))))
    ax.yaxis.set_major_locator(ticker.FixedLocator(sorted(t for t in ticks if t <= top * 1.0001)))
    ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_locator(ticker.NullLocator())


def draw(figure, path):
    plt.rcParams.update(
        {
            "font.size": 10,
            "axes.titlesize": 10.5,
            "axes.labelsize": 10,
            "legend.fontsize": 8.5,
            "xtick.labelsize": 9,
            "ytick.labelsize": 9,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "grid.linewidth": 0.6,
        }
    )
    size = (figure["width"] / DPI, figure["height"] / DPI)
    fig = plt.figure(figsize=size, dpi=DPI, layout="constrained")
    ax = fig.add_subplot()
    fallback = {}  # an unknown key's colour index; an empty key is a key of its own
    core = []  # the values the y axis must show: points, and bar ends near their point
    legend = []  # (handle, label) in the order of the series
    for number, series in enumerate(figure["series"]):
        key = series.get("model", "")
        known = key in STYLES or key.endswith("+single_scatter")
        index = 0 if known else fallback.setdefault(key or ("", number), len(fallback))
        colour, line_style, marker, order = style_of(series, index)
        x, y = values(series["x"]), values(series["y"])
        core += [v for v in series["y"] if v is not None]
        label = "\n".join(textwrap.wrap(series["name"], LEGEND_WRAP)) or None
        if series["markers"]:
            low, high = series.get("low"), series.get("high")
            error = None
            if low is not None:
                # A bar reaching more than a factor 30 below its point (a standard error as large
                # as the value) would stretch a log axis over many empty decades: it runs off the
                # bottom of the axis instead, which is what such a bar means.
                ends = list(zip(series["y"], low, high))
                shown = [(v, lo, hi) for v, lo, hi in ends if v is not None]
                core += [lo for v, lo, _ in shown if lo is not None and lo > v / 30]
                core += [hi for _, _, hi in shown if hi is not None]
                # A null low end is one the axis cannot show: the bar runs to 0, off a log axis.
                below = [
                    0.0 if v is None else v if lo is None else max(v - lo, 0.0) for v, lo, _ in ends
                ]
                above = [0.0 if v is None or hi is None else max(hi - v, 0.0) for v, _, hi in ends]
                error = [below, above]
            handle = ax.errorbar(
                x,
                y,
                yerr=error,
                color=colour,
                marker=marker or "o",
                markersize=3.2,
                linestyle="none" if error is not None else line_style,
                linewidth=0.8,
                elinewidth=0.8,
                capsize=0,
                label=label,
                zorder=order,
            )
        else:
            (handle,) = ax.plot(
                x,
                y,
                color=colour,
                linestyle=line_style,
                marker=marker,
                markersize=4,
                linewidth=1.8 if order >= 10 else 1.5,
                label=label,
                zorder=order,
            )
        for px, py, text in zip(series["x"], series["y"], series.get("point_labels", [])):
            if px is not None and py is not None:
                ax.annotate(
                    text,
                    (px, py),
                    xytext=(4, 4),
                    textcoords="offset points",
                    fontsize=7,
                    color=colour,
                    zorder=order,
                )
        if label:
            legend.append((handle, label))
    set_scale(ax.set_yscale, figure["y_scale"])
    if figure["log_x"]:
        ax.set_xscale("log")
        log_ticks(ax.xaxis)
    if figure["y_scale"] == "log":
        positive = [v for v in core if v > 0]
        if positive:
            ax.set_ylim(min(positive) / 1.6, max(positive) * 1.6)
        log_ticks(ax.yaxis)
    elif figure["y_scale"] == "sqrt":
        sqrt_ticks(ax)
    if figure["y_scale"] != "log" and not figure["log_x"]:
        ax.xaxis.set_minor_locator(ticker.AutoMinorLocator())
    if figure["y_scale"] == "linear":
        ax.yaxis.set_minor_locator(ticker.AutoMinorLocator())
    ax.grid(True, which="major")
    fig.suptitle(titled(figure), fontsize=10.5)
    ax.set_xlabel(figure["x_label"])
    ax.set_ylabel(figure["y_label"] + (", square-root axis" if figure["y_scale"] == "sqrt" else ""))
    if legend:
        ax.legend(
            [h for h, _ in legend],
            [text for _, text in legend],
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
            borderaxespad=0.0,
            frameon=False,
            handlelength=2.6,
        )
    fig.savefig(path, format="png", dpi=DPI)
    plt.close(fig)


def draw_images(figure, path):
    """Images side by side in grey, pixels as squares, each titled; no axes."""
    panels = figure["panels"]
    size = (figure["width"] / DPI, figure["height"] / DPI)
    fig, axes = plt.subplots(
        1, len(panels), figsize=size, dpi=DPI, layout="constrained", squeeze=False
    )
    for ax, panel in zip(axes[0], panels):
        ax.imshow(panel["pixels"], cmap="gray", vmin=0.0, vmax=1.0, interpolation="nearest")
        lines = [w for line in panel["title"].split("\n") for w in textwrap.wrap(line, 30)]
        ax.set_title("\n".join(lines), fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(titled(figure), fontsize=10.5)
    fig.savefig(path, format="png", dpi=DPI)
    plt.close(fig)


def main():
    if len(sys.argv) < 2:
        return  # only asked whether matplotlib imports (require_plotting)
    with open(sys.argv[1], encoding="utf-8") as file:
        request = json.load(file)
    for figure in request["figures"]:
        if figure.get("kind") == "images":
            draw_images(figure, figure["output"])
        else:
            draw(figure, figure["output"])


main()

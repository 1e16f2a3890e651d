#include "scatterlab/transport/declared_tally.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

// The scores a scene may declare, each at its event.
constexpr std::array<Score, 4> declarable = {Score::exitance, Score::transmittance, Score::fluence,
                                             Score::absorbed};
constexpr int max_bins = 100'000;
// One tally's cells: past this its buffers (several per thread and batch) outgrow a machine.
constexpr double max_cells = 1e8;

// The filters, in the order of their cells: space, direction, time, order. Adding one is a row
// here with its case in declare_chained_tallies, its Coordinate and EventBinning case
// (tally/filter.hpp) and its factory; the schema (io/scene_schema.cpp) lists its keys.
struct FilterRow {
  std::string_view key;
  Coordinate coordinate;
  bool at_exits, in_volume;  // the events it bins
  // The surface whose exits it bins (ExitSurface::none: any).
  ExitSurface exits_through;
  // Of min and max: "length" is the scene's length unit; "rad" an angle over its whole range
  // (bins alone); "" a count (order), or a switch (layer, triangle: a bin per one).
  std::string_view unit;
  std::string_view per;  // what its bins divide by, for the description
};
constexpr ExitSurface any = ExitSurface::none;
constexpr auto filter_rows = std::to_array<FilterRow>({
    {"x", Coordinate::x, true, true, any, "length", "per unit length in x"},
    {"y", Coordinate::y, true, true, any, "length", "per unit length in y"},
    {"r", Coordinate::r, true, true, any, "length",
     "per unit area at distance r from the beam axis"},
    {"z", Coordinate::z, false, true, any, "length", "per unit depth z"},
    {"rho", Coordinate::rho, false, true, any, "length",
     "per unit volume at distance rho from the source"},
    {"psi", Coordinate::psi, true, false, ExitSurface::sphere, "rad",
     "per unit area of the sphere by the angle psi from the lit pole"},
    {"azimuth", Coordinate::azimuth, true, false, ExitSurface::sphere, "rad",
     "by the exit point's azimuth about z (alone: per unit area of its lune)"},
    {"triangle", Coordinate::triangle, true, false, ExitSurface::mesh, "",
     "per unit area of each triangle"},
    {"theta", Coordinate::theta, false, true, any, "rad",
     "per steradian by the direction's polar angle theta from +z"},
    {"theta_o", Coordinate::exit_angle, true, false, any, "rad",
     "per steradian at exit angle theta_o from the outward normal, outside"},
    {"phi", Coordinate::phi, true, true, ExitSurface::plane, "rad",
     "by the direction's azimuth phi about z (alone: per radian)"},
    {"t", Coordinate::t, true, true, any, "s",
     "per second of time of flight t after a unit impulse"},
    {"order", Coordinate::order, true, true, any, "",
     "by scattering order (the last bin: and more)"},
    {"layer", Coordinate::layer, false, true, any, "", "by layer, top down"},
});

// The names of the surfaces, for refusals.
std::string_view surface_name(ExitSurface surface) {
  switch (surface) {
    case ExitSurface::plane:
      return "a plane (half_space, slab)";
    case ExitSurface::sphere:
      return "a sphere";
    case ExitSurface::mesh:
      return "a mesh";
    case ExitSurface::none:
      break;
  }
  return "none";
}
constexpr std::array<std::string_view, filter_rows.size()> filter_keys = [] {
  std::array<std::string_view, filter_rows.size()> keys{};
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = filter_rows[i].key;
  return keys;
}();

const FilterRow& row_of(Coordinate coordinate) {
  for (const FilterRow& row : filter_rows) {
    if (row.coordinate == coordinate) return row;
  }
  throw std::invalid_argument("declared tally: a filter of no row");
}

// The keys of the filters that bin exits, or events in the volume.
std::vector<std::string_view> filters_of(bool exits) {
  std::vector<std::string_view> keys;
  for (const FilterRow& row : filter_rows) {
    if (exits ? row.at_exits : row.in_volume) keys.push_back(row.key);
  }
  return keys;
}

std::string key(std::size_t i, std::string_view rest) {
  return fmt::format("tally[{}].{}", i + 1, rest);
}

// A filter's axis with its defaults: r and t from 0; the angles over their whole range
// (theta_o [0, pi/2], theta and psi [0, pi], phi and azimuth [0, 2 pi]); order from 0 by 1.
UniformAxis axis_of(const DeclaredFilter& f) {
  switch (f.coordinate) {
    case Coordinate::exit_angle:
      return {0.0, 0.5 * pi, f.bins};
    case Coordinate::theta:
    case Coordinate::psi:
      return {0.0, pi, f.bins};
    case Coordinate::phi:
    case Coordinate::azimuth:
      return {0.0, 2.0 * pi, f.bins};
    case Coordinate::order:
      return {0.0, static_cast<double>(f.bins), f.bins};
    default:
      return {f.min.value_or(0.0), f.max.value_or(0.0), f.bins};
  }
}

void check_filter(const DeclaredFilter& f, std::size_t i, const DeclaredTallyFrame& frame) {
  const FilterRow& row = row_of(f.coordinate);
  const std::string at = key(i, fmt::format("filters.{}", row.key));
  if (f.coordinate == Coordinate::layer) {  // as many bins as the slab has layers
    if (frame.layers == 0) {
      throw InputError(at, fmt::format("is asked in a {} scene", frame.geometry),
                       "layer only in a slab: the other geometries have one medium");
    }
    return;
  }
  if (f.coordinate == Coordinate::triangle) return;  // a bin per triangle (the surface checked)
  if (f.bins < 1 || f.bins > max_bins) {
    throw InputError(at + ".bins", f.bins == 0 ? "is missing" : fmt::format("is {}", f.bins),
                     "an integer in [1, 100000]");
  }
  if (row.unit == "rad" || f.coordinate == Coordinate::order) return;  // bins alone
  const std::string unit = row.unit == "length" ? frame.length_unit : std::string(row.unit);
  if (!f.max) throw InputError(at + ".max", "is missing", fmt::format("a number, in {}", unit));
  const bool signed_axis = f.coordinate == Coordinate::x || f.coordinate == Coordinate::y ||
                           f.coordinate == Coordinate::z;
  if (signed_axis && !f.min) {
    throw InputError(at + ".min", "is missing", fmt::format("a number, in {}", unit));
  }
  const UniformAxis axis = axis_of(f);
  if (!std::isfinite(axis.min) || !std::isfinite(axis.max) || !(axis.max > axis.min)) {
    throw InputError(at, fmt::format("spans [{}, {}]", axis.min, axis.max),
                     fmt::format("finite ends with max > min, in {}", unit));
  }
  if (!signed_axis && axis.min < 0.0) {
    throw InputError(at + ".min", fmt::format("is {}", axis.min), "a number >= 0");
  }
  if (row.unit != "length") return;
  // The walk's units: as a grid's axes, finite bins of non-zero width (length_units.hpp).
  if (std::max(std::abs(axis.min), std::abs(axis.max)) * frame.walk_per_unit > max_grid_mfp ||
      axis.width() * frame.walk_per_unit < min_bin_mfp) {
    throw InputError(
        at, fmt::format("spans [{}, {}] {} in {} bins", axis.min, axis.max, unit, axis.bins),
        fmt::format("ends within {:g} mfp and bins at least {:g} mfp wide", max_grid_mfp,
                    min_bin_mfp));
  }
}

// The units of a tally of `score` over its filters: a length power (from the filters' measures
// and the score's weight), per steradian with theta_o, and per joule with t, per watt without.
Units units_of(const DeclaredTally& t) {
  Units units;
  units.length = t.score == Score::fluence ? 1 : 0;  // a collision scores 1 mfp
  if (t.filter(Coordinate::r)) units.length -= 2;
  if (t.filter(Coordinate::rho)) units.length -= 3;
  for (const Coordinate c : {Coordinate::x, Coordinate::y, Coordinate::z})
    units.length -= t.filter(c) != nullptr;
  for (const Coordinate c : {Coordinate::psi, Coordinate::azimuth, Coordinate::triangle}) {
    if (t.filter(c)) {
      units.length -= 2;  // per unit area of the surface
      break;
    }
  }
  const bool polar = t.filter(Coordinate::exit_angle) || t.filter(Coordinate::theta);
  if (polar) units.steradians = -1;
  if (t.filter(Coordinate::phi) && !polar) units.radians = -1;
  if (t.filter(Coordinate::t)) units.seconds = -1;
  return units;
}

std::string description_of(const DeclaredTally& t) {
  constexpr std::array<std::string_view, 4> what = {
      "power leaving through the lit surface", "power leaving through the far side",
      "fluence rate (collision estimator)", "power absorbed"};
  const auto at = std::find(declarable.begin(), declarable.end(), t.score);
  std::string text(what.at(static_cast<std::size_t>(at - declarable.begin())));
  for (const FilterRow& row : filter_rows) {
    if (t.filter(row.coordinate)) text += fmt::format(", {}", row.per);
  }
  return text + (t.filters.empty() ? ", in all" : ", bin average");
}

}  // namespace

DeclaredTallyFrame homogeneous_frame(std::string_view geometry, const Medium& medium,
                                     std::optional<double> index) {
  DeclaredTallyFrame frame;
  frame.geometry = geometry;
  frame.surface = geometry == "half_space" ? ExitSurface::plane
                  : geometry == "sphere"   ? ExitSurface::sphere
                  : geometry == "mesh"     ? ExitSurface::mesh
                                           : ExitSurface::none;
  frame.has_index = index.has_value();
  frame.index = index.value_or(1.0);
  frame.length_unit = medium.length_unit;
  frame.walk_per_unit = mfp_per_length_unit(medium);
  // One mfp is 1 / sigma_t in the scene's unit.
  if (medium.length_unit != "mfp") {
    frame.seconds_per_walk_length =
        millimetres_per(medium.length_unit) * 1e-3 / medium.sigma_t / speed_of_light;
  }
  return frame;
}

DeclaredTallyFrame slab_frame(const std::string& length_unit, int layers) {
  DeclaredTallyFrame frame;
  frame.geometry = "slab";
  frame.layers = layers;
  frame.transmits = true;
  frame.has_volume_estimator = false;
  frame.length_unit = length_unit;
  if (length_unit != "mfp") {
    frame.seconds_per_walk_length = millimetres_per(length_unit) * 1e-3 / speed_of_light;
  }
  return frame;
}

std::optional<Score> declared_score(std::string_view name) {
  const std::optional<Score> score = score_named(name);
  if (!score || std::find(declarable.begin(), declarable.end(), *score) == declarable.end()) {
    return std::nullopt;
  }
  return score;
}

void check_declared_tallies(const std::vector<DeclaredTally>& tallies,
                            const DeclaredTallyFrame& frame) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < tallies.size(); ++i) {
    const DeclaredTally& t = tallies[i];
    const bool named = !t.name.empty() && t.name.size() <= 64 &&
                       t.name.find_first_not_of(
                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                           "0123456789_") == std::string::npos;
    if (!named) {
      throw InputError(key(i, "name"), fmt::format("is \"{}\"", t.name),
                       "1 to 64 letters, digits and _");
    }
    if (!names.insert(t.name).second) {
      throw InputError(key(i, "name"), fmt::format("\"{}\" is taken by an earlier tally", t.name),
                       "a name of its own");
    }
    const std::string_view score = to_string(t.score);
    const auto refuse_score = [&](std::string_view why) {
      throw InputError(key(i, "score"),
                       fmt::format("\"{}\" in a {} scene: {}", score, frame.geometry, why),
                       "\"exitance\" (a geometry with a surface), \"transmittance\" (a slab), "
                       "\"fluence\" (not a slab) or \"absorbed\"");
    };
    if (t.score == Score::exitance && frame.surface == ExitSurface::none) {
      refuse_score("it has no surface to leave through");
    }
    if (t.score == Score::transmittance && !frame.transmits) {
      refuse_score("only a slab has a far side");
    }
    if (t.score == Score::fluence && !frame.has_volume_estimator) {
      refuse_score("its walk scores no collisions in the volume");
    }
    const bool exits = t.score == Score::exitance || t.score == Score::transmittance;
    for (std::size_t j = 0; j < t.filters.size(); ++j) {
      const DeclaredFilter& f = t.filters[j];
      const FilterRow& row = row_of(f.coordinate);
      if (t.filter(f.coordinate) != &f) {
        throw InputError(key(i, fmt::format("filters.{}", row.key)), "is given twice",
                         "each filter once");
      }
      if (exits ? !row.at_exits : !row.in_volume) {
        throw InputError(
            key(i, fmt::format("filters.{}", row.key)), fmt::format("bins \"{}\"", score),
            fmt::format("filters {} for a score {}", fmt::join(filters_of(exits), ", "),
                        exits ? "at the surface" : "in the volume"));
      }
      if (exits && row.exits_through != any && row.exits_through != frame.surface) {
        throw InputError(key(i, fmt::format("filters.{}", row.key)),
                         fmt::format("bins \"{}\" in a {} scene, whose surface is {}", score,
                                     frame.geometry, surface_name(frame.surface)),
                         fmt::format("{} only on {}", row.key, surface_name(row.exits_through)));
      }
      check_filter(f, i, frame);
    }
    if (t.filter(Coordinate::t) && frame.length_unit == "mfp") {
      throw InputError(
          key(i, "filters.t"),
          fmt::format("is asked in a {} scene whose lengths are in mfp", frame.geometry),
          "a scene with a physical length unit (\"um\", \"mm\", \"cm\" or "
          "\"m\") and its coefficients in it: time needs lengths in metres");
    }
    if (t.group_index && frame.has_index) {
      throw InputError(key(i, "group_index"), fmt::format("is given in a {} scene", frame.geometry),
                       "no group_index: the geometry's own index times the flight (eta, or each "
                       "layer's n)");
    }
    if (t.group_index && !(*t.group_index >= 0.1 && *t.group_index <= 10.0)) {
      throw InputError(key(i, "group_index"), fmt::format("is {}", *t.group_index),
                       "a refractive index in [0.1, 10]");
    }
    if (t.filter(Coordinate::t) && !frame.has_index && !t.group_index) {
      throw InputError(key(i, "group_index"), "is missing",
                       fmt::format("the medium's group index (e.g. 1.4) for the time of flight "
                                   "in a {} scene, which has no index of its own",
                                   frame.geometry));
    }
    double cells = 1.0;
    for (const DeclaredFilter& f : t.filters) {
      cells *= f.coordinate == Coordinate::layer ? frame.layers
               : f.coordinate == Coordinate::triangle
                   ? static_cast<double>(frame.triangle_areas.size())
                   : f.bins;
    }
    if (cells > max_cells) {
      throw InputError(key(i, "filters"), fmt::format("make {:g} cells", cells),
                       fmt::format("at most {:g} cells in one tally", max_cells));
    }
  }
}

std::vector<TallyDeclaration> declare_chained_tallies(const std::vector<DeclaredTally>& tallies,
                                                      const DeclaredTallyFrame& frame,
                                                      const std::vector<TallyDeclaration>& taken) {
  std::vector<TallyDeclaration> declarations;
  for (std::size_t i = 0; i < tallies.size(); ++i) {
    const DeclaredTally& t = tallies[i];
    for (const TallyDeclaration& d : taken) {
      if (d.name == t.name) {
        throw InputError(
            key(i, "name"),
            fmt::format("\"{}\" is one of the {} scene's own tallies", t.name, frame.geometry),
            "a name of its own");
      }
    }
    TallyDeclaration d{t.name, t.score, {}, units_of(t), description_of(t)};
    d.chained = true;
    for (const FilterRow& row : filter_rows) {
      const DeclaredFilter* f = t.filter(row.coordinate);
      if (f == nullptr) continue;
      const UniformAxis axis = axis_of(*f);
      const std::string unit = row.unit == "length" ? frame.length_unit : std::string(row.unit);
      switch (row.coordinate) {
        case Coordinate::r:
          d.filters.push_back(radius_filter(length_axis_in_mfp(axis, frame.walk_per_unit)));
          break;
        case Coordinate::rho:
          d.filters.push_back(shell_filter(length_axis_in_mfp(axis, frame.walk_per_unit)));
          break;
        case Coordinate::x:
        case Coordinate::y:
        case Coordinate::z:
          d.filters.push_back(
              position_filter(row.coordinate, length_axis_in_mfp(axis, frame.walk_per_unit)));
          break;
        case Coordinate::exit_angle:
          d.filters.push_back(exit_solid_angle_filter(axis, t.filter(Coordinate::phi) != nullptr));
          break;
        case Coordinate::theta:
          d.filters.push_back(polar_angle_filter(axis, t.filter(Coordinate::phi) != nullptr));
          break;
        case Coordinate::phi:
          d.filters.push_back(azimuth_angle_filter(axis));
          break;
        case Coordinate::psi:
          d.filters.push_back(
              sphere_polar_filter(axis, frame.radius, t.filter(Coordinate::azimuth) != nullptr));
          break;
        case Coordinate::azimuth:
          d.filters.push_back(
              sphere_azimuth_filter(axis, frame.radius, t.filter(Coordinate::psi) != nullptr));
          break;
        case Coordinate::triangle:
          d.filters.push_back(triangle_filter(frame.triangle_areas));
          break;
        case Coordinate::t:
          d.filters.push_back(time_filter(
              axis, frame.seconds_per_walk_length * t.group_index.value_or(frame.index)));
          break;
        case Coordinate::order:
          d.filters.push_back(order_filter(f->bins));
          break;
        case Coordinate::layer:
          d.filters.push_back(layer_filter(static_cast<std::size_t>(frame.layers)));
          break;
        default:
          break;
      }
      // The file's own axes: edges in the scene's units (orders, layers and triangles are
      // numbered).
      if (!row.unit.empty()) d.axes.push_back({std::string(row.key), axis.edges(), unit});
    }
    declarations.push_back(std::move(d));
  }
  return declarations;
}

std::string fingerprint_text(const std::vector<DeclaredTally>& tallies) {
  std::string text;
  for (const DeclaredTally& t : tallies) {
    text += fmt::format("tally {} {}|", t.name, to_string(t.score));
    for (const DeclaredFilter& f : t.filters) {
      const UniformAxis axis = axis_of(f);
      text +=
          fmt::format("{} {:a} {:a} {}|", row_of(f.coordinate).key, axis.min, axis.max, axis.bins);
    }
    text += t.group_index ? fmt::format("n {:a}|", *t.group_index) : "n -|";
  }
  return text;
}

const DeclaredFilter* DeclaredTally::filter(Coordinate coordinate) const {
  for (const DeclaredFilter& f : filters) {
    if (f.coordinate == coordinate) return &f;
  }
  return nullptr;
}

std::span<const std::string_view> declared_filter_keys() {
  return filter_keys;
}

std::optional<Coordinate> declared_filter(std::string_view name) {
  for (const FilterRow& row : filter_rows) {
    if (row.key == name) return row.coordinate;
  }
  return std::nullopt;
}

bool declared_filter_is_switch(std::string_view name) {
  return name == "layer" || name == "triangle";
}

}  // namespace scatterlab

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
constexpr std::array<Score, 6> declarable = {Score::exitance,   Score::transmittance,
                                             Score::fluence,    Score::absorbed,
                                             Score::collisions, Score::path_length};
constexpr int max_bins = 100'000;
// One tally's cells: past this its buffers (several per thread and batch) outgrow a machine.
constexpr double max_cells = 1e8;

constexpr ExitSurface any = ExitSurface::none;

// The filters, in the order of their cells: space, direction, time, order. Each row says all
// there is to say about a filter: its key, the coordinate it bins (tally/filter.hpp), the events
// and surfaces it bins, how its axis is given, what its bins divide a tally by (its units; a
// filter of a pair, phi or azimuth, leaves them to its partner when both are there), the
// geometries whose scenes take it (the schema's, io/scene_schema.cpp, is written from these
// rows), its meaning, and how it is made in the walk's units. Adding a filter of a coordinate
// the events carry is a row here.
struct FilterRow {
  std::string_view key;
  Coordinate coordinate;
  bool at_exits, in_volume;   // the events it bins
  ExitSurface exits_through;  // the surface whose exits it bins (any: every one)
  FilterAxis axis;
  double range;  // an angle's: its axis is [0, range]
  Units units;   // its share of the tally's units
  int pair;      // 1: theta, theta_o with phi; 2: psi with azimuth; 0: none
  bool follows;  // of a pair, the one that leaves the units to the other
  std::string_view geometries;
  std::string_view meaning;  // of its bins, for the schema
  std::string_view per;      // what its bins divide by, for the tally's description
  // The filter, in the walk's units; `paired`: the other filter of its pair is there too.
  Filter (*make)(const UniformAxis& axis, const DeclaredTally& t, const DeclaredTallyFrame& frame,
                 bool paired);
};

using L = FilterAxis;
constexpr std::string_view every = "infinite half_space sphere mesh slab";

UniformAxis in_walk(const UniformAxis& axis, const DeclaredTallyFrame& frame) {
  return length_axis_in_mfp(axis, frame.walk_per_unit);
}

constexpr auto filter_rows = std::to_array<FilterRow>({
    {"x", Coordinate::x, true, true, any, L::signed_length, 0.0, Units{0, -1}, 0, false, every,
     "bins of x (of an exit: on the surface, about the entry point)", "per unit length in x",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return position_filter(Coordinate::x, in_walk(a, f));
     }},
    {"y", Coordinate::y, true, true, any, L::signed_length, 0.0, Units{0, -1}, 0, false, every,
     "bins of y (of an exit: on the surface, about the entry point)", "per unit length in y",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return position_filter(Coordinate::y, in_walk(a, f));
     }},
    {"r", Coordinate::r, true, true, any, L::length, 0.0, Units{0, -2}, 0, false, every,
     "bins of the distance from the beam axis", "per unit area at distance r from the beam axis",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return radius_filter(in_walk(a, f));
     }},
    {"z", Coordinate::z, false, true, any, L::signed_length, 0.0, Units{0, -1}, 0, false, every,
     "bins of depth", "per unit depth z",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return position_filter(Coordinate::z, in_walk(a, f));
     }},
    {"rho", Coordinate::rho, false, true, any, L::length, 0.0, Units{0, -3}, 0, false, every,
     "bins of the distance from the source (the origin)",
     "per unit volume at distance rho from the source",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return shell_filter(in_walk(a, f));
     }},
    {"psi", Coordinate::psi, true, false, ExitSurface::sphere, L::angle, pi, Units{0, -2}, 2, false,
     "sphere", "bins of an exit point's angle from the lit pole (0, 0, -R)",
     "per unit area of the sphere by the angle psi from the lit pole",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool paired) {
       return sphere_polar_filter(a, f.radius, paired);
     }},
    {"azimuth", Coordinate::azimuth, true, false, ExitSurface::sphere, L::angle, 2.0 * pi,
     Units{0, -2}, 2, true, "sphere", "bins of an exit point's azimuth about z from +x",
     "by the exit point's azimuth about z (alone: per unit area of its lune)",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame& f, bool paired) {
       return sphere_azimuth_filter(a, f.radius, paired);
     }},
    {"triangle", Coordinate::triangle, true, false, ExitSurface::mesh, L::each, 0.0, Units{0, -2},
     0, false, "mesh", "a bin per triangle of the mesh, by its area",
     "per unit area of each triangle",
     [](const UniformAxis&, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return triangle_filter(f.triangle_areas);
     }},
    {"theta", Coordinate::theta, false, true, any, L::angle, pi, Units{0, 0, -1}, 1, false, every,
     "bins of the direction's polar angle from +z (fluence, absorbed)",
     "per steradian by the direction's polar angle theta from +z",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame&, bool paired) {
       return polar_angle_filter(a, paired);
     }},
    {"theta_o", Coordinate::exit_angle, true, false, any, L::angle, 0.5 * pi, Units{0, 0, -1}, 1,
     false, every, "bins of the exit angle from the outward normal, outside",
     "per steradian at exit angle theta_o from the outward normal, outside",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame&, bool paired) {
       return exit_solid_angle_filter(a, paired);
     }},
    {"phi", Coordinate::phi, true, true, ExitSurface::plane, L::angle, 2.0 * pi,
     Units{0, 0, 0, 0, -1}, 1, true, every,
     "bins of the direction's azimuth about z from +x (in the volume, and at exits through a "
     "plane)",
     "by the direction's azimuth phi about z (alone: per radian)",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame&, bool) {
       return azimuth_angle_filter(a);
     }},
    {"t", Coordinate::t, true, true, any, L::seconds, 0.0, Units{0, 0, 0, -1}, 0, false, every,
     "bins of the time of flight since the light entered",
     "per second of time of flight t after a unit impulse",
     [](const UniformAxis& a, const DeclaredTally& t, const DeclaredTallyFrame& f, bool) {
       return time_filter(a, f.seconds_per_walk_length * t.group_index.value_or(f.index));
     }},
    {"order", Coordinate::order, true, true, any, L::count, 0.0, Units{0}, 0, false, every,
     "bins of the scattering order 0, 1, ...; the last holds its order and more",
     "by scattering order (the last bin: and more)",
     [](const UniformAxis& a, const DeclaredTally&, const DeclaredTallyFrame&, bool) {
       return order_filter(a.bins);
     }},
    {"layer", Coordinate::layer, false, true, any, L::each, 0.0, Units{0}, 0, false, "slab",
     "a bin per layer, top down", "by layer, top down",
     [](const UniformAxis&, const DeclaredTally&, const DeclaredTallyFrame& f, bool) {
       return layer_filter(static_cast<std::size_t>(f.layers));
     }},
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

// Whether the other filter of `row`'s pair is in `t` too.
bool paired(const FilterRow& row, const DeclaredTally& t) {
  if (row.pair == 0) return false;
  for (const DeclaredFilter& f : t.filters) {
    const FilterRow& other = row_of(f.coordinate);
    if (other.pair == row.pair && other.coordinate != row.coordinate) return true;
  }
  return false;
}

// A filter's axis with its defaults: lengths and t from 0, an angle over its whole range, an
// order from 0 by 1.
UniformAxis axis_of(const DeclaredFilter& f) {
  const FilterRow& row = row_of(f.coordinate);
  switch (row.axis) {
    case FilterAxis::angle:
      return {0.0, row.range, f.bins};
    case FilterAxis::count:
      return {0.0, static_cast<double>(f.bins), f.bins};
    default:
      return {f.min.value_or(0.0), f.max.value_or(0.0), f.bins};
  }
}

void check_filter(const DeclaredFilter& f, std::size_t i, const DeclaredTallyFrame& frame) {
  const FilterRow& row = row_of(f.coordinate);
  const std::string at = key(i, fmt::format("filters.{}", row.key));
  if (f.coordinate == Coordinate::layer && frame.layers == 0) {
    throw InputError(at, fmt::format("is asked in a {} scene", frame.geometry),
                     "layer only in a slab: the other geometries have one medium");
  }
  if (row.axis == FilterAxis::each) return;  // a bin per layer or triangle
  if (f.bins < 1 || f.bins > max_bins) {
    throw InputError(at + ".bins", f.bins == 0 ? "is missing" : fmt::format("is {}", f.bins),
                     "an integer in [1, 100000]");
  }
  if (row.axis == FilterAxis::angle || row.axis == FilterAxis::count) return;  // bins alone
  const bool seconds = row.axis == FilterAxis::seconds;
  const bool signed_axis = row.axis == FilterAxis::signed_length;
  const std::string unit = seconds ? "s" : frame.length_unit;
  if (!f.max) throw InputError(at + ".max", "is missing", fmt::format("a number, in {}", unit));
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
  if (seconds) return;
  // The walk's units: as a grid's axes, finite bins of non-zero width (length_units.hpp).
  if (std::max(std::abs(axis.min), std::abs(axis.max)) * frame.walk_per_unit > max_grid_mfp ||
      axis.width() * frame.walk_per_unit < min_bin_mfp) {
    throw InputError(
        at, fmt::format("spans [{}, {}] {} in {} bins", axis.min, axis.max, unit, axis.bins),
        fmt::format("ends within {:g} mfp and bins at least {:g} mfp wide", max_grid_mfp,
                    min_bin_mfp));
  }
}

// The units of a tally of `score` over its filters: W per W incident (a collision of the fluence
// scores 1 mfp), times each filter's share.
Units units_of(const DeclaredTally& t) {
  Units units;
  // A collision of the fluence scores 1 mfp; a path, its length.
  units.length = t.score == Score::fluence || t.score == Score::path_length ? 1 : 0;
  for (const DeclaredFilter& f : t.filters) {
    const FilterRow& row = row_of(f.coordinate);
    if (row.follows && paired(row, t)) continue;
    units.length += row.units.length;
    units.steradians += row.units.steradians;
    units.seconds += row.units.seconds;
    units.radians += row.units.radians;
  }
  return units;
}

std::string description_of(const DeclaredTally& t) {
  constexpr std::array<std::string_view, declarable.size()> what = {
      "power leaving through the lit surface",
      "power leaving through the far side",
      "fluence rate (collision estimator)",
      "power absorbed",
      "collisions",
      "path travelled by the light leaving through the lit surface, times its power (over the "
      "exitance: the mean path)"};
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
                       "\"exitance\" and \"path_length\" (a geometry with a surface, not a "
                       "slab's path), \"transmittance\" (a slab), \"fluence\" and "
                       "\"collisions\" (not a slab) or \"absorbed\"");
    };
    const bool leaves = t.score == Score::exitance || t.score == Score::path_length;
    if (leaves && frame.surface == ExitSurface::none) {
      refuse_score("it has no surface to leave through");
    }
    // A slab's walk keeps each photon's optical path, n l layer by layer (for its time), not
    // its length.
    if (t.score == Score::path_length && frame.transmits) {
      refuse_score("its walk keeps the optical path n l, not the path's length");
    }
    if (t.score == Score::transmittance && !frame.transmits) {
      refuse_score("only a slab has a far side");
    }
    if ((t.score == Score::fluence || t.score == Score::collisions) &&
        !frame.has_volume_estimator) {
      refuse_score("its walk scores no collisions in the volume");
    }
    const bool exits = leaves || t.score == Score::transmittance;
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
      d.filters.push_back(row.make(axis, t, frame, paired(row, t)));
      // The file's own axes: edges in the scene's units (orders, layers and triangles are
      // numbered).
      if (row.axis != FilterAxis::count && row.axis != FilterAxis::each) {
        const std::string unit = row.axis == FilterAxis::seconds ? "s"
                                 : row.axis == FilterAxis::angle ? "rad"
                                                                 : frame.length_unit;
        d.axes.push_back({std::string(row.key), axis.edges(), unit});
      }
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

std::optional<Coordinate> declared_filter(std::string_view name) {
  for (const FilterRow& row : filter_rows) {
    if (row.key == name) return row.coordinate;
  }
  return std::nullopt;
}

std::vector<DeclaredFilterKey> declared_filter_schema() {
  std::vector<DeclaredFilterKey> keys;
  for (const FilterRow& row : filter_rows) {
    keys.push_back({row.key, row.axis, row.range, row.geometries, row.meaning});
  }
  return keys;
}

}  // namespace scatterlab

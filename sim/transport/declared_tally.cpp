#include "scatterlab/transport/declared_tally.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <set>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

constexpr std::array<std::string_view, 4> score_names = {"exitance", "transmittance", "fluence",
                                                         "absorbed"};
constexpr int max_bins = 100'000;
// One tally's cells: past this its buffers (several per thread and batch) outgrow a machine.
constexpr double max_cells = 1e8;

std::string key(std::size_t i, std::string_view rest) {
  return fmt::format("tally[{}].{}", i + 1, rest);
}

void check_axis(const UniformAxis& axis, std::size_t i, std::string_view name, double walk_per_unit,
                std::string_view unit) {
  const std::string at = key(i, fmt::format("filters.{}", name));
  if (axis.bins < 1 || axis.bins > max_bins) {
    throw InputError(at + ".bins", fmt::format("is {}", axis.bins), "an integer in [1, 100000]");
  }
  if (!std::isfinite(axis.min) || !std::isfinite(axis.max) || !(axis.max > axis.min)) {
    throw InputError(at, fmt::format("spans [{}, {}]", axis.min, axis.max),
                     fmt::format("finite ends with max > min, in {}", unit));
  }
  if ((name == "r" || name == "t") && axis.min < 0.0) {
    throw InputError(at + ".min", fmt::format("is {}", axis.min), "a number >= 0");
  }
  if (name == "t") return;
  // The walk's units: as a grid's axes, finite bins of non-zero width (length_units.hpp).
  if (std::max(std::abs(axis.min), std::abs(axis.max)) * walk_per_unit > max_grid_mfp ||
      axis.width() * walk_per_unit < min_bin_mfp) {
    throw InputError(
        at, fmt::format("spans [{}, {}] {} in {} bins", axis.min, axis.max, unit, axis.bins),
        fmt::format("ends within {:g} mfp and bins at least {:g} mfp wide", max_grid_mfp,
                    min_bin_mfp));
  }
}

// The units of a tally of `score` over its filters: a length power k (from the filters' measures
// and the score's weight) and per joule with t, per watt without.
std::string units_of(const DeclaredTally& t, const std::string& length) {
  int power = t.score == DeclaredScore::fluence ? 1 : 0;  // a collision scores 1 mfp
  if (t.r) power -= 2;
  if (t.z) power -= 1;
  const std::string per = t.t ? "J" : "W";
  if (power == 0) return fmt::format("W per {} incident", per);
  if (power == 1) return fmt::format("W {} per {} incident", length, per);
  return fmt::format("W {}^{} per {} incident", length, power, per);
}

std::string description_of(const DeclaredTally& t) {
  std::string what;
  switch (t.score) {
    case DeclaredScore::exitance:
      what = "power leaving through the lit surface";
      break;
    case DeclaredScore::transmittance:
      what = "power leaving through the far side";
      break;
    case DeclaredScore::fluence:
      what = "fluence rate (collision estimator)";
      break;
    case DeclaredScore::absorbed:
      what = "power absorbed";
      break;
  }
  std::string per;
  if (t.r)
    per += t.score == DeclaredScore::fluence || t.score == DeclaredScore::absorbed
               ? ", per unit area of the ring at distance r from the beam axis"
               : ", per unit area at distance r from the beam axis";
  if (t.z) per += ", per unit depth z";
  if (t.t) per += ", per second of time of flight t after a unit impulse";
  return what + per + (t.r || t.z || t.t ? ", bin average" : ", in all");
}

}  // namespace

DeclaredTallyFrame homogeneous_frame(std::string_view geometry, const Medium& medium,
                                     std::optional<double> index) {
  DeclaredTallyFrame frame;
  frame.geometry = geometry;
  frame.has_surface = index.has_value();
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

DeclaredTallyFrame slab_frame(const std::string& length_unit) {
  DeclaredTallyFrame frame;
  frame.geometry = "slab";
  frame.transmits = true;
  frame.has_volume_estimator = false;
  frame.length_unit = length_unit;
  frame.walk_length_label = length_unit;
  if (length_unit != "mfp") {
    frame.seconds_per_walk_length = millimetres_per(length_unit) * 1e-3 / speed_of_light;
  }
  return frame;
}

std::string to_string(DeclaredScore score) {
  return std::string(score_names[static_cast<std::size_t>(score)]);
}

std::optional<DeclaredScore> declared_score(std::string_view name) {
  for (std::size_t i = 0; i < score_names.size(); ++i) {
    if (score_names[i] == name) return static_cast<DeclaredScore>(i);
  }
  return std::nullopt;
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
    const std::string score = to_string(t.score);
    const auto refuse_score = [&](std::string_view why) {
      throw InputError(key(i, "score"),
                       fmt::format("\"{}\" in a {} scene: {}", score, frame.geometry, why),
                       "\"exitance\" (a geometry with a surface), \"transmittance\" (a slab), "
                       "\"fluence\" (not a slab) or \"absorbed\"");
    };
    if (t.score == DeclaredScore::exitance && !frame.has_surface) {
      refuse_score("it has no surface to leave through");
    }
    if (t.score == DeclaredScore::transmittance && !frame.transmits) {
      refuse_score("only a slab has a far side");
    }
    if (t.score == DeclaredScore::fluence && !frame.has_volume_estimator) {
      refuse_score("its walk scores no collisions in the volume");
    }
    const bool exits =
        t.score == DeclaredScore::exitance || t.score == DeclaredScore::transmittance;
    if (exits && t.z) {
      throw InputError(key(i, "filters.z"), fmt::format("bins \"{}\"", score),
                       "filters r and t for a score at the surface: it has no depth");
    }
    if (t.r) check_axis(*t.r, i, "r", frame.walk_per_unit, frame.length_unit);
    if (t.z) check_axis(*t.z, i, "z", frame.walk_per_unit, frame.length_unit);
    if (t.t) {
      check_axis(*t.t, i, "t", 1.0, "s");
      if (frame.length_unit == "mfp") {
        throw InputError(
            key(i, "filters.t"),
            fmt::format("is asked in a {} scene whose lengths are in mfp", frame.geometry),
            "a scene with a physical length unit (\"um\", \"mm\", \"cm\" or \"m\") "
            "and its coefficients in it: time needs lengths in metres");
      }
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
    if (t.t && !frame.has_index && !t.group_index) {
      throw InputError(key(i, "group_index"), "is missing",
                       fmt::format("the medium's group index (e.g. 1.4) for the time of flight "
                                   "in a {} scene, which has no index of its own",
                                   frame.geometry));
    }
    double cells = 1.0;
    for (const auto& axis : {t.r, t.z, t.t}) {
      if (axis) cells *= axis->bins;
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
    static constexpr Score scores[] = {Score::exit, Score::transmitted, Score::fluence,
                                       Score::absorbed};
    TallyDeclaration d{t.name,
                       scores[static_cast<std::size_t>(t.score)],
                       {},
                       units_of(t, frame.walk_length_label),
                       description_of(t)};
    d.chained = true;
    // Space before time, as the file's dims read: r, z, t.
    if (t.r) {
      d.filters.push_back(radius_filter(length_axis_in_mfp(*t.r, frame.walk_per_unit)));
      d.axes.push_back({"r", t.r->edges(), frame.length_unit});
    }
    if (t.z) {
      d.filters.push_back(depth_filter(length_axis_in_mfp(*t.z, frame.walk_per_unit)));
      d.axes.push_back({"z", t.z->edges(), frame.length_unit});
    }
    if (t.t) {
      const double index = t.group_index.value_or(frame.index);
      d.filters.push_back(time_filter(*t.t, frame.seconds_per_walk_length * index));
      d.axes.push_back({"t", t.t->edges(), "s"});
    }
    declarations.push_back(std::move(d));
  }
  return declarations;
}

std::string fingerprint_text(const std::vector<DeclaredTally>& tallies) {
  std::string text;
  const auto axis = [](const std::optional<UniformAxis>& a) {
    return a ? fmt::format("{:a} {:a} {}", a->min, a->max, a->bins) : std::string("-");
  };
  for (const DeclaredTally& t : tallies) {
    text += fmt::format("tally {} {}|r {}|z {}|t {}|n {}|", t.name, to_string(t.score), axis(t.r),
                        axis(t.z), axis(t.t),
                        t.group_index ? fmt::format("{:a}", *t.group_index) : "-");
  }
  return text;
}

}  // namespace scatterlab

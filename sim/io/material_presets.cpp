#include "scatterlab/io/material_presets.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/toml_reader.hpp"

namespace scatterlab {

namespace detail {
// (file stem, text) of every data/materials/*.toml, in file-name order: defined in the source
// that CMake generates from sim/io/material_tables.cpp.in.
std::vector<std::pair<std::string_view, std::string_view>> material_table_texts();
}  // namespace detail

namespace {

void check_keys(const toml::table& table, const std::string& path,
                const std::set<std::string>& accepted) {
  for (const auto& [key, node] : table) {
    if (!accepted.contains(std::string(key.str()))) {
      std::string list;
      for (const auto& a : accepted) list += (list.empty() ? "" : ", ") + a;
      throw InputError(path + "." + std::string(key.str()), "unknown key", list);
    }
  }
}

std::string string_at(const toml::table& table, const std::string& path, const char* key) {
  const auto* value = table.get_as<std::string>(key);
  if (value == nullptr) throw InputError(path + "." + key, "missing or not a string", "a string");
  return value->get();
}

// An array of one number per channel: coefficients >= 0, or (mean_cosine) HG g with |g| < 1.
std::vector<double> numbers_at(const toml::table& table, const std::string& path, const char* key,
                               std::size_t expected, bool required, bool mean_cosine = false) {
  const std::string field = path + "." + key;
  const std::string range = mean_cosine ? "numbers with |g| < 1" : "numbers >= 0";
  const toml::node* node = table.get(key);
  if (node == nullptr) {
    if (required) throw InputError(field, "missing", "an array of " + range);
    return {};
  }
  const toml::array* array = node->as_array();
  const std::string accepted = std::to_string(expected) + " " + range + ", one per channel";
  if (array == nullptr || array->size() != expected)
    throw InputError(field, "wrong shape", accepted);
  std::vector<double> values;
  for (const toml::node& element : *array) {
    const auto value = element.value<double>();
    const bool in_range =
        value && std::isfinite(*value) && (mean_cosine ? std::abs(*value) < 1.0 : *value >= 0.0);
    if (!in_range) throw InputError(field, "holds a value out of range", accepted);
    values.push_back(*value);
  }
  return values;
}

// Lower case, without spaces, hyphens or underscores, so that a name matches however its words
// are joined: "Regular Milk", "regular-milk" and "regular_milk" are "regularmilk", and "skim milk"
// is Jensen's "skimmilk".
std::string normalised(std::string_view name) {
  std::string key;
  for (const char c : name) {
    if (c != ' ' && c != '-' && c != '_') {
      key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  return key;
}

std::string join(const std::vector<std::string>& names, const char* separator) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : separator) + name;
  return joined;
}

}  // namespace

const MaterialPreset& MaterialLibrary::find(std::string_view name) const {
  std::string known;
  for (const MaterialPreset& m : materials) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw InputError("material", "no preset named \"" + std::string(name) + "\"", known);
}

MaterialLibrary parse_material_library(std::string_view toml_text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << origin << ":" << e.source().begin.line << ":" << e.source().begin.column << ": "
          << e.description();
    throw InputError("materials", where.str(), "a TOML file as data/materials/jensen2001.toml");
  }
  check_keys(root, "", {"source", "materials"});
  const toml::table* source = root["source"].as_table();
  if (source == nullptr) throw InputError("source", "missing", "a [source] table");
  check_keys(*source, "source", {"citation", "length_unit", "eta", "channels"});
  MaterialLibrary library;
  library.citation = string_at(*source, "source", "citation");
  library.length_unit = string_at(*source, "source", "length_unit");
  if (library.length_unit != "um" && library.length_unit != "mm" && library.length_unit != "cm" &&
      library.length_unit != "m") {
    throw InputError("source.length_unit", "got \"" + library.length_unit + "\"",
                     "um, mm, cm or m");
  }
  const auto eta = source->get_as<double>("eta");
  if (eta == nullptr || !(eta->get() >= 0.5 && eta->get() <= 2.5)) {
    throw InputError("source.eta", "missing or out of range", "a number in [0.5, 2.5]");
  }
  library.eta = eta->get();
  const toml::array* channels = (*source)["channels"].as_array();
  if (channels == nullptr || channels->empty()) {
    throw InputError("source.channels", "missing or empty", "an array of channel names");
  }
  for (const toml::node& c : *channels) {
    const auto name = c.value<std::string>();
    if (!name) throw InputError("source.channels", "holds a non-string", "an array of names");
    library.channels.push_back(*name);
  }
  const toml::table* materials = root["materials"].as_table();
  if (materials == nullptr || materials->empty()) {
    throw InputError("materials", "missing or empty", "[materials.<name>] tables");
  }
  for (const auto& [key, node] : *materials) {
    const std::string path = "materials." + std::string(key.str());
    const toml::table* table = node.as_table();
    if (table == nullptr) throw InputError(path, "not a table", "a [" + path + "] table");
    check_keys(*table, path, {"sigma_s_reduced", "sigma_s", "g", "sigma_a", "diffuse_reflectance"});
    MaterialPreset preset;
    preset.name = std::string(key.str());
    const std::size_t n = library.channels.size();
    const bool reduced = table->get("sigma_s_reduced") != nullptr;
    if (reduced == (table->get("sigma_s") != nullptr)) {
      throw InputError(path + (reduced ? ".sigma_s" : ".sigma_s_reduced"),
                       reduced ? "given together with sigma_s_reduced" : "missing",
                       "either sigma_s_reduced (no g known) or sigma_s with g");
    }
    if (reduced) {
      preset.sigma_s_reduced = numbers_at(*table, path, "sigma_s_reduced", n, true);
      if (table->get("g") != nullptr) {
        throw InputError(
            path + ".g", "given with sigma_s_reduced",
            "g only with sigma_s (sigma_s_reduced = sigma_s (1 - g) already holds it)");
      }
    } else {
      preset.sigma_s = numbers_at(*table, path, "sigma_s", n, true);
      preset.g = numbers_at(*table, path, "g", n, true, true);
    }
    preset.sigma_a = numbers_at(*table, path, "sigma_a", n, true);
    preset.diffuse_reflectance = numbers_at(*table, path, "diffuse_reflectance", n, false);
    library.materials.push_back(std::move(preset));
  }
  return library;
}

MaterialLibrary load_material_library(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw InputError("materials", "cannot read " + path.string(), "a readable TOML file");
  std::ostringstream text;
  text << file.rdbuf();
  MaterialLibrary library = parse_material_library(text.str(), path.string());
  library.id = path.stem().string();
  return library;
}

const std::vector<MaterialLibrary>& shipped_material_libraries() {
  static const std::vector<MaterialLibrary> libraries = [] {
    std::vector<MaterialLibrary> parsed;
    for (const auto& [stem, text] : detail::material_table_texts()) {
      parsed.push_back(
          parse_material_library(text, "data/materials/" + std::string(stem) + ".toml"));
      parsed.back().id = std::string(stem);
    }
    return parsed;
  }();
  return libraries;
}

ResolvedMaterial resolve_material(const MaterialRequest& request, const MaterialFields& fields,
                                  const std::vector<MaterialLibrary>& libraries) {
  // Which library: a qualified name names it; otherwise every library is searched.
  const std::string wanted = normalised(request.name);
  const std::size_t slash = wanted.find('/');
  const std::string library_part = slash == std::string::npos ? "" : wanted.substr(0, slash);
  const std::string name_part = slash == std::string::npos ? wanted : wanted.substr(slash + 1);
  std::vector<std::pair<const MaterialLibrary*, const MaterialPreset*>> found;
  std::vector<std::string> accepted, candidates;
  for (const MaterialLibrary& library : libraries) {
    std::vector<std::string> names;
    for (const MaterialPreset& preset : library.materials) {
      names.push_back(preset.name);
      candidates.push_back(preset.name);
      candidates.push_back(library.id + "/" + preset.name);
      if ((library_part.empty() || library_part == normalised(library.id)) &&
          normalised(preset.name) == name_part) {
        found.emplace_back(&library, &preset);
      }
    }
    accepted.push_back(library.id + ": " + join(names, ", "));
  }
  if (found.empty()) {
    const auto nearest = nearest_name(wanted, candidates);
    const std::string hint = nearest ? " (did you mean \"" + *nearest + "\"?)" : "";
    throw InputError(fields.material, "no material named \"" + request.name + "\"" + hint,
                     "a name from a table in data/materials, optionally qualified as "
                     "table/name: " +
                         join(accepted, "; "));
  }
  if (found.size() > 1) {
    std::vector<std::string> qualified;
    for (const auto& [library, preset] : found)
      qualified.push_back(library->id + "/" + preset->name);
    throw InputError(fields.material, "\"" + request.name + "\" is in more than one table",
                     "a qualified name: " + join(qualified, " or "));
  }
  const MaterialLibrary& library = *found.front().first;
  const MaterialPreset& preset = *found.front().second;

  const std::string channels = join(library.channels, ", ");
  if (!request.channel) {
    throw InputError(fields.channel,
                     "missing: material \"" + preset.name + "\" has one value per channel",
                     "one of " + channels + " (one run per channel)");
  }
  const auto at = std::find(library.channels.begin(), library.channels.end(), *request.channel);
  if (at == library.channels.end()) {
    throw InputError(fields.channel, "got \"" + *request.channel + "\"", "one of " + channels);
  }
  const auto k = static_cast<std::size_t>(at - library.channels.begin());

  const std::string unit = request.length_unit.value_or(library.length_unit);
  if (!is_physical_length_unit(unit)) {
    throw InputError(fields.length_unit,
                     "got \"" + unit + "\" with material \"" + preset.name +
                         "\", whose coefficients are physical",
                     "\"um\", \"mm\", \"cm\" or \"m\" (\"mfp\" only without a material)");
  }
  // A coefficient per table unit is (unit / table unit) times as large per requested unit.
  const double scale = millimetres_per(unit) / millimetres_per(library.length_unit);
  if (request.g && !(std::abs(*request.g) < 1.0)) {
    throw InputError(fields.g, "got " + std::to_string(*request.g), "a number with |g| < 1");
  }

  MaterialOrigin origin{preset.name, library.id, *request.channel, library.citation, ""};
  double sigma_s = 0.0;
  double g = 0.0;
  if (!preset.sigma_s.empty()) {
    sigma_s = preset.sigma_s[k];
    g = request.g.value_or(preset.g[k]);
    if (request.g) origin.note = "g set by the user; sigma_s and sigma_a as tabulated";
  } else {
    // Only sigma_s' = sigma_s (1 - g) is measured: g = 0 unless asked, sigma_s' kept (similarity
    // relation, Bitterli 2013 eqs. 2.23-2.24).
    g = request.g.value_or(0.0);
    sigma_s = preset.sigma_s_reduced[k] / (1.0 - g);
    origin.note = request.g ? "the table gives sigma_s' only: sigma_s = sigma_s' / (1 - g) with "
                              "the user's g (similarity relation)"
                            : "the table gives sigma_s' only: g = 0, sigma_s = sigma_s' "
                              "(similarity relation)";
  }
  ResolvedMaterial resolved;
  resolved.medium = Medium::from_coefficients(preset.sigma_a[k] * scale, sigma_s * scale, g, unit);
  resolved.origin = std::move(origin);
  resolved.eta = library.eta;
  return resolved;
}

}  // namespace scatterlab

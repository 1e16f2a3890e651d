#include "scatterlab/io/material_presets.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "scatterlab/core/error.hpp"

namespace scatterlab {
namespace {

void check_keys(const toml::table& table, const std::string& path, const std::set<std::string>& accepted) {
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

std::vector<double> numbers_at(const toml::table& table, const std::string& path, const char* key,
                               std::size_t expected, bool required) {
  const std::string field = path + "." + key;
  const toml::node* node = table.get(key);
  if (node == nullptr) {
    if (required) throw InputError(field, "missing", "an array of numbers >= 0");
    return {};
  }
  const toml::array* array = node->as_array();
  const std::string accepted = std::to_string(expected) + " numbers >= 0, one per channel";
  if (array == nullptr || array->size() != expected) throw InputError(field, "wrong shape", accepted);
  std::vector<double> values;
  for (const toml::node& element : *array) {
    const auto value = element.value<double>();
    if (!value || !(*value >= 0.0) || !std::isfinite(*value)) {
      throw InputError(field, "holds a value that is not a finite number >= 0", accepted);
    }
    values.push_back(*value);
  }
  return values;
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
    throw InputError("source.length_unit", "got \"" + library.length_unit + "\"", "um, mm, cm or m");
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
    check_keys(*table, path, {"sigma_s_reduced", "sigma_a", "diffuse_reflectance"});
    MaterialPreset preset;
    preset.name = std::string(key.str());
    const std::size_t n = library.channels.size();
    preset.sigma_s_reduced = numbers_at(*table, path, "sigma_s_reduced", n, true);
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
  return parse_material_library(text.str(), path.string());
}

}  // namespace scatterlab

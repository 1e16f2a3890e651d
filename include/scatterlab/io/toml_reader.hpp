#pragma once
// Strict reading of TOML files (scene files of every command): unknown keys and tables with a
// suggestion for typos, wrong types and out-of-range integers, each an InputError naming the
// dotted key, what it got (with file:line:column) and what is accepted. Included only by .cpp
// files that read TOML (io's scenes, render's scenes), which link toml++ privately: no other
// header exposes it.

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/spelling.hpp"
#include "scatterlab/io/text_file.hpp"

namespace scatterlab::toml_reading {

using Keys = std::initializer_list<std::string_view>;

template <class Names = Keys>
std::string join(const Names& keys, std::string_view before = "", std::string_view after = "") {
  std::string joined;
  for (const auto key : keys) {
    if (!joined.empty()) joined += ", ";
    joined += fmt::format("{}{}{}", before, key, after);
  }
  return joined;
}

inline std::string dotted(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

template <class Names = Keys>
std::string suggestion(std::string_view key, const Names& accepted) {
  const auto nearest = nearest_name(key, accepted);
  return nearest ? fmt::format(", did you mean \"{}\"?", *nearest) : "";
}

// A value as the user wrote it, for messages: `a string ("abc")`, `an integer (-3)`.
inline std::string describe(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return fmt::format("a string (\"{}\")", node.as_string()->get());
    case toml::node_type::integer:
      return fmt::format("an integer ({})", node.as_integer()->get());
    case toml::node_type::floating_point:
      return fmt::format("a float ({})", node.as_floating_point()->get());
    case toml::node_type::boolean:
      return fmt::format("a boolean ({})", node.as_boolean()->get());
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// Reads one parsed document into a Scene, checking names and types as it goes; ranges are left

// Reads values out of parsed tables; `origin` names the text in messages.
class TomlReader {
 public:
  explicit TomlReader(const std::string& origin) : origin_(origin) {}

  std::string at(const toml::source_region& region) const {
    return fmt::format(" ({}:{}:{})", origin_, region.begin.line, region.begin.column);
  }
  std::string at(const toml::node& node) const { return at(node.source()); }

  [[noreturn]] void wrong_type(const toml::node& node, const std::string& field,
                               std::string_view accepted) const {
    throw InputError(field, "got " + describe(node) + at(node), std::string(accepted));
  }

  void check_keys(const toml::table& table, const std::string& path, Keys accepted) const {
    check_names(table, path, accepted);
  }

  // The same for any range of names (a schema's: io/scene_schema.hpp).
  template <class Names>
  void check_names(const toml::table& table, const std::string& path, const Names& accepted) const {
    for (auto&& [key, node] : table) {
      const std::string_view name = key.str();
      if (std::find(accepted.begin(), accepted.end(), name) != accepted.end()) continue;
      const bool is_table = node.is_table();
      const std::string what = std::string(is_table ? "unknown table" : "unknown key") +
                               (path.empty() ? "" : " in [" + path + "]");
      throw InputError(dotted(path, name), what + suggestion(name, accepted) + at(key.source()),
                       path.empty() ? join(accepted, "[", "]") : join(accepted));
    }
  }

  // The sub-table `key`, or nullptr when absent.
  const toml::table* subtable(const toml::table& parent, std::string_view key,
                              const std::string& path) const {
    const toml::node* node = parent.get(key);
    if (node == nullptr) return nullptr;
    if (!node->is_table()) wrong_type(*node, dotted(path, key), "a table");
    return node->as_table();
  }

  std::optional<double> number(const toml::table& table, std::string_view key,
                               const std::string& path, std::string_view accepted) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return std::nullopt;
    if (const auto* value = node->as_floating_point()) return value->get();
    // An integer where a number is expected is fine: albedo = 1 means 1.0.
    if (const auto* value = node->as_integer()) return static_cast<double>(value->get());
    wrong_type(*node, dotted(path, key), accepted);
  }

  // Three numbers, [x, y, z].
  std::optional<std::array<double, 3>> vector3(const toml::table& table, std::string_view key,
                                               const std::string& path,
                                               std::string_view accepted) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return std::nullopt;
    const toml::array* list = node->as_array();
    if (list == nullptr || list->size() != 3) wrong_type(*node, dotted(path, key), accepted);
    std::array<double, 3> values{};
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node& item = *list->get(i);
      if (const auto* value = item.as_floating_point()) {
        values[i] = value->get();
      } else if (const auto* whole = item.as_integer()) {
        values[i] = static_cast<double>(whole->get());
      } else {
        wrong_type(item, dotted(path, key), accepted);
      }
    }
    return values;
  }

  // An integer, or a float that is a whole number (photons = 1e7).
  std::optional<std::int64_t> integer(const toml::table& table, std::string_view key,
                                      const std::string& path, std::string_view accepted) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return std::nullopt;
    if (const auto* value = node->as_integer()) return value->get();
    if (const auto* value = node->as_floating_point()) {
      const double x = value->get();
      // 2^63 is exact in a double; every whole double below it converts exactly.
      constexpr double limit = 9223372036854775808.0;
      if (std::isfinite(x) && std::trunc(x) == x && x >= -limit && x < limit) {
        return static_cast<std::int64_t>(x);
      }
      throw InputError(dotted(path, key),
                       fmt::format("got {}, which is not a whole number{}", x, at(*node)),
                       std::string(accepted));
    }
    wrong_type(*node, dotted(path, key), accepted);
  }

  // An integer converted to T, which must hold it; `lowest` (>= 0) and `highest` bound the values
  // accepted here (finer ranges are checked by each spec's validate()).
  template <typename T>
  std::optional<T> integer_as(
      const toml::table& table, std::string_view key, const std::string& path, std::int64_t lowest,
      std::string_view accepted,
      std::int64_t highest = std::numeric_limits<std::int64_t>::max()) const {
    const auto value = integer(table, key, path, accepted);
    if (!value) return std::nullopt;
    const bool fits =
        *value >= lowest && *value <= highest &&
        *value >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
        static_cast<std::uint64_t>(*value) <= std::uint64_t{std::numeric_limits<T>::max()};
    if (!fits) {
      throw InputError(dotted(path, key), fmt::format("got {}{}", *value, at(*table.get(key))),
                       std::string(accepted));
    }
    return static_cast<T>(*value);
  }

  std::optional<bool> boolean(const toml::table& table, std::string_view key,
                              const std::string& path) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return std::nullopt;
    if (const auto* value = node->as_boolean()) return value->get();
    wrong_type(*node, dotted(path, key), "true or false");
  }

  std::optional<std::string> string(const toml::table& table, std::string_view key,
                                    const std::string& path, std::string_view accepted) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return std::nullopt;
    if (const auto* value = node->as_string()) return value->get();
    wrong_type(*node, dotted(path, key), accepted);
  }

 private:
  std::string origin_;
};

// A TOML syntax error is an InputError for "scene" starting "<origin>:<line>:<column>:".
inline toml::table parse_toml(std::string_view toml_text, const std::string& origin) {
  try {
    return toml::parse(toml_text, origin);
  } catch (const toml::parse_error& error) {
    const auto& begin = error.source().begin;
    throw InputError(
        "scene", fmt::format("{}:{}:{}: {}", origin, begin.line, begin.column, error.description()),
        "a valid TOML file");
  }
}

// The scene file's text: a regular file of at most 1 MiB (io/text_file.hpp).
inline std::string read_text(const std::filesystem::path& path) {
  return read_scene_file(path, "scene");
}

}  // namespace scatterlab::toml_reading

#include "request_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "scatterlab/core/error.hpp"
#include "scatterlab/explore/api.hpp"

namespace scatterlab::explore_request {

namespace fs = std::filesystem;

json parse_body(std::string_view body) {
  json parsed = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded() || !parsed.is_object()) {
    throw InputError("body", "not a JSON object", "a JSON object (see the API in docs/guide/explorer.md)");
  }
  return parsed;
}

double number(const json& object, const std::string& key, const std::string& field,
              std::optional<double> fallback) {
  const auto found = object.find(key);
  if (found == object.end() || found->is_null()) {
    if (fallback) return *fallback;
    throw InputError(field, "missing", "a finite number");
  }
  if (!found->is_number() || !std::isfinite(found->get<double>())) {
    throw InputError(field, "got " + found->dump(), "a finite number");
  }
  return found->get<double>();
}

int whole(const json& object, const std::string& key, const std::string& field, int fallback,
          int lowest, int highest) {
  const double value = number(object, key, field, fallback);
  if (value != std::trunc(value) || value < lowest || value > highest) {
    throw InputError(field, fmt::format("got {}", value),
                     fmt::format("a whole number in [{}, {}]", lowest, highest));
  }
  return static_cast<int>(value);
}

double scale_of(const json& request) {
  const double scale = number(request, "scale", "scale", 1.0);
  if (!(scale > 0.0)) {
    throw InputError("scale", fmt::format("got {}", scale), "a finite number > 0");
  }
  return scale;
}

HalfSpaceMedium medium_of(const json& m, const std::string& field, double scale) {
  if (!m.is_object()) {
    throw InputError(field, "missing or not an object",
                     "{\"sigma_a\", \"sigma_s\" or \"sigma_s_reduced\", \"g\", \"eta\"}");
  }
  for (const auto& [key, value] : m.items()) {
    static const std::set<std::string> known{"sigma_a", "sigma_s", "sigma_s_reduced", "g", "eta"};
    if (!known.contains(key)) {
      throw InputError(field + "." + key, "unknown key",
                       "sigma_a, sigma_s, sigma_s_reduced, g, eta");
    }
  }
  HalfSpaceMedium medium;
  medium.g = number(m, "g", field + ".g", 0.0);
  medium.eta = number(m, "eta", field + ".eta", 1.0);
  medium.sigma_a = number(m, "sigma_a", field + ".sigma_a") * scale;
  const bool plain = m.contains("sigma_s"), reduced = m.contains("sigma_s_reduced");
  if (plain == reduced) {
    throw InputError(field + ".sigma_s", plain ? "given with sigma_s_reduced" : "missing",
                     "exactly one of sigma_s and sigma_s_reduced (= sigma_s (1 - g))");
  }
  medium.validate();  // g first: sigma_s_reduced is divided by 1 - g
  // Similarity relation (Bitterli 2013 eq. 2.24): sigma_s = sigma_s' / (1 - g).
  medium.sigma_s =
      plain ? number(m, "sigma_s", field + ".sigma_s") * scale
            : number(m, "sigma_s_reduced", field + ".sigma_s_reduced") * scale / (1.0 - medium.g);
  medium.validate();
  if (!(medium.sigma_t() > 0.0) || !std::isfinite(medium.sigma_t())) {
    throw InputError(field + ".sigma_a", "sigma_a + sigma_s is 0 or not finite",
                     "coefficients whose sum is finite and > 0");
  }
  return medium;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::vector<OpenFile> open_files(const std::vector<fs::path>& folders,
                                 const std::string& extension) {
  std::vector<OpenFile> list;
  for (std::size_t i = 0; i < folders.size(); ++i) {
    const fs::path& folder = folders[i];
    std::vector<OpenFile> found;
    std::error_code error;
    for (auto it = fs::recursive_directory_iterator(folder, error);
         !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
      if (it.depth() > 3) it.disable_recursion_pending();
      if (it->is_regular_file() && it->path().extension() == extension) {
        const std::string name = fs::relative(it->path(), folder).generic_string();
        found.push_back({fmt::format("{}/{}", i, name), folder, it->path(), name});
      }
    }
    std::sort(found.begin(), found.end(),
              [](const OpenFile& a, const OpenFile& b) { return a.name < b.name; });
    list.insert(list.end(), found.begin(), found.end());
  }
  return list;
}

OpenFile resolve_open_file(const std::vector<fs::path>& folders, const std::string& path,
                           const std::string& field, const std::string& extension,
                           const std::string& accepted_kind) {
  const std::string accepted =
      fmt::format("I/NAME: the index I of an open folder and the name of {} in it", accepted_kind);
  const auto slash = path.find('/');
  std::size_t index = 0;
  try {
    std::size_t used = 0;
    index = std::stoul(path.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument(field);
  } catch (const std::exception&) {
    throw InputError(field, fmt::format("got \"{}\"", path), accepted);
  }
  if (slash == std::string::npos || index >= folders.size()) {
    throw InputError(field, fmt::format("got \"{}\" ({} open folders)", path, folders.size()),
                     accepted);
  }
  const fs::path& folder = folders[index];
  const fs::path candidate = folder / fs::path(path.substr(slash + 1));
  if (!lies_inside(candidate, folder)) {
    throw ApiRefusal{
        403, fmt::format("{}: {} lies outside the open folder {}", field, path, folder.string())};
  }
  std::error_code error;
  if (!fs::is_regular_file(candidate, error) || candidate.extension() != extension) {
    throw InputError(field, fmt::format("{} is not a file of the folder", path), accepted_kind);
  }
  return {path, folder, candidate, path.substr(slash + 1)};
}

std::map<std::string, double> text_model_parameters(const json& request, const std::string& model) {
  const json parameters = request.value("parameters", json::object());
  if (!parameters.is_object()) {
    throw InputError("parameters", "not an object", "{model: {parameter: value}}");
  }
  std::map<std::string, double> values;
  if (const auto set = parameters.find(model); set != parameters.end()) {
    if (!set->is_object())
      throw InputError("parameters." + model, "not an object", "{name: value}");
    for (const auto& [key, value] : set->items())
      values[key] = number(*set, key, "parameters." + key);
  }
  return values;
}

}  // namespace scatterlab::explore_request

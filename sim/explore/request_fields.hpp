#pragma once
// The explorer's requests read field by field (api.cpp, mesh_view.cpp): a JSON body, its numbers,
// its media and the open folders' files, each refusal an InputError naming the field or an
// ApiRefusal with its HTTP status. Private to the explore module.

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab::explore_request {

using json = nlohmann::json;

// A request the API refuses with a status other than 400: its status and message.
struct ApiRefusal {
  int status;
  std::string message;
};

json parse_body(std::string_view body);

// object[key] as a finite number (InputError(field, ...) otherwise); `fallback` when missing.
double number(const json& object, const std::string& key, const std::string& field,
              std::optional<double> fallback = std::nullopt);
// The same, a whole number in [lowest, highest].
int whole(const json& object, const std::string& key, const std::string& field, int fallback,
          int lowest, int highest);

// The medium of object `m` (named `field` in errors) in the plot's unit: its coefficients times
// `scale` (api.hpp: sigma_a, sigma_s or sigma_s_reduced, g, eta).
HalfSpaceMedium medium_of(const json& m, const std::string& field, double scale);
// request["scale"], > 0, 1 when missing.
double scale_of(const json& request);

double milliseconds_since(std::chrono::steady_clock::time_point start);

// The values request["parameters"][model] gives a text model's parameters, by name (an object of
// numbers; InputError "parameters.<model>" or "parameters.<name>" otherwise); empty when absent.
std::map<std::string, double> text_model_parameters(const json& request, const std::string& model);

// A file of an open folder as the page names it: "I/NAME", the index I of an open folder and a
// file's name in it.
struct OpenFile {
  std::string path;  // I/NAME
  std::filesystem::path folder, file;
  std::string name;  // NAME
};
// The files with `extension` (".h5", ".obj") in the open folders, up to four levels deep, sorted
// by name within each folder.
std::vector<OpenFile> open_files(const std::vector<std::filesystem::path>& folders,
                                 const std::string& extension);
// The file "I/NAME" (`field` in errors): InputError when it is malformed or no file with
// `extension`; ApiRefusal 403 when it lies outside its open folder (after symbolic links).
OpenFile resolve_open_file(const std::vector<std::filesystem::path>& folders,
                           const std::string& path, const std::string& field,
                           const std::string& extension, const std::string& accepted_kind);

}  // namespace scatterlab::explore_request

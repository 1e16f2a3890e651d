// The explorer's requests as its server hands them to the API (explore/api.hpp, server.cpp): the
// input's first line is the method and the target (a path with an optional ?query, decoded as
// cpp-httplib decodes them), the rest is the body. The API answers every refusal itself, with a
// status and a JSON error, so only a crash (or an answer without a body) is a finding here; with
// SCATTERLAB_FUZZ_STRICT=1 an answer of 500 is one too (a request refused as a failure of the
// server, not as bad input).

#include <httplib.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "scatterlab/explore/api.hpp"

namespace {

using namespace scatterlab;

std::unique_ptr<const ExploreApi> api;

// request[key] as a number, `fallback` (the API's default) when it is missing; a value that is not
// a number is refused by the API at once, and counts as nothing here.
double size_of(const nlohmann::json& request, const char* key, double fallback) {
  if (!request.is_object() || !request.contains(key)) return fallback;
  const nlohmann::json& value = request[key];
  return value.is_number() ? value.get<double>() : 0.0;
}

// Within their documented ranges some sizes run for minutes under the sanitizers: a lit sphere of
// 90 bins x 65536 samples, a cloud of 65536 points relaxed 200 times, a sphere of 4096 x 4096
// facets (explore/api.hpp, mesh_view.hpp). Larger sizes run the same code longer; requests for
// them are left out, so that a time-out stands for a hang.
bool within_budget(std::string_view path, std::string_view body) {
  const nlohmann::json request = nlohmann::json::parse(body, nullptr, false);
  if (path == "/api/lit_sphere") {
    return size_of(request, "bins", 36) * size_of(request, "samples", 2048) <= 36 * 256;
  }
  if (path == "/api/mesh_exitance") {
    const nlohmann::json mesh =
        request.is_object() ? request.value("mesh", nlohmann::json()) : nlohmann::json();
    return size_of(request, "points", 4096) <= 64 && size_of(request, "relaxation", 40) <= 4 &&
           size_of(mesh, "rings", 24) <= 64 && size_of(mesh, "segments", 48) <= 64;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scatterlab::fuzz::limit_memory();
  const std::filesystem::path source(SCATTERLAB_SOURCE_DIR);
  const std::filesystem::path corpus = std::filesystem::path(SCATTERLAB_FUZZ_DIR) / "corpus";
  ExploreOptions options;
  options.page = source / "web";
  // Files the requests may name: "0/NAME.h5" and "1/NAME.obj" (read only).
  options.open_folders = {corpus / "hdf5_file", corpus / "obj_mesh"};
  options.models = source / "data" / "models";
  (void)fuzz::work_folder();
  api = std::make_unique<const ExploreApi>(options);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = fuzz::text_of(data, size);
  const std::size_t line_end = input.find('\n');
  const std::string_view line = input.substr(0, line_end);
  const std::string_view body =
      line_end == std::string_view::npos ? std::string_view() : input.substr(line_end + 1);
  const std::size_t space = line.find(' ');
  if (space == std::string_view::npos) return -1;
  const std::string method(line.substr(0, space));
  const std::string_view target = line.substr(space + 1);
  const std::size_t question = target.find('?');
  const std::string path = httplib::detail::decode_url(std::string(target.substr(0, question)),
                                                       /*convert_plus_to_space=*/false);
  httplib::Params params;
  if (question != std::string_view::npos) {
    httplib::detail::parse_query_text(std::string(target.substr(question + 1)), params);
  }
  if (!within_budget(path, body)) return -1;
  std::map<std::string, std::string> query;
  for (const auto& [key, value] : params) query.emplace(key, value);

  const ApiResponse response = api->handle(method, path, query, body);
  if (response.body.empty() && response.file.empty()) {
    fuzz::finding("an answer of status " + std::to_string(response.status) + " without a body");
  }
  if (fuzz::strict() && response.status == 500) {
    fuzz::finding("status 500: " + response.body);
  }
  return 0;
}

#include "scatterlab/explore/server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <sys/socket.h>

#include <fstream>
#include <iterator>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

struct ExploreServer::Impl {
  httplib::Server server;
};

ExploreServer::ExploreServer(const ExploreApi& api, const std::string& host, int port)
    : impl_(std::make_unique<Impl>()) {
  if (port < 0 || port > 65535) {
    throw InputError("port", fmt::format("got {}", port), "0 (any free port) to 65535");
  }
  httplib::Server& server = impl_->server;
  server.set_payload_max_length(std::size_t{1} << 20);
  // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a second explorer would
  // share a port already in use instead of being told that it is.
  server.set_socket_options([](int socket) {
    int yes = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  const auto answer = [&api](const httplib::Request& request, httplib::Response& response) {
    std::map<std::string, std::string> query;
    for (const auto& [key, value] : request.params) query.emplace(key, value);
    const ApiResponse result = api.handle(request.method, request.path, query, request.body);
    response.status = result.status;
    if (!result.file.empty()) {
      std::ifstream in(result.file, std::ios::binary);
      std::string contents{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      response.set_content(std::move(contents), result.content_type.c_str());
    } else {
      response.set_content(result.body, result.content_type.c_str());
    }
    // The page and its data come from this server only.
    response.set_header("Cache-Control", "no-store");
    response.set_header("X-Content-Type-Options", "nosniff");
  };
  server.Get(".*", answer);
  server.Post(".*", answer);
  server.Put(".*", answer);
  server.Delete(".*", answer);
  server.Patch(".*", answer);
  // What httplib itself refuses (a body over the limit, a malformed request) gets JSON too.
  server.set_error_handler([](const httplib::Request&, httplib::Response& response) {
    if (!response.body.empty()) return;
    response.set_content(fmt::format("{{\"error\": \"HTTP {}\"}}", response.status),
                         "application/json");
  });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& response, std::exception_ptr) {
        response.status = 500;
        response.set_content("{\"error\": \"internal error\"}", "application/json");
      });
  if (port == 0) {
    port_ = server.bind_to_any_port(host);
  } else {
    port_ = server.bind_to_port(host, port) ? port : -1;
  }
  if (port_ <= 0) {
    throw InputError("port", fmt::format("cannot listen on {}:{}", host, port),
                     "a free port on an address of this machine (--host, --port)");
  }
}

ExploreServer::~ExploreServer() = default;

void ExploreServer::run() {
  impl_->server.listen_after_bind();
}

void ExploreServer::stop() {
  impl_->server.stop();
}

}  // namespace scatterlab

#pragma once
// The explorer's HTTP server: cpp-httplib in front of ExploreApi (api.hpp), on one address and
// port, answering on a few threads. Request bodies over 1 MiB are refused (413).

#include <memory>
#include <string>

#include "scatterlab/explore/api.hpp"

namespace scatterlab {

class ExploreServer {
 public:
  // Binds host:port at once (port 0: a free port chosen by the system); throws
  // InputError("port", ...) when the address cannot be bound.
  ExploreServer(const ExploreApi& api, const std::string& host, int port);
  ~ExploreServer();
  ExploreServer(const ExploreServer&) = delete;
  ExploreServer& operator=(const ExploreServer&) = delete;

  int port() const { return port_; }
  // Answers requests until stop() is called (from another thread).
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int port_ = 0;
};

}  // namespace scatterlab

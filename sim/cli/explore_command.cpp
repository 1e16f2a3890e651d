// scatterlab explore: the explorer, a local web application (Bitterli 2013 §3.6): the profiles of
// every model for a material the user changes, the lit sphere, Monte Carlo files and models from
// text files, served by explore/server.hpp to a browser on this machine.
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/explore/api.hpp"
#include "scatterlab/explore/server.hpp"
#include "shipped_path.hpp"

namespace scatterlab::cli {
namespace {

namespace fs = std::filesystem;

struct ExploreCommandOptions {
  std::string host = "127.0.0.1";
  int port = 8765;
  std::vector<std::string> open;
  std::string models;
  std::string page;
};

// The page's folder: --page, else the installed one beside the program
// (<prefix>/share/scatterlab/explore), else the source tree's web/ this program was built from.
fs::path find_page(const std::string& page) {
  if (!page.empty()) return page;
  return shipped_path("explore", SCATTERLAB_SOURCE_WEB);
}

int run_explore(const ExploreCommandOptions& o) {
  ExploreOptions options;
  options.page = find_page(o.page);
  for (const std::string& folder : o.open) options.open_folders.emplace_back(folder);
  if (!o.models.empty()) options.models = o.models;
  if (!fs::is_regular_file(options.page / "node_modules/plotly.js-dist-min/plotly.min.js")) {
    throw InputError(
        "--page",
        fmt::format("{} lacks its plotting library (node_modules/plotly.js-dist-min)",
                    options.page.string()),
        "the page's folder after scripts/setup.sh (npm ci in web/) or cmake --install");
  }
  const ExploreApi api(options);

  // SIGINT and SIGTERM end the server: blocked here, before the server's threads start (they
  // inherit the mask), and waited for by this thread, which then stops the server cleanly.
  sigset_t ending;
  sigemptyset(&ending);
  sigaddset(&ending, SIGINT);
  sigaddset(&ending, SIGTERM);
  sigaddset(&ending, SIGUSR1);  // the server's thread, when it stops by itself
  pthread_sigmask(SIG_BLOCK, &ending, nullptr);

  ExploreServer server(api, o.host, o.port);
  const std::string shown_host =
      o.host.find(':') != std::string::npos ? "[" + o.host + "]" : o.host;
  fmt::print("scatterlab explore: http://{}:{}/ (the page: {}; Ctrl-C ends it)\n", shown_host,
             server.port(), options.page.string());
  std::fflush(stdout);
  std::thread serving([&server] {
    server.run();
    ::kill(::getpid(), SIGUSR1);
  });
  int signal_number = 0;
  sigwait(&ending, &signal_number);
  server.stop();
  serving.join();
  fmt::print("scatterlab explore: stopped\n");
  return 0;
}

}  // namespace

Action add_explore_command(CLI::App& app) {
  auto o = std::make_shared<ExploreCommandOptions>();
  auto* command = app.add_subcommand("explore", kExploreDescription);
  command->add_option("--host", o->host,
                      "Address to listen on (127.0.0.1: this machine only; 0.0.0.0: every "
                      "network the machine is on)");
  command->add_option("--port", o->port, "Port to listen on; 0 picks a free one")
      ->check(CLI::Range(0, 65535));
  command->add_option(
      "--open", o->open,
      "A folder whose searchlight and lit-sphere files (*.h5) the page may read (repeatable)");
  command->add_option("--models", o->models,
                      "A folder of text models (*.toml; docs/guide/explorer.md)");
  command->add_option("--page", o->page,
                      "The page's folder (default: the installed one, else the source tree's "
                      "web/)");
  return [o] { return run_explore(*o); };
}

}  // namespace scatterlab::cli

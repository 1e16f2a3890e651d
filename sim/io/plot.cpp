#include "scatterlab/io/plot.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"

extern char** environ;

namespace scatterlab {

namespace detail {
std::string_view plot_figure_script();  // sim/io/plot_figure.py, compiled in (plot_script.cpp.in)
}  // namespace detail

namespace {

constexpr const char* missing_matplotlib =
    "figures need python3 with matplotlib (Debian: python3-matplotlib)";

// The value as drawn: nullopt where the scale cannot show it.
std::optional<double> drawable(double v, AxisScale scale) {
  if (!std::isfinite(v)) return std::nullopt;
  if (scale == AxisScale::log && !(v > 0.0)) return std::nullopt;
  if (scale == AxisScale::sqrt && v < 0.0) return std::nullopt;
  return v;
}

void check_size(int width, int height) {
  if (width < 100 || height < 100) {
    throw InputError("plot", "size " + std::to_string(width) + "x" + std::to_string(height),
                     "at least 100 x 100 pixels");
  }
}

void check(const LinePlot& plot) {
  if (plot.series.empty()) throw InputError("plot", "no series", "at least one series");
  for (const PlotSeries& s : plot.series) {
    if (s.x.size() != s.y.size() || (!s.y_error.empty() && s.y_error.size() != s.y.size()) ||
        (!s.point_labels.empty() && s.point_labels.size() != s.y.size())) {
      throw InputError("plot", "series \"" + s.name + "\" has mismatched lengths",
                       "x, y (and y_error and point_labels if given) of equal length");
    }
  }
  check_size(plot.width, plot.height);
  const AxisScale x_scale = plot.log_x ? AxisScale::log : AxisScale::linear;
  for (const PlotSeries& s : plot.series) {
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      if (drawable(s.x[i], x_scale) && drawable(s.y[i], plot.y_scale)) return;
    }
  }
  throw InputError("plot", "no point can be drawn on a " + to_string(plot.y_scale) + " axis",
                   "at least one finite point (positive on a log axis)");
}

// A JSON string: quotes, backslashes and control characters escaped (RFC 8259 §7).
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string json_number(std::optional<double> v) {
  return v ? fmt::format("{:.17g}", *v) : "null";
}

// One figure as JSON for plot_figure.py; points the scales cannot show become null (a gap).
std::string figure_json(const LinePlot& plot, const std::string& output) {
  const AxisScale x_scale = plot.log_x ? AxisScale::log : AxisScale::linear;
  std::string json = fmt::format(
      "{{\"output\": {}, \"title\": {}, \"x_label\": {}, \"y_label\": {}, \"y_scale\": {}, "
      "\"log_x\": {}, \"width\": {}, \"height\": {}, \"series\": [",
      json_string(output), json_string(plot.title), json_string(plot.x_label),
      json_string(plot.y_label), json_string(to_string(plot.y_scale)), plot.log_x, plot.width,
      plot.height);
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    std::string xs, ys, lows, highs;
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      const auto x = drawable(s.x[i], x_scale);
      const auto y = x ? drawable(s.y[i], plot.y_scale) : std::nullopt;
      // Appended in two steps: "const char* + std::string" trips GCC 12's -Wrestrict at -O3.
      const auto append = [i](std::string& list, std::optional<double> v) {
        if (i > 0) list += ", ";
        list += json_number(v);
      };
      append(xs, y ? x : std::nullopt);
      append(ys, y);
      if (!s.y_error.empty()) {
        // A low end the scale cannot show (at or below 0 on a log axis, below 0 on a sqrt axis)
        // is null: plot_figure.py runs the bar off the bottom of the axis.
        const double e = s.y_error[i];
        const bool bar = y && std::isfinite(e);
        append(lows, bar ? drawable(*y - e, plot.y_scale) : y);
        append(highs, bar ? drawable(*y + e, plot.y_scale).value_or(*y) : y);
      }
    }
    json += fmt::format(
        "{}{{\"name\": {}, \"model\": {}, \"markers\": {}, \"x\": [{}], \"y\": [{}]",
        k == 0 ? "" : ", ", json_string(s.name), json_string(s.model), s.markers, xs, ys);
    if (!s.y_error.empty()) json += fmt::format(", \"low\": [{}], \"high\": [{}]", lows, highs);
    if (!s.point_labels.empty()) {
      json += ", \"point_labels\": [";
      for (std::size_t i = 0; i < s.point_labels.size(); ++i) {
        if (i > 0) json += ", ";
        json += json_string(s.point_labels[i]);
      }
      json += "]";
    }
    json += "}";
  }
  return json + "]}";
}

// The python3 that draws: $SCATTERLAB_PYTHON, else Debian's /usr/bin/python3 (where
// python3-matplotlib installs), else python3 on the PATH.
std::string python_program() {
  const char* chosen = std::getenv("SCATTERLAB_PYTHON");
  if (chosen != nullptr && *chosen != '\0') return chosen;
  if (::access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  return "python3";
}

// A private directory under the system's temporary directory, removed with this object.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "scatterlab-plot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("plot: cannot make a scratch directory " + pattern + ": " +
                               std::strerror(errno));
    }
    path_ = pattern;
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Runs `python -c script request` (`python -c script` for an empty request: the script only
// imports matplotlib), with stdout and stderr captured; returns the exit status and the captured
// text. posix_spawn, not a shell: no quoting of the arguments.
std::pair<int, std::string> run_python(const std::string& python,
                                       const std::filesystem::path& request) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("plot: no pipe for python3: ") + std::strerror(errno));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  const std::string script(detail::plot_figure_script());
  const std::string request_path = request.string();
  std::string arg0 = python, arg1 = "-c", arg2 = script, arg3 = request_path;
  char* argv[] = {arg0.data(), arg1.data(), arg2.data(), request.empty() ? nullptr : arg3.data(),
                  nullptr};
  pid_t pid = 0;
  const int spawned = python.find('/') == std::string::npos
                          ? ::posix_spawnp(&pid, python.c_str(), &actions, nullptr, argv, environ)
                          : ::posix_spawn(&pid, python.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (spawned != 0) {
    ::close(pipe_fds[0]);
    throw std::runtime_error(
        fmt::format("{}: cannot run {}: {}", missing_matplotlib, python, std::strerror(spawned)));
  }
  std::string output;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n > 0) {
      output.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR)
      throw std::runtime_error(std::string("plot: waitpid: ") + std::strerror(errno));
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return {code, output};
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// Draws figure k of `paths.size()` (its JSON from figure_json(k, where python writes it)) and
// writes each to its path, atomically. The figures have been checked.
void draw(const std::vector<std::filesystem::path>& paths,
          const std::function<std::string(std::size_t, const std::string&)>& figure_json) {
  // The outputs' directories are checked (InputError "out") before python starts.
  std::vector<std::unique_ptr<AtomicOutput>> outputs;
  for (const auto& path : paths) outputs.push_back(std::make_unique<AtomicOutput>(path));

  const ScratchDirectory scratch;
  std::string request = "{\"figures\": [";
  for (std::size_t k = 0; k < paths.size(); ++k) {
    if (k > 0) request += ", ";
    request += figure_json(k, (scratch.path() / fmt::format("{}.png", k)).string());
  }
  request += "]}\n";
  const auto request_path = scratch.path() / "figures.json";
  write_whole_file(request_path, request);

  const std::string python = python_program();
  const auto [code, output] = run_python(python, request_path);
  if (code == 3) {
    throw std::runtime_error(fmt::format("{} ({}: {})", missing_matplotlib, python, output));
  }
  if (code != 0) {
    throw std::runtime_error(fmt::format("plot: {} failed drawing {} (exit status {}): {}", python,
                                         paths.front().string(), code, output));
  }
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const std::string png = read_bytes(scratch.path() / fmt::format("{}.png", k));
    if (png.empty())
      throw std::runtime_error("plot: matplotlib drew nothing for " + paths[k].string());
    write_whole_file(outputs[k]->temporary_path(), png);
  }
  for (const auto& file : outputs) file->commit();
}

// The panels as JSON: each image's display values, (value * 2^exposure)^(1/gamma) clamped to
// [0, 1] as write_png of an Image maps them to grey levels, rows from the top.
std::string image_figure_json(const ImageFigure& figure, const std::string& output) {
  std::string json = fmt::format(
      "{{\"kind\": \"images\", \"output\": {}, \"title\": {}, \"width\": {}, \"height\": {}, "
      "\"panels\": [",
      json_string(output), json_string(figure.title), figure.width, figure.height);
  const double scale = std::exp2(figure.exposure);
  for (std::size_t p = 0; p < figure.panels.size(); ++p) {
    const Image& image = *figure.panels[p].image;
    json += fmt::format("{}{{\"title\": {}, \"pixels\": [", p == 0 ? "" : ", ",
                        json_string(figure.panels[p].title));
    for (int j = 0; j < image.height; ++j) {
      json += j == 0 ? "[" : ", [";
      for (int i = 0; i < image.width; ++i) {
        const double v = std::clamp(
            std::pow(std::max(image.at(i, j) * scale, 0.0), 1.0 / figure.gamma), 0.0, 1.0);
        if (i > 0) json += ", ";
        json += fmt::format("{:.4f}", std::isfinite(v) ? v : 0.0);
      }
      json += "]";
    }
    json += "]}";
  }
  return json + "]}";
}

}  // namespace

void require_plotting() {
  const std::string python = python_program();
  const auto [code, output] = run_python(python, {});
  if (code != 0) {
    throw std::runtime_error(
        fmt::format("{} ({}: exit status {}: {})", missing_matplotlib, python, code, output));
  }
}

void write_pngs(const std::vector<PlotFile>& plots) {
  if (plots.empty()) return;
  for (const PlotFile& p : plots) check(p.plot);
  std::vector<std::filesystem::path> paths;
  for (const PlotFile& p : plots) paths.push_back(p.path);
  draw(paths, [&plots](std::size_t k, const std::string& output) {
    return figure_json(plots[k].plot, output);
  });
}

void write_png(const ImageFigure& figure, const std::filesystem::path& path) {
  if (figure.panels.empty()) throw InputError("plot", "an image figure with no panel", "a panel");
  for (const ImagePanel& panel : figure.panels) {
    if (panel.image == nullptr || panel.image->width < 1 || panel.image->height < 1 ||
        panel.image->width != figure.panels.front().image->width ||
        panel.image->height != figure.panels.front().image->height) {
      throw InputError("plot", "panel \"" + panel.title + "\" has no image or another size",
                       "images of one size");
    }
  }
  check_size(figure.width, figure.height);
  if (!(figure.gamma > 0.0) || !std::isfinite(figure.gamma)) {
    throw InputError("gamma", "got " + std::to_string(figure.gamma), "a finite number > 0");
  }
  if (!std::isfinite(figure.exposure)) {
    throw InputError("exposure", "got " + std::to_string(figure.exposure),
                     "a finite number (stops)");
  }
  draw({path}, [&figure](std::size_t, const std::string& output) {
    return image_figure_json(figure, output);
  });
}

void write_png(const LinePlot& plot, const std::filesystem::path& path) {
  write_pngs({PlotFile{plot, path}});
}

std::string to_string(AxisScale scale) {
  switch (scale) {
    case AxisScale::linear:
      return "linear";
    case AxisScale::log:
      return "log";
    case AxisScale::sqrt:
      return "sqrt";
  }
  return "linear";
}

}  // namespace scatterlab

// _scatterlab: the compiled half of the Python package (python/scatterlab/). It parses a scene's
// TOML text with the same readers as the command line (io/scene.hpp), so that every key is
// checked and named the same way, runs it in this process with the GIL released, and writes the
// run's file with the same writer (validate/run_file.hpp); the package reads the file back. The
// analytic models are bound as numpy ufunc-like functions (py::vectorize).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <signal.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/medium.hpp"
#ifdef SCATTERLAB_WITH_FIT
#include "scatterlab/fit/lobe_fits_file.hpp"
#include "scatterlab/fit/lobe_model.hpp"
#endif
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/scene_schema.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/io/text_file.hpp"
#include "scatterlab/models/chandrasekhar_h.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/half_space_medium.hpp"
#include "scatterlab/models/point_source_exact.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/validate/run_file.hpp"

namespace py = pybind11;

namespace scatterlab::python {
namespace {

// Ctrl-C during a run. Python runs its SIGINT handler only on the main thread and only when that
// thread holds the GIL, which a run hands back once per batch: seconds or minutes apart. While a
// run holds the main thread, SIGINT instead sets the run's stop flag, so that the engine stops
// within a slice of photons (batch_runner.hpp) as the command line does; once the run has ended
// and Python's handler is back, the signal is handed on to it (PyErr_SetInterrupt), so that
// whatever handler the user has (KeyboardInterrupt by default) runs. Elsewhere than the main
// thread Python receives no signals, and nothing is installed.
class InterruptGuard {
 public:
  explicit InterruptGuard(std::atomic<bool>& stop) {
    const py::module_ threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return;
    // A SIGINT that is ignored, or that ends the process, stays so.
    if (sigaction(SIGINT, nullptr, &previous_) != 0 || previous_.sa_handler == SIG_IGN ||
        previous_.sa_handler == SIG_DFL) {
      return;
    }
    stop_ = &stop;
    caught_ = 0;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    installed_ = sigaction(SIGINT, &action, nullptr) == 0;
  }
  ~InterruptGuard() {
    if (!installed_) return;
    sigaction(SIGINT, &previous_, nullptr);
    stop_ = nullptr;
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  bool caught() const { return installed_ && caught_ != 0; }

 private:
  static void on_interrupt(int) {
    caught_ = 1;
    if (stop_ != nullptr) stop_->store(true);  // lock-free: safe in a signal handler
  }
  static inline std::atomic<bool>* stop_ = nullptr;
  static inline volatile std::sig_atomic_t caught_ = 0;
  struct sigaction previous_ {};
  bool installed_ = false;
};

// Runs `work(progress, control, stopped)` (transport, write) without the GIL. After each batch that
// the calling thread transports, the progress callback takes the GIL back to call
// `progress(batches_done, batches)` (when given) and to let Python see a signal; on the main
// thread Ctrl-C stops the run within a slice of photons (InterruptGuard). Either way it raises
// KeyboardInterrupt (or runs the user's SIGINT handler), and no file is written.
template <class Work>
void without_gil(const py::object& progress, Work&& work) {
  std::atomic<bool> stop{false};
  std::optional<py::error_already_set> failure;
  RunControl control;
  control.stop_requested = &stop;
  std::optional<InterruptGuard> interrupts(std::in_place, stop);
  const ProgressCallback callback = [&](const BatchProgress& done) {
    py::gil_scoped_acquire gil;
    if (failure) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) progress(done.batches_done, done.batches);
    } catch (py::error_already_set& e) {
      failure.emplace(std::move(e));
      stop = true;
    }
  };
  {
    py::gil_scoped_release released;
    work(callback, control, stop);
  }
  const bool interrupted = interrupts->caught();
  interrupts.reset();  // Python's handler back in place
  if (failure) throw std::move(*failure);
  if (interrupted) {
    PyErr_SetInterrupt();
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    // The user's handler returned: the run was stopped all the same, and wrote no file.
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
}

// Parses `toml` as a scene (the one reader, io/scene.hpp; `geometry` for a text that names none),
// runs it and writes its file to `path`, as the command line's simulate does for one process.
void run_scene(const std::string& toml, const std::string& origin, const std::string& geometry,
               const std::string& path, const std::string& command, bool model_fluence,
               const py::object& progress) {
  Scene scene = parse_scene(toml, origin, Validation::on_read, geometry);
  if (scene.mesh_text) {  // meshes are traced with Embree, in the program's render component
    throw InputError("geometry.type", "\"mesh\" in the Python module",
                     "a sphere here; a mesh scene runs with scatterlab simulate --scene");
  }
  auto* half_space = std::get_if<HalfSpaceSpec>(&scene.spec);
  if (model_fluence && (half_space == nullptr || !half_space->tallies.fluence)) {
    throw InputError("model_fluence",
                     half_space == nullptr
                         ? "given for a " + std::string(scene.geometry()) + " scene"
                         : "given with tallies.fluence = false",
                     "model_fluence for a half-space with the fluence tally on");
  }
  // Runs the spec (the engine checks its memory first, engine.hpp), and writes its file unless
  // the run was stopped.
  const std::filesystem::path out_path(path);
  without_gil(progress, [&](const ProgressCallback& callback, const RunControl& control,
                            const std::atomic<bool>& stopped) {
    const TransportOutput out = run_spec(scene.spec, callback, control);
    if (!stopped) write_run_result(out_path, scene.spec, out, command, model_fluence);
  });
}

// Fits a file's lobes and writes the fits back (fit::fit_file, as `scatterlab fit FILE`), without
// the GIL; `progress(bins_done, bins)` is called as bins finish. The fits cannot be stopped part
// way: an exception from `progress` (or Ctrl-C) is raised once they end, and the file is then
// already written.
#ifdef SCATTERLAB_WITH_FIT
void fit_file(const std::string& path, const std::string& csv, const std::string& models,
              int quadrature, int threads, const py::object& progress) {
  const std::vector<fit::LobeModel> lobe_models = fit::parse_lobe_models(models);
  std::optional<py::error_already_set> failure;
  const WorkProgress callback = [&](std::uint64_t done, std::uint64_t bins) {
    py::gil_scoped_acquire gil;
    if (failure) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) progress(done, bins);
    } catch (py::error_already_set& e) {
      failure.emplace(std::move(e));
    }
  };
  {
    py::gil_scoped_release released;
    const std::filesystem::path file(path);
    fit::fit_file(file, csv.empty() ? fit::default_fits_csv(file) : std::filesystem::path(csv),
                  lobe_models, fit::FitOptions{}, quadrature, threads, callback);
  }
  if (failure) throw std::move(*failure);
}
#else
// A build without the fit component (Ceres) answers as the program's `fit` does.
void fit_file(const std::string&, const std::string&, const std::string&, int, int,
              const py::object&) {
  throw not_in_this_build("fit", "Ceres (Debian: libceres-dev)");
}
#endif

// The half-space models' medium: albedo with sigma_t = 1 (lengths in mfp).
HalfSpaceMedium half_space(double albedo, double g, double eta) {
  HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(albedo, g, eta);
  medium.validate();
  return medium;
}

void bind_models(py::module_& m) {
  m.def("better_dipole", py::vectorize([](double r, double albedo, double g, double eta) {
          return dipole_reflectance(better_dipole(half_space(albedo, g, eta)), r);
        }),
        py::arg("r"), py::arg("albedo"), py::arg("g"), py::arg("eta"));
  m.def("classical_dipole", py::vectorize([](double r, double albedo, double g, double eta) {
          return dipole_reflectance(classical_dipole(half_space(albedo, g, eta)), r);
        }),
        py::arg("r"), py::arg("albedo"), py::arg("g"), py::arg("eta"));
  m.def("better_dipole_fluence",
        py::vectorize([](double r, double z, double albedo, double g, double eta) {
          return dipole_fluence(better_dipole(half_space(albedo, g, eta)), r, z);
        }),
        py::arg("r"), py::arg("z"), py::arg("albedo"), py::arg("g"), py::arg("eta"));
  m.def("better_dipole_total", py::vectorize([](double albedo, double g, double eta) {
          return dipole_total_reflectance(better_dipole(half_space(albedo, g, eta)));
        }),
        py::arg("albedo"), py::arg("g"), py::arg("eta"));
  m.def("point_source_fluence", py::vectorize(&point_source_fluence), py::arg("albedo"),
        py::arg("rho"));
  m.def("point_source_fluence_collided", py::vectorize(&point_source_fluence_collided),
        py::arg("albedo"), py::arg("rho"));
  m.def("point_source_fluence_uncollided", py::vectorize(&point_source_fluence_uncollided),
        py::arg("rho"));
  m.def("point_source_fluence_shell_average",
        py::vectorize([](double albedo, double rho0, double rho1) {
          return point_source_fluence_shell_average(albedo, rho0, rho1);
        }),
        py::arg("albedo"), py::arg("rho0"), py::arg("rho1"));
  m.def("discrete_eigenvalue", py::vectorize(&discrete_eigenvalue), py::arg("albedo"));
  m.def("chandrasekhar_h", py::vectorize(&chandrasekhar_h), py::arg("albedo"), py::arg("mu"));
  m.def("half_space_diffuse_reflectance", py::vectorize(&half_space_diffuse_reflectance),
        py::arg("albedo"), py::arg("mu0"));
  m.def("single_scatter_exitance",
        py::vectorize([](double r, double albedo, double g, double eta, double sigma_t) {
          const Medium medium = Medium::from_albedo(albedo, sigma_t, g);
          return half_space_single_scatter_exitance(medium, eta, r).value;
        }),
        py::arg("r"), py::arg("albedo"), py::arg("g"), py::arg("eta"), py::arg("sigma_t"));
}

}  // namespace
}  // namespace scatterlab::python

PYBIND11_MODULE(_scatterlab, m) {
  namespace sp = scatterlab::python;
  m.doc() = "scatterlab's compiled core; use the scatterlab package, not this module";
  m.attr("version") = SCATTERLAB_VERSION;
  // Bad input: ValueError, the message naming the field as the command line's does.
  py::register_exception<scatterlab::InputError>(m, "InputError", PyExc_ValueError);
  // A scene file's text, read as the command line reads one: a device, FIFO or directory, or a
  // file over 1 MiB, is refused before it is opened or read.
  m.def(
      "read_scene_file",
      [](const std::string& path) { return scatterlab::read_scene_file(path, "scene"); },
      py::arg("path"));
  // The checks `scatterlab info` makes of a file (io/simulation_file.hpp), before h5py reads it:
  // one of another format_version, one that contradicts itself, or one whose damage would crash
  // HDF5 (global heaps, links) is refused naming FILE.
  m.def(
      "check_file",
      [](const std::string& path) { (void)scatterlab::read_file_header(path, "FILE"); },
      py::arg("path"));
  // The scene's keys (io/scene_schema.hpp): (dotted path, [geometry.type, ...]) each.
  m.def("scene_keys", [] {
    std::vector<std::pair<std::string, std::vector<std::string>>> keys;
    for (const scatterlab::SceneKey& key : scatterlab::scene_keys()) {
      std::vector<std::string> geometries;
      for (const std::string_view geometry : scatterlab::scene_geometries) {
        if (scatterlab::scene_key_of(key, geometry)) geometries.emplace_back(geometry);
      }
      keys.emplace_back(std::string(key.path), std::move(geometries));
    }
    return keys;
  });
  // Checks a scene's text as run_scene would read it, and runs nothing (scatterlab.Scene).
  m.def(
      "check_scene",
      [](const std::string& toml, const std::string& origin, const std::string& geometry) {
        (void)scatterlab::parse_scene(toml, origin, scatterlab::Validation::on_read, geometry);
      },
      py::arg("toml"), py::arg("origin"), py::arg("geometry"));
  m.def("run_scene", &sp::run_scene, py::arg("toml"), py::arg("origin"), py::arg("geometry"),
        py::arg("path"), py::arg("command"), py::arg("model_fluence"), py::arg("progress"));
  m.def("fit_file", &sp::fit_file, py::arg("path"), py::arg("csv"), py::arg("models"),
        py::arg("quadrature"), py::arg("threads"), py::arg("progress"));
  sp::bind_models(m);
}

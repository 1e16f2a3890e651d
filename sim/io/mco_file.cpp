#include "scatterlab/io/mco_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scatterlab/io/atomic_output.hpp"

// The layout is MCML 1.2.2's WriteResult (mcmlio.c: WriteVersion, WriteInParm, WriteRAT,
// WriteA_layer, WriteA_z, WriteRd_r, WriteRd_a, WriteTt_r, WriteTt_a, WriteA_rz, WriteRd_ra,
// WriteTt_ra; section 9.3 of the MCML manual, Wang & Jacques 1992), byte for byte: MCML's CONV
// finds each section by the keyword that starts its line ("RAT", "A_l", ..., "Tt_ra") and then
// reads the numbers that follow, one data line per value for the 1D arrays and free-form for the 2D
// ones, so the keywords, the comment lines and the order all matter to it.

namespace scatterlab {
namespace {

// The numbers are formatted by C's printf, not by fmt, because MCML's layout is what printf's
// %G and %E write and fmt's conversions of the same letters differ: fmt's {:G} without a
// precision writes the shortest digits that round-trip (0.1 + 0.2 gives "0.30000000000000004"
// where %G gives "0.3"), and fmt gives no guarantee to match printf's choice between the fixed
// and the exponent form or its exponent width in every case. `format` is one of the literal
// conversions below, for one finite double.
std::string c_format(const char* format, double value) {
  char buffer[64];
  const int length = std::snprintf(buffer, sizeof buffer, format, value);
  if (length < 0 || static_cast<std::size_t>(length) >= sizeof buffer) {
    throw std::logic_error("write_mco: a number does not fit its field");
  }
  return std::string(buffer, static_cast<std::size_t>(length));
}

std::string g(double value) {
  return c_format("%G", value);
}

void check_size(const std::vector<double>& values, std::size_t expected, std::string_view name) {
  if (values.size() != expected) {
    throw std::invalid_argument(fmt::format(
        "write_mco: {} holds {} values, the run's grid needs {}", name, values.size(), expected));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    // printf writes "NAN" or "INF", which MCML's readers take for no number at all.
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument(fmt::format("write_mco: {}[{}] is {}", name, i, values[i]));
    }
  }
}

void check_finite(double value, std::string_view name) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(fmt::format("write_mco: {} is {}", name, value));
  }
}

void check_input(const McmlRun& run, const McoResults& results, double seconds) {
  if (run.nz < 1 || run.nr < 1 || run.na < 1 || run.layers.empty()) {
    throw std::invalid_argument(
        fmt::format("write_mco: the run's grid (Nz {}, Nr {}, Na {}, {} layers) is empty", run.nz,
                    run.nr, run.na, run.layers.size()));
  }
  // The name is echoed as one word on a data line, which CONV skips unread; a space or a '#'
  // would shift or hide it.
  if (run.output_file.empty() ||
      run.output_file.find_first_of(" \t\r\n\f\v#") != std::string::npos) {
    throw std::invalid_argument(fmt::format(
        "write_mco: the output file name '{}' is not one word without '#'", run.output_file));
  }
  if (!std::isfinite(seconds) || seconds < 0) {
    throw std::invalid_argument(fmt::format("write_mco: {} seconds of run time", seconds));
  }
  const auto nz = static_cast<std::size_t>(run.nz);
  const auto nr = static_cast<std::size_t>(run.nr);
  const auto na = static_cast<std::size_t>(run.na);
  check_finite(results.specular_reflectance, "specular_reflectance");
  check_finite(results.diffuse_reflectance, "diffuse_reflectance");
  check_finite(results.absorbed, "absorbed");
  check_finite(results.total_transmittance, "total_transmittance");
  check_size(results.absorbed_by_layer, run.layers.size(), "absorbed_by_layer (A_l)");
  check_size(results.absorbed_by_depth, nz, "absorbed_by_depth (A_z)");
  check_size(results.absorbed_density, nr * nz, "absorbed_density (A_rz)");
  check_size(results.reflectance_by_radius, nr, "reflectance_by_radius (Rd_r)");
  check_size(results.reflectance_by_angle, na, "reflectance_by_angle (Rd_a)");
  check_size(results.reflectance_by_radius_angle, nr * na, "reflectance_by_radius_angle (Rd_ra)");
  check_size(results.transmittance_by_radius, nr, "transmittance_by_radius (Tt_r)");
  check_size(results.transmittance_by_angle, na, "transmittance_by_angle (Tt_a)");
  check_size(results.transmittance_by_radius_angle, nr * na,
             "transmittance_by_radius_angle (Tt_ra)");
}

// A 1D array: its header line, one number a line, a blank line.
void write_column(std::ostream& out, std::string_view header, const std::vector<double>& values) {
  out << header << '\n';
  for (const double value : values) out << c_format("%12.4E", value) << '\n';
  out << '\n';
}

// A 2D array: a title and four lines naming the order of the values, all comments; the keyword
// alone on its line; then the values row by row, each followed by a space, five to a line counted
// over the whole array (so a row may end mid-line), and one line end after the last.
void write_matrix(std::ostream& out, std::string_view title, std::string_view symbol,
                  std::string_view columns, std::string_view keyword,
                  const std::vector<double>& values) {
  out << title << '\n';
  out << fmt::format("# {0}[0][0], [0][1],..[0][{1}-1]\n", symbol, columns);
  out << fmt::format("# {0}[1][0], [1][1],..[1][{1}-1]\n", symbol, columns);
  out << "# ...\n";
  out << fmt::format("# {0}[nr-1][0], [nr-1][1],..[nr-1][{1}-1]\n", symbol, columns);
  out << keyword << '\n';
  for (std::size_t i = 0; i < values.size(); ++i) {
    out << c_format("%12.4E", values[i]) << ' ';
    if ((i + 1) % 5 == 0) out << '\n';
  }
  out << '\n';
}

void write_body(std::ostream& out, const McmlRun& run, const McoResults& results, double seconds) {
  // WriteVersion.
  out << "A1 \t# Version number of the file format.\n\n"
      << "####\n# Data categories include: \n"
      << "# InParm, RAT, \n"
      << "# A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, \n"
      << "# A_rz, Rd_ra, Tt_ra \n####\n\n";
  // MCML's time report, a comment line that CONV skips.
  out << "# User time: " << c_format("%8.0f", seconds)
      << " sec = " << c_format("%8.2f", seconds / 3600.0)
      << " hr.   Simulation time of this run.\n\n";

  // WriteInParm: the input echoed with %G (six significant digits), as CONV reads it back.
  out << "InParm \t\t\t# Input parameters. cm is used.\n";
  out << run.output_file << " \tA\t\t# output file name, ASCII.\n";
  out << run.photons << " \t\t\t# No. of photons\n";
  out << g(run.dz) << '\t' << g(run.dr) << "\t\t# dz, dr [cm]\n";
  out << run.nz << '\t' << run.nr << '\t' << run.na << "\t# No. of dz, dr, da.\n\n";
  out << run.layers.size() << "\t\t\t\t\t# Number of layers\n";
  out << "#n\tmua\tmus\tg\td\t# One line for each layer\n";
  out << g(run.n_above) << "\t\t\t\t\t# n for medium above\n";
  for (std::size_t i = 0; i < run.layers.size(); ++i) {
    const McmlLayer& layer = run.layers[i];
    out << g(layer.n) << '\t' << g(layer.mu_a) << '\t' << g(layer.mu_s) << '\t' << g(layer.g)
        << '\t' << g(layer.thickness) << "\t# layer " << i + 1 << '\n';
  }
  out << g(run.n_below) << "\t\t\t\t\t# n for medium below\n\n";

  // WriteRAT.
  out << "RAT #Reflectance, absorption, transmission. \n";
  out << c_format("%-14.6G", results.specular_reflectance) << " \t#Specular reflectance [-]\n";
  out << c_format("%-14.6G", results.diffuse_reflectance) << " \t#Diffuse reflectance [-]\n";
  out << c_format("%-14.6G", results.absorbed) << " \t#Absorbed fraction [-]\n";
  out << c_format("%-14.6G", results.total_transmittance) << " \t#Transmittance [-]\n";
  out << '\n';

  // WriteA_layer: %G, not %E, as MCML writes it.
  out << "A_l #Absorption as a function of layer. [-]\n";
  for (const double value : results.absorbed_by_layer) out << c_format("%12.4G", value) << '\n';
  out << '\n';

  write_column(out, "A_z #A[0], [1],..A[nz-1]. [1/cm]", results.absorbed_by_depth);
  write_column(out, "Rd_r #Rd[0], [1],..Rd[nr-1]. [1/cm2]", results.reflectance_by_radius);
  write_column(out, "Rd_a #Rd[0], [1],..Rd[na-1]. [sr-1]", results.reflectance_by_angle);
  write_column(out, "Tt_r #Tt[0], [1],..Tt[nr-1]. [1/cm2]", results.transmittance_by_radius);
  write_column(out, "Tt_a #Tt[0], [1],..Tt[na-1]. [sr-1]", results.transmittance_by_angle);

  write_matrix(out, "# A[r][z]. [1/cm3]", "A", "nz", "A_rz", results.absorbed_density);
  write_matrix(out, "# Rd[r][angle]. [1/(cm2sr)].", "Rd", "na", "Rd_ra",
               results.reflectance_by_radius_angle);
  write_matrix(out, "# Tt[r][angle]. [1/(cm2sr)].", "Tt", "na", "Tt_ra",
               results.transmittance_by_radius_angle);
}

}  // namespace

void write_mco(const std::filesystem::path& path, const McmlRun& run, const McoResults& results,
               double seconds) {
  check_input(run, results, seconds);
  write_text_file(path, [&](std::ostream& out) { write_body(out, run, results, seconds); });
}

McoResults mco_results(const std::vector<TallyResult>& tallies, const McmlRun& run) {
  const auto values = [&tallies](const char* name, double factor = 1.0) {
    const TallyResult* t = find_tally(tallies, name);
    if (t == nullptr) throw std::invalid_argument(fmt::format("mco_results: no tally {}", name));
    std::vector<double> v = t->mean;
    for (double& x : v) x *= factor;
    return v;
  };
  const double d_alpha = 0.5 * std::numbers::pi / run.na;
  const double per_solid_angle = 2.0 * std::sin(0.5 * d_alpha) / d_alpha;
  const double per_projected = std::cos(0.5 * d_alpha);
  McoResults r;
  r.specular_reflectance = values("specular_reflectance").at(0);
  r.diffuse_reflectance = values("diffuse_reflectance").at(0);
  r.absorbed = values("absorbed").at(0);
  r.total_transmittance = values("total_transmittance").at(0);
  r.absorbed_by_layer = values("absorbed_by_layer");
  r.absorbed_by_depth = values("absorbed_by_depth");
  r.absorbed_density = values("absorbed_by_radius_depth");
  r.reflectance_by_radius = values("diffuse_reflectance_by_radius");
  r.reflectance_by_angle = values("diffuse_reflectance_by_angle", per_solid_angle);
  r.reflectance_by_radius_angle = values("diffuse_reflectance_by_radius_angle", per_projected);
  r.transmittance_by_radius = values("total_transmittance_by_radius");
  r.transmittance_by_angle = values("total_transmittance_by_angle", per_solid_angle);
  r.transmittance_by_radius_angle = values("total_transmittance_by_radius_angle", per_projected);
  return r;
}

}  // namespace scatterlab

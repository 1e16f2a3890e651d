#pragma once
// MCML output files (.mco): the results of one run in MCML 1.2.2's ASCII layout, so that MCML's
// own scripts and its CONV convolution program read them (L. Wang, S. L. Jacques, L. Zheng,
// "MCML - Monte Carlo modeling of light transport in multi-layered tissues", Comput. Methods
// Programs Biomed. 47 (1995) 131-146; the output file chapter of the MCML manual, Wang & Jacques
// 1992). Units are MCML's: cm, sr.

#include <filesystem>
#include <vector>

#include "scatterlab/io/mcml_input.hpp"
#include "scatterlab/tally/tally_result.hpp"

namespace scatterlab {

struct McoResults {
  double specular_reflectance = 0, diffuse_reflectance = 0, absorbed = 0,
         total_transmittance = 0;                   // RAT
  std::vector<double> absorbed_by_layer;            // A_l [layer], dimensionless
  std::vector<double> absorbed_by_depth;            // A_z [iz], 1/cm
  std::vector<double> absorbed_density;             // A_rz [ir][iz] row-major, 1/cm^3
  std::vector<double> reflectance_by_radius;        // Rd_r [ir], 1/cm^2
  std::vector<double> reflectance_by_angle;         // Rd_a [ia], 1/sr
  std::vector<double> reflectance_by_radius_angle;  // Rd_ra [ir][ia], 1/(cm^2 sr)
  std::vector<double> transmittance_by_radius, transmittance_by_angle,
      transmittance_by_radius_angle;  // Tt_r, Tt_a, Tt_ra likewise
};

// Writes MCML 1.2.2's ASCII output (.mco) for `run`: the same sections, order, headers and number
// layout as MCML's WriteResult (version line "A1", the InParm echo of the input, RAT, A_l, A_z,
// Rd_r, Rd_a, Tt_r, Tt_a, A_rz, Rd_ra, Tt_ra with 5 numbers per line where MCML does so), so that
// MCML's own scripts and its CONV convolution program read it. `seconds` is the run's wall time for
// MCML's "User time" line. Written atomically (write_text_file,
// include/scatterlab/io/atomic_output.hpp). Throws std::invalid_argument when a vector's size does
// not match run's grid.
void write_mco(const std::filesystem::path& path, const McmlRun& run, const McoResults& results,
               double seconds);

// A layered slab's tallies (transport/layered_slab.hpp, on `run`'s grid) as MCML reports them.
// Our files divide each bin by its exact measure; MCML's ScaleRdTt divides R_d(alpha) and
// T_t(alpha) by the midpoint solid angle 2 pi sin(alpha_m) d_alpha, and R_d(r, alpha), T_t(r,
// alpha) by the ring's area times 4 pi sin(alpha_m) sin(d_alpha / 2) cos(alpha_m), so those are
// rescaled here: by 2 sin(d_alpha / 2) / d_alpha from our per-steradian profile, and by
// cos(d_alpha / 2) from our radiance (whose exact projected solid angle is
// pi sin(2 alpha_m) sin(d_alpha)). The rest (rings, depths, totals) are MCML's measures already.
McoResults mco_results(const std::vector<TallyResult>& tallies, const McmlRun& run);

}  // namespace scatterlab

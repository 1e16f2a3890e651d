#pragma once
// MCML input files (.mci): the layered slabs, photon counts and grids of MCML 1.2.2 (L. Wang,
// S. L. Jacques, L. Zheng, "MCML - Monte Carlo modeling of light transport in multi-layered
// tissues", Comput. Methods Programs Biomed. 47 (1995) 131-146; the file format is the input
// file chapter of the MCML manual, Wang & Jacques 1992, "Monte Carlo Modeling of Light Transport
// in Multi-layered Tissues in Standard C").
//
// The file is line oriented. Text after '#' is a comment, and blank or comment-only lines are
// skipped. The data lines are, in order: the file version (1.0), the number of runs, and for each
// run: the output file name and its format (A), the number of photons, "dz dr" (cm), "Nz Nr Na",
// the number of layers, n of the medium above, one line "n mua mus g d" per layer from the top
// (mua, mus in 1/cm, d in cm), n of the medium below.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/transport/layered_slab.hpp"

namespace scatterlab {

struct McmlLayer {
  double n, mu_a, mu_s, g, thickness;  // mu in cm^-1, thickness in cm
};

struct McmlRun {
  std::string output_file;  // as written in the .mci, e.g. "sample.mco"
  char file_format = 'A';   // MCML accepts only 'A' (ASCII)
  std::uint64_t photons = 0;
  double dz = 0, dr = 0;       // cm
  int nz = 0, nr = 0, na = 0;  // grid bins in z, r, and exit angle alpha over [0, pi/2]
  double n_above = 1.0;
  std::vector<McmlLayer> layers;  // top to bottom
  double n_below = 1.0;
  int line = 0;  // line of the .mci where this run starts (for messages)
};

// Every run of an MCML input file, in order. Throws InputError (include/scatterlab/core/error.hpp)
// naming "<path>:<line> <field>" (field as MCML names it: "photons", "dz", "Nr", "layer 2 mua",
// ...) and what is accepted, for a missing, malformed or out-of-range value.
std::vector<McmlRun> read_mcml_input(const std::filesystem::path& path);

// The same from the file's text; `origin` stands for the file in messages (its path).
std::vector<McmlRun> parse_mcml_input(std::string_view text, const std::string& origin);

// The run as the layered slab's spec (transport/layered_slab.hpp): its layers in cm, its grid
// (r and z from 0 in Nr x dr and Nz x dz, alpha over [0, pi/2] in Na bins), its photons, and
// the spec's defaults for the rest (analog absorption, 64 batches).
LayeredSlabSpec layered_slab_spec(const McmlRun& run);

}  // namespace scatterlab

// The shipped Jensen et al. 2001 presets load with their units and source, and the reader is
// strict.
#include <gtest/gtest.h>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/models/dipole.hpp"

namespace scatterlab {
namespace {

TEST(MaterialPresets, JensenTableLoads) {
  const MaterialLibrary library =
      load_material_library(std::string(SCATTERLAB_SOURCE_DIR) + "/data/materials/jensen2001.toml");
  EXPECT_EQ(library.length_unit, "mm");
  EXPECT_NE(library.citation.find("Jensen"), std::string::npos);
  EXPECT_DOUBLE_EQ(library.eta, 1.3);
  ASSERT_EQ(library.materials.size(), 12u);
  for (const MaterialPreset& m : library.materials) {
    ASSERT_EQ(m.sigma_a.size(), 3u);
    ASSERT_EQ(m.sigma_s_reduced.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      // Every preset is a usable medium: the dipole's R_dr in (0, 1].
      const HalfSpaceMedium medium{m.sigma_a[k], m.sigma_s_reduced[k], 0.0, library.eta};
      const double r_dr = dipole_total_reflectance(classical_dipole(medium));
      EXPECT_TRUE(r_dr > 0.0 && r_dr <= 1.0) << m.name << " channel " << k;
    }
  }
  EXPECT_DOUBLE_EQ(library.find("ketchup").sigma_a[1], 0.97);
  EXPECT_THROW(library.find("ketchp"), InputError);
}

TEST(MaterialPresets, StrictReading) {
  const std::string head =
      "[source]\ncitation = \"x\"\nlength_unit = \"mm\"\neta = 1.3\nchannels = [\"r\", \"g\"]\n";
  EXPECT_NO_THROW(parse_material_library(head + "[materials.a]\nsigma_s_reduced = [1, 2]\nsigma_a = [0.1, 0.2]\n", "t"));
  try {
    parse_material_library(head + "[materials.a]\nsigma_s_reduced = [1, 2]\nsigma_a = [0.1]\n", "t");
    FAIL() << "short array accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.sigma_a");
  }
  try {
    parse_material_library(head + "[materials.a]\nsigma_s_reduced = [1, 2]\nsigma_a = [0.1, -2]\n", "t");
    FAIL() << "negative coefficient accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.sigma_a");
  }
  try {
    parse_material_library(head + "[materials.a]\nsigma_s = [1, 2]\nsigma_a = [0.1, 0.2]\n", "t");
    FAIL() << "unknown key accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.sigma_s");
  }
}

}  // namespace
}  // namespace scatterlab

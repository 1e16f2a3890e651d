// The shipped tables (Jensen et al. 2001, Narasimhan et al. 2006) load with their units and
// source, a few values match the tables, every material resolves to a valid medium on every
// channel, and the reader and the name lookup are strict.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

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
    FAIL() << "sigma_s without g accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.g");
  }
  try {
    parse_material_library(head +
                               "[materials.a]\nsigma_s = [1, 2]\nsigma_s_reduced = [1, 2]\n"
                               "g = [0, 0]\nsigma_a = [0.1, 0.2]\n",
                           "t");
    FAIL() << "sigma_s with sigma_s_reduced accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.sigma_s");
  }
  try {
    parse_material_library(head +
                               "[materials.a]\nsigma_s_reduced = [1, 2]\ng = [0.5, 0.5]\n"
                               "sigma_a = [0.1, 0.2]\n",
                           "t");
    FAIL() << "g with sigma_s_reduced accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.g");
  }
  try {
    parse_material_library(head +
                               "[materials.a]\nsigma_s = [1, 2]\ng = [0.5, 1.0]\n"
                               "sigma_a = [0.1, 0.2]\n",
                           "t");
    FAIL() << "g = 1 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.g");
  }
  try {
    parse_material_library(head + "[materials.a]\nsigma_a = [0.1, 0.2]\n", "t");
    FAIL() << "no scattering coefficient accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "materials.a.sigma_s_reduced");
  }
  EXPECT_NO_THROW(parse_material_library(
      head + "[materials.a]\nsigma_s = [1, 2]\ng = [0.5, -0.2]\nsigma_a = [0.1, 0.2]\n", "t"));
}

const MaterialFields scene_fields{"medium.material", "medium.channel", "medium.length_unit",
                                  "medium.g"};

const MaterialLibrary& shipped(const std::string& id) {
  for (const MaterialLibrary& library : shipped_material_libraries()) {
    if (library.id == id) return library;
  }
  throw std::runtime_error("no shipped table " + id);
}

// The compiled-in tables are the files in data/materials, read the same way.
TEST(MaterialPresets, ShippedTablesAreTheDataFiles) {
  ASSERT_EQ(shipped_material_libraries().size(), 2u);
  for (const char* id : {"jensen2001", "narasimhan2006"}) {
    const MaterialLibrary file = load_material_library(std::string(SCATTERLAB_SOURCE_DIR) +
                                                       "/data/materials/" + id + ".toml");
    const MaterialLibrary& compiled = shipped(id);
    EXPECT_EQ(file.id, compiled.id);
    EXPECT_EQ(file.citation, compiled.citation);
    ASSERT_EQ(file.materials.size(), compiled.materials.size()) << id;
    for (std::size_t i = 0; i < file.materials.size(); ++i) {
      EXPECT_EQ(file.materials[i].name, compiled.materials[i].name);
      EXPECT_EQ(file.materials[i].sigma_a, compiled.materials[i].sigma_a);
    }
  }
}

// Narasimhan et al. 2006, Table 1 (diluted samples), values checked against the table as
// transcribed in data/materials/narasimhan2006.toml's sources.
TEST(MaterialPresets, NarasimhanTableLoads) {
  const MaterialLibrary& library = shipped("narasimhan2006");
  EXPECT_EQ(library.length_unit, "mm");
  EXPECT_NE(library.citation.find("Narasimhan"), std::string::npos);
  EXPECT_NE(library.citation.find("Table 1"), std::string::npos);
  EXPECT_DOUBLE_EQ(library.eta, 1.33);
  ASSERT_EQ(library.materials.size(), 34u);
  for (const MaterialPreset& m : library.materials) {
    EXPECT_TRUE(m.sigma_s_reduced.empty()) << m.name;
    ASSERT_EQ(m.sigma_s.size(), 3u) << m.name;
    ASSERT_EQ(m.g.size(), 3u) << m.name;
    ASSERT_EQ(m.sigma_a.size(), 3u) << m.name;
  }
  const MaterialPreset& milk = library.find("regular_milk");
  EXPECT_DOUBLE_EQ(milk.sigma_s[0], 1.1873);
  EXPECT_DOUBLE_EQ(milk.sigma_a[2], 0.0013);
  EXPECT_DOUBLE_EQ(milk.g[2], 0.681);
  EXPECT_DOUBLE_EQ(library.find("espresso").sigma_a[1], 0.2287);
  EXPECT_DOUBLE_EQ(library.find("white_grapefruit_juice").g[0], 0.548);
  EXPECT_DOUBLE_EQ(library.find("merlot").sigma_s[2], 0.0);
  // pbrt-v2 lists sigma_t = sigma_s + sigma_a of the same rows: 1.1874, 0.4376 and 0.7143.
  EXPECT_NEAR(milk.sigma_s[0] + milk.sigma_a[0], 1.1874, 1e-12);
  const MaterialPreset& espresso = library.find("espresso");
  EXPECT_NEAR(espresso.sigma_s[0] + espresso.sigma_a[0], 0.4376, 1e-12);
  const MaterialPreset& coke = library.find("coke");
  EXPECT_NEAR(coke.sigma_s[0] + coke.sigma_a[0], 0.7143, 1e-12);
}

// Every material of every table is a valid medium on every channel, in its table's unit.
TEST(MaterialPresets, EveryMaterialResolvesOnEveryChannel) {
  std::size_t resolved = 0;
  for (const MaterialLibrary& library : shipped_material_libraries()) {
    for (const MaterialPreset& preset : library.materials) {
      for (std::size_t k = 0; k < library.channels.size(); ++k) {
        const ResolvedMaterial m = resolve_material(
            {library.id + "/" + preset.name, library.channels[k], {}, {}}, scene_fields);
        EXPECT_NO_THROW(m.medium.validate()) << preset.name;
        EXPECT_EQ(m.medium.length_unit, library.length_unit);
        EXPECT_NEAR(m.medium.sigma_a(), preset.sigma_a[k], 1e-12 * (1 + preset.sigma_a[k]));
        EXPECT_EQ(m.origin.channel, library.channels[k]);
        EXPECT_EQ(m.eta, library.eta);
        ++resolved;
      }
    }
  }
  EXPECT_EQ(resolved, (12u + 34u) * 3u);
}

// Jensen's table has sigma_s' only: g = 0 and sigma_s = sigma_s' by default; a chosen g keeps
// sigma_s' (sigma_s = sigma_s' / (1 - g)). Narasimhan's g is replaced alone.
TEST(MaterialPresets, GChoiceAndUnits) {
  const ResolvedMaterial apple = resolve_material({"apple", "red", {}, {}}, scene_fields);
  EXPECT_DOUBLE_EQ(apple.medium.g, 0.0);
  EXPECT_DOUBLE_EQ(apple.medium.sigma_t, 2.29 + 0.0030);
  EXPECT_NEAR(apple.medium.sigma_s(), 2.29, 1e-12);
  EXPECT_DOUBLE_EQ(apple.eta, 1.3);
  EXPECT_NE(apple.origin.note.find("similarity"), std::string::npos);
  const ResolvedMaterial forward = resolve_material({"apple", "red", {}, 0.5}, scene_fields);
  EXPECT_DOUBLE_EQ(forward.medium.g, 0.5);
  EXPECT_NEAR(forward.medium.sigma_s() * (1.0 - 0.5), 2.29, 1e-12);
  const ResolvedMaterial milk = resolve_material({"Regular Milk", "blue", {}, 0.2}, scene_fields);
  EXPECT_DOUBLE_EQ(milk.medium.g, 0.2);
  EXPECT_NEAR(milk.medium.sigma_s(), 1.4589, 1e-12);
  EXPECT_EQ(milk.origin.name, "regular_milk");
  // However its words are joined: Jensen writes "skimmilk", a user "skim milk" or "Skim-Milk".
  for (const char* name : {"skim milk", "Skim-Milk", "skim_milk", "jensen2001/skim milk"}) {
    EXPECT_EQ(resolve_material({name, "red", {}, {}}, scene_fields).origin.name, "skimmilk")
        << name;
  }
  // 1/mm -> 1/cm: ten times larger.
  const ResolvedMaterial in_cm = resolve_material({"apple", "red", "cm", {}}, scene_fields);
  EXPECT_EQ(in_cm.medium.length_unit, "cm");
  EXPECT_NEAR(in_cm.medium.sigma_t, 10.0 * (2.29 + 0.0030), 1e-12);
}

std::string field_of(const MaterialRequest& request,
                     const std::vector<MaterialLibrary>& libraries = shipped_material_libraries(),
                     std::string* message = nullptr) {
  try {
    resolve_material(request, scene_fields, libraries);
  } catch (const InputError& e) {
    if (message != nullptr) *message = e.what();
    return e.field();
  }
  return "(accepted)";
}

TEST(MaterialPresets, BadRequestsNameTheField) {
  std::string message;
  EXPECT_EQ(field_of({"ketchp", "red", {}, {}}, shipped_material_libraries(), &message),
            "medium.material");
  EXPECT_NE(message.find("did you mean \"ketchup\""), std::string::npos) << message;
  EXPECT_NE(message.find("narasimhan2006: "), std::string::npos) << message;  // lists names
  EXPECT_EQ(field_of({"apple", {}, {}, {}}), "medium.channel");
  EXPECT_EQ(field_of({"apple", "violet", {}, {}}), "medium.channel");
  EXPECT_EQ(field_of({"apple", "red", "mfp", {}}), "medium.length_unit");
  EXPECT_EQ(field_of({"apple", "red", "furlong", {}}), "medium.length_unit");
  EXPECT_EQ(field_of({"apple", "red", {}, 1.0}), "medium.g");
  EXPECT_EQ(field_of({"narasimhan2006/apple", "red", {}, {}}), "medium.material");
  // A name in two tables must be qualified.
  std::vector<MaterialLibrary> two = {shipped("jensen2001"), shipped("jensen2001")};
  two[1].id = "copy";
  EXPECT_EQ(field_of({"apple", "red", {}, {}}, two, &message), "medium.material");
  EXPECT_NE(message.find("jensen2001/apple or copy/apple"), std::string::npos) << message;
  EXPECT_EQ(field_of({"copy/apple", "red", {}, {}}, two), "(accepted)");
}

}  // namespace
}  // namespace scatterlab

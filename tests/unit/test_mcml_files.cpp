// MCML's files: the input reader (.mci) against MCML 1.2.2's format and this engine's limits, and
// the output writer (.mco) against MCML's layout, read back the way MCML's CONV reads it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "input_error_field.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/mcml_input.hpp"
#include "scatterlab/io/mco_file.hpp"
#include "scratch_directory.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;
using test_support::field_of;

// A fresh directory per test (scratch_directory.hpp).
class McmlFilesTest : public test_support::ScratchDirectoryTest {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path path = directory_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
};

// Two runs, with the comments, blank lines, tabs and trailing comments MCML's template has. The
// line numbers matter: the refusals below name them.
const std::vector<std::string> kTwoRuns = {
    "#### MCML input for the reader's tests",        // 1
    "",                                              // 2
    "1.0\t\t\t\t\t\t# file version",                 // 3
    "2\t\t\t\t\t\t# number of runs",                 // 4
    "",                                              // 5
    "### run 1",                                     // 6
    "first.mco\tA\t\t\t\t# output filename, ASCII",  // 7
    "1000000\t\t\t\t\t\t# No. of photons",           // 8
    "0.01\t0.02\t\t\t\t\t# dz, dr",                  // 9
    "40\t50\t30\t\t\t\t# No. of dz, dr & da.",       // 10
    "   # an indented comment",                      // 11
    "2\t\t\t\t\t\t# No. of layers",                  // 12
    "1.0\t\t\t\t\t\t# n for medium above.",          // 13
    "1.37\t1\t100\t0.90\t0.1\t\t# layer 1",          // 14
    "1.4  0.5  10  0  1.0E+8   # layer 2",           // 15
    "1.0#n for medium below, no space before #",     // 16
    "\t",                                            // 17
    "### run 2",                                     // 18
    "second.mco a",                                  // 19
    "+2000",                                         // 20
    "5E-3 0.005",                                    // 21
    "10 20 5",                                       // 22
    "1",                                             // 23
    "1.33",                                          // 24
    "1.5 -0 0 -0.5 2.5",                             // 25
    "1.5",                                           // 26
};

std::string joined(const std::vector<std::string>& lines, const std::string& end = "\n") {
  std::string text;
  for (const std::string& line : lines) text += line + end;
  return text;
}

TEST_F(McmlFilesTest, McmlInputReadsEveryRunAndEveryValue) {
  const fs::path path = write("two.mci", joined(kTwoRuns));
  const std::vector<McmlRun> runs = read_mcml_input(path);
  ASSERT_EQ(runs.size(), 2u);

  const McmlRun& first = runs[0];
  EXPECT_EQ(first.output_file, "first.mco");
  EXPECT_EQ(first.file_format, 'A');
  EXPECT_EQ(first.photons, 1000000u);
  EXPECT_EQ(first.dz, 0.01);
  EXPECT_EQ(first.dr, 0.02);
  EXPECT_EQ(first.nz, 40);
  EXPECT_EQ(first.nr, 50);
  EXPECT_EQ(first.na, 30);
  EXPECT_EQ(first.n_above, 1.0);
  ASSERT_EQ(first.layers.size(), 2u);
  EXPECT_EQ(first.layers[0].n, 1.37);
  EXPECT_EQ(first.layers[0].mu_a, 1.0);
  EXPECT_EQ(first.layers[0].mu_s, 100.0);
  EXPECT_EQ(first.layers[0].g, 0.9);
  EXPECT_EQ(first.layers[0].thickness, 0.1);
  EXPECT_EQ(first.layers[1].n, 1.4);
  EXPECT_EQ(first.layers[1].mu_a, 0.5);
  EXPECT_EQ(first.layers[1].mu_s, 10.0);
  EXPECT_EQ(first.layers[1].g, 0.0);
  EXPECT_EQ(first.layers[1].thickness, 1.0e8);
  EXPECT_EQ(first.n_below, 1.0);
  EXPECT_EQ(first.line, 7);

  const McmlRun& second = runs[1];
  EXPECT_EQ(second.output_file, "second.mco");
  EXPECT_EQ(second.file_format, 'A');  // MCML reads the letter case-blind
  EXPECT_EQ(second.photons, 2000u);
  EXPECT_EQ(second.dz, 0.005);
  EXPECT_EQ(second.dr, 0.005);
  EXPECT_EQ(second.nz, 10);
  EXPECT_EQ(second.nr, 20);
  EXPECT_EQ(second.na, 5);
  EXPECT_EQ(second.n_above, 1.33);
  ASSERT_EQ(second.layers.size(), 1u);
  EXPECT_EQ(second.layers[0].n, 1.5);
  EXPECT_EQ(second.layers[0].mu_a, 0.0);
  EXPECT_FALSE(std::signbit(second.layers[0].mu_a));  // "-0" read as 0
  EXPECT_EQ(second.layers[0].mu_s, 0.0);
  EXPECT_EQ(second.layers[0].g, -0.5);
  EXPECT_EQ(second.layers[0].thickness, 2.5);
  EXPECT_EQ(second.n_below, 1.5);
  EXPECT_EQ(second.line, 19);
}

TEST_F(McmlFilesTest, McmlInputReadsWindowsLineEndsAndNoFinalLineEnd) {
  const std::vector<McmlRun> unix_runs = read_mcml_input(write("unix.mci", joined(kTwoRuns)));
  std::string windows = joined(kTwoRuns, "\r\n");
  const std::vector<McmlRun> windows_runs = read_mcml_input(write("windows.mci", windows));
  windows.resize(windows.size() - 2);
  const std::vector<McmlRun> unended_runs = read_mcml_input(write("unended.mci", windows));
  for (const auto* runs : {&windows_runs, &unended_runs}) {
    ASSERT_EQ(runs->size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      const McmlRun& a = unix_runs[i];
      const McmlRun& b = (*runs)[i];
      EXPECT_EQ(a.output_file, b.output_file);
      EXPECT_EQ(a.photons, b.photons);
      EXPECT_EQ(a.nz, b.nz);
      EXPECT_EQ(a.layers.size(), b.layers.size());
      EXPECT_EQ(a.n_below, b.n_below);
      EXPECT_EQ(a.line, b.line);
    }
  }
}

// The text reader (what the fuzz target reads) is the file reader's: the same runs, and the same
// refusal, word for word, when the origin is the file's path.
TEST_F(McmlFilesTest, McmlInputFromTextReadsAsFromTheFile) {
  const fs::path path = write("two.mci", joined(kTwoRuns));
  const std::vector<McmlRun> from_file = read_mcml_input(path);
  const std::vector<McmlRun> from_text = parse_mcml_input(joined(kTwoRuns), path.string());
  ASSERT_EQ(from_text.size(), from_file.size());
  for (std::size_t i = 0; i < from_file.size(); ++i) {
    EXPECT_EQ(from_text[i].output_file, from_file[i].output_file);
    EXPECT_EQ(from_text[i].photons, from_file[i].photons);
    EXPECT_EQ(from_text[i].nr, from_file[i].nr);
    EXPECT_EQ(from_text[i].layers.size(), from_file[i].layers.size());
    EXPECT_EQ(from_text[i].n_below, from_file[i].n_below);
    EXPECT_EQ(from_text[i].line, from_file[i].line);
  }
  std::vector<std::string> lines = kTwoRuns;
  lines[14] = "1.4 0.5 10 1 1e8";
  const fs::path bad = write("bad.mci", joined(lines));
  const auto message_of = [](auto&& read) {
    try {
      read();
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no InputError");
  };
  EXPECT_EQ(message_of([&] { parse_mcml_input(joined(lines), bad.string()); }),
            message_of([&] { read_mcml_input(bad); }));
}

struct Refusal {
  int line;                 // the line of kTwoRuns replaced
  std::string replacement;  // its new text
  std::string field;        // the field the error names on that line
};

TEST_F(McmlFilesTest, McmlInputRefusesEachMalformedValueNamingLineAndField) {
  const std::vector<Refusal> refusals = {
      {3, "2.0", "file version"},
      {3, "mcmli2.0", "file version"},
      {3, "1.0 2", "file version"},
      {4, "0", "number of runs"},
      {4, "2.0", "number of runs"},
      {7, "first.mco B", "format"},
      {7, "first.mco", "format"},
      {7, "first.mco A B", "format"},
      {8, "0", "photons"},
      {8, "-5", "photons"},
      {8, "1e6", "photons"},  // MCML would run 1 photon
      {8, "1000000.0", "photons"},
      {8, "99999999999999999999", "photons"},
      {8, "0x10", "photons"},
      {9, "0 0.02", "dz"},
      {9, "-0.01 0.02", "dz"},
      {9, "nan 0.02", "dz"},
      {9, "inf 0.02", "dz"},
      {9, "1e999 0.02", "dz"},
      {9, "0x1p-4 0.02", "dz"},
      {9, "0.01x 0.02", "dz"},
      {9, "0.01 zero", "dr"},
      {9, "0.01 0", "dr"},
      {9, "0.01", "dr"},
      {10, "0 50 30", "Nz"},
      {10, "40 100001 30", "Nr"},
      {10, "40 -1 30", "Nr"},
      {10, "40 50 30.0", "Na"},
      {10, "40 50", "Na"},
      {12, "0", "number of layers"},
      {12, "two", "number of layers"},
      {13, "0", "n above"},
      {13, "-inf", "n above"},
      {14, "-1.37 1 100 0.9 0.1", "layer 1 n"},
      {14, "0 1 100 0.9 0.1", "layer 1 n"},
      {15, "1.4 -0.5 10 0 1e8", "layer 2 mua"},
      {15, "1.4 inf 10 0 1e8", "layer 2 mua"},
      {15, "1.4 0.5 -10 0 1e8", "layer 2 mus"},
      {15, "1.4 0.5 10 1 1e8", "layer 2 g"},
      {15, "1.4 0.5 10 -1 1e8", "layer 2 g"},
      {15, "1.4 0.5 10 1.5 1e8", "layer 2 g"},
      {15, "1.4 0.5 10 0 0", "layer 2 d"},
      {15, "1.4 0.5 10 0 -1", "layer 2 d"},
      {15, "1.4 0.5 10 0 inf", "layer 2 d"},
      {15, "1.4 0.5 10 0", "layer 2 d"},
      {15, "1.4 0.5 10 0 1e8 7", "layer 2 d"},
      {15, "1.4 0.5 10", "layer 2 g"},
      {16, "nan", "n below"},
      {19, "first.mco A", "output file"},  // as MCML's CheckParm: one file per run
      {19, "second\x01.mco A", "output file"},
      {25, "1.5 0 0 0.9", "layer 1 d"},
  };
  for (const Refusal& refusal : refusals) {
    std::vector<std::string> lines = kTwoRuns;
    lines[static_cast<std::size_t>(refusal.line - 1)] = refusal.replacement;
    const fs::path path = write("bad.mci", joined(lines));
    const std::string expected =
        path.string() + ":" + std::to_string(refusal.line) + " " + refusal.field;
    SCOPED_TRACE(refusal.replacement);
    EXPECT_EQ(field_of([&] { read_mcml_input(path); }), expected);
    try {
      read_mcml_input(path);
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(expected + ": ", 0), 0u) << message;
      EXPECT_NE(message.find("; accepted: "), std::string::npos) << message;
    }
  }
}

TEST_F(McmlFilesTest, McmlInputSaysWhatItAccepts) {
  std::vector<std::string> lines = kTwoRuns;
  lines[14] = "1.4 0.5 10 1 1e8";
  const fs::path g_path = write("g.mci", joined(lines));
  try {
    read_mcml_input(g_path);
    ADD_FAILURE() << "g = 1 was read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("|g| < 1"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("Henyey-Greenstein"), std::string::npos);
  }
  lines = kTwoRuns;
  lines[7] = "1e6";
  const fs::path photons_path = write("photons.mci", joined(lines));
  try {
    read_mcml_input(photons_path);
    ADD_FAILURE() << "1e6 photons was read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("got '1e6'"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("whole number"), std::string::npos);
  }
}

TEST_F(McmlFilesTest, McmlInputRefusesAFileThatEndsEarlyOrGoesOn) {
  // The last line gone: "n below" is missing where the file ends (line 26 of 25).
  std::vector<std::string> lines = kTwoRuns;
  lines.pop_back();
  fs::path path = write("short.mci", joined(lines));
  EXPECT_EQ(field_of([&] { read_mcml_input(path); }), path.string() + ":26 n below");

  // Three runs declared, two written.
  lines = kTwoRuns;
  lines[3] = "3";
  path = write("three.mci", joined(lines));
  EXPECT_EQ(field_of([&] { read_mcml_input(path); }), path.string() + ":27 output file");

  // Data after the last declared run.
  lines = kTwoRuns;
  lines.push_back("# a comment is fine");
  lines.push_back("third.mco A");
  path = write("more.mci", joined(lines));
  EXPECT_EQ(field_of([&] { read_mcml_input(path); }), path.string() + ":28 number of runs");

  // Nothing but comments.
  path = write("empty.mci", "# nothing here\n\n");
  EXPECT_EQ(field_of([&] { read_mcml_input(path); }), path.string() + ":3 file version");
}

TEST_F(McmlFilesTest, McmlInputRefusesWhatIsNotAFile) {
  EXPECT_EQ(field_of([&] { read_mcml_input(directory_); }), "mcml input");
  EXPECT_EQ(field_of([&] { read_mcml_input(directory_ / "absent.mci"); }), "mcml input");
  try {
    read_mcml_input(directory_);
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("is a directory; accepted: a regular MCML input file (.mci)"),
              std::string::npos)
        << message;
  }
}

TEST_F(McmlFilesTest, McmlInputReadsTheShippedFiles) {
  const fs::path data = fs::path(SCATTERLAB_SOURCE_DIR) / "data" / "mcml";

  const std::vector<McmlRun> sample = read_mcml_input(data / "sample.mci");
  ASSERT_EQ(sample.size(), 1u);
  EXPECT_EQ(sample[0].output_file, "sample.mco");
  EXPECT_EQ(sample[0].photons, 1000000u);
  EXPECT_EQ(sample[0].nz, 40);
  EXPECT_EQ(sample[0].nr, 50);
  EXPECT_EQ(sample[0].na, 1);
  ASSERT_EQ(sample[0].layers.size(), 3u);
  EXPECT_EQ(sample[0].layers[2].mu_a, 2.0);
  EXPECT_EQ(sample[0].layers[2].g, 0.7);

  const std::vector<McmlRun> skin = read_mcml_input(data / "skin.mci");
  ASSERT_EQ(skin.size(), 1u);
  ASSERT_EQ(skin[0].layers.size(), 3u);
  EXPECT_EQ(skin[0].layers[0].mu_a, 2.7);
  EXPECT_EQ(skin[0].layers[0].mu_s, 187.0);
  EXPECT_EQ(skin[0].layers[0].thickness, 0.01);
  EXPECT_EQ(skin[0].layers[1].mu_s, 170.0);
  EXPECT_EQ(skin[0].layers[2].thickness, 0.5);

  const std::vector<McmlRun> hulst = read_mcml_input(data / "van_de_hulst.mci");
  ASSERT_EQ(hulst.size(), 1u);
  ASSERT_EQ(hulst[0].layers.size(), 1u);
  EXPECT_EQ(hulst[0].layers[0].g, 0.75);
  EXPECT_EQ(hulst[0].na, 30);
  EXPECT_EQ(hulst[0].n_above, hulst[0].layers[0].n);
  EXPECT_EQ(hulst[0].n_below, hulst[0].layers[0].n);

  const std::vector<McmlRun> giovanelli = read_mcml_input(data / "giovanelli.mci");
  ASSERT_EQ(giovanelli.size(), 1u);
  ASSERT_EQ(giovanelli[0].layers.size(), 1u);
  const McmlLayer& medium = giovanelli[0].layers[0];
  EXPECT_EQ(medium.n, 1.5);
  EXPECT_EQ(giovanelli[0].n_below, 1.5);
  EXPECT_GE(medium.thickness * (medium.mu_a + medium.mu_s), 1000.0);  // mean free paths
}

// A run small enough to write out by hand, and results that exercise the number formats.
McmlRun small_run() {
  McmlRun run;
  run.output_file = "small.mco";
  run.photons = 1000;
  run.dz = 0.01;
  run.dr = 0.02;
  run.nz = 3;
  run.nr = 2;
  run.na = 1;
  run.n_above = 1.0;
  run.layers = {{1.37, 1.0, 100.0, 0.9, 0.1}, {1.4, 0.5, 10.0, 0.0, 1.0e8}};
  run.n_below = 1.0;
  return run;
}

McoResults small_results() {
  McoResults results;
  results.specular_reflectance = 0.0243729;
  results.diffuse_reflectance = 0.237544;
  results.absorbed = 0.641594;
  results.total_transmittance = 0.0964896;
  results.absorbed_by_layer = {0.2612, 0.1488};
  results.absorbed_by_depth = {2.799, 0.000123456, 0.0};
  results.absorbed_density = {3294.8, 3038.6, 2503.3, 1851.4, 1275.8, 853.63};
  results.reflectance_by_radius = {30.924, 10.071};
  results.reflectance_by_angle = {0.034038};
  results.reflectance_by_radius_angle = {1.5, 2.5};
  results.transmittance_by_radius = {0.58942, 0.60085};
  results.transmittance_by_angle = {0.013826};
  results.transmittance_by_radius_angle = {0.25, 1.0e-7};
  return results;
}

// The file MCML 1.2.2's WriteResult writes for small_run(), byte for byte (its printf formats:
// %G for the input echo, %-14.6G for RAT, %12.4G for A_l, %12.4E for the arrays).
const std::string kSmallMco =
    "A1 \t# Version number of the file format.\n"
    "\n"
    "####\n"
    "# Data categories include: \n"
    "# InParm, RAT, \n"
    "# A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, \n"
    "# A_rz, Rd_ra, Tt_ra \n"
    "####\n"
    "\n"
    "# User time:     1488 sec =     0.41 hr.   Simulation time of this run.\n"
    "\n"
    "InParm \t\t\t# Input parameters. cm is used.\n"
    "small.mco \tA\t\t# output file name, ASCII.\n"
    "1000 \t\t\t# No. of photons\n"
    "0.01\t0.02\t\t# dz, dr [cm]\n"
    "3\t2\t1\t# No. of dz, dr, da.\n"
    "\n"
    "2\t\t\t\t\t# Number of layers\n"
    "#n\tmua\tmus\tg\td\t# One line for each layer\n"
    "1\t\t\t\t\t# n for medium above\n"
    "1.37\t1\t100\t0.9\t0.1\t# layer 1\n"
    "1.4\t0.5\t10\t0\t1E+08\t# layer 2\n"
    "1\t\t\t\t\t# n for medium below\n"
    "\n"
    "RAT #Reflectance, absorption, transmission. \n"
    "0.0243729      \t#Specular reflectance [-]\n"
    "0.237544       \t#Diffuse reflectance [-]\n"
    "0.641594       \t#Absorbed fraction [-]\n"
    "0.0964896      \t#Transmittance [-]\n"
    "\n"
    "A_l #Absorption as a function of layer. [-]\n"
    "      0.2612\n"
    "      0.1488\n"
    "\n"
    "A_z #A[0], [1],..A[nz-1]. [1/cm]\n"
    "  2.7990E+00\n"
    "  1.2346E-04\n"
    "  0.0000E+00\n"
    "\n"
    "Rd_r #Rd[0], [1],..Rd[nr-1]. [1/cm2]\n"
    "  3.0924E+01\n"
    "  1.0071E+01\n"
    "\n"
    "Rd_a #Rd[0], [1],..Rd[na-1]. [sr-1]\n"
    "  3.4038E-02\n"
    "\n"
    "Tt_r #Tt[0], [1],..Tt[nr-1]. [1/cm2]\n"
    "  5.8942E-01\n"
    "  6.0085E-01\n"
    "\n"
    "Tt_a #Tt[0], [1],..Tt[na-1]. [sr-1]\n"
    "  1.3826E-02\n"
    "\n"
    "# A[r][z]. [1/cm3]\n"
    "# A[0][0], [0][1],..[0][nz-1]\n"
    "# A[1][0], [1][1],..[1][nz-1]\n"
    "# ...\n"
    "# A[nr-1][0], [nr-1][1],..[nr-1][nz-1]\n"
    "A_rz\n"
    "  3.2948E+03   3.0386E+03   2.5033E+03   1.8514E+03   1.2758E+03 \n"
    "  8.5363E+02 \n"
    "# Rd[r][angle]. [1/(cm2sr)].\n"
    "# Rd[0][0], [0][1],..[0][na-1]\n"
    "# Rd[1][0], [1][1],..[1][na-1]\n"
    "# ...\n"
    "# Rd[nr-1][0], [nr-1][1],..[nr-1][na-1]\n"
    "Rd_ra\n"
    "  1.5000E+00   2.5000E+00 \n"
    "# Tt[r][angle]. [1/(cm2sr)].\n"
    "# Tt[0][0], [0][1],..[0][na-1]\n"
    "# Tt[1][0], [1][1],..[1][na-1]\n"
    "# ...\n"
    "# Tt[nr-1][0], [nr-1][1],..[nr-1][na-1]\n"
    "Tt_ra\n"
    "  2.5000E-01   1.0000E-07 \n";

TEST_F(McmlFilesTest, McoWritesMcmlsLayoutByteForByte) {
  const fs::path path = directory_ / "small.mco";
  write_mco(path, small_run(), small_results(), 1488.13);
  EXPECT_EQ(read(path), kSmallMco);
}

// Reads an .mco as MCML's CONV does: data lines are those that are neither blank nor start
// (after blanks) with '#'; each section is found by the keyword at the start of a data line; a
// 1D array is one number per data line, a 2D array free-form numbers after its keyword.
class ConvLikeReader {
 public:
  explicit ConvLikeReader(const std::string& text) : in_(text) {}

  std::string data_line() {
    std::string line;
    while (std::getline(in_, line)) {
      const std::size_t first = line.find_first_not_of(" \t");
      if (first != std::string::npos && line[first] != '#') return line;
    }
    throw std::runtime_error("incomplete data");
  }
  void seek(const std::string& key) {
    while (data_line().rfind(key, 0) != 0) {
    }
  }
  double number_line() {
    double value = 0;
    if (std::sscanf(data_line().c_str(), "%lf", &value) != 1) throw std::runtime_error("number");
    return value;
  }
  std::vector<double> numbers_by_line(std::size_t count) {
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) values.push_back(number_line());
    return values;
  }
  std::vector<double> free_numbers(std::size_t count) {
    std::vector<double> values(count);
    for (double& value : values) {
      if (!(in_ >> value)) throw std::runtime_error("free-form number");
    }
    return values;
  }

 private:
  std::istringstream in_;
};

// 4 significant digits: the arrays' %12.4E keeps 5, A_l's %12.4G keeps 4.
void expect_four_digits(const std::vector<double>& read_back, const std::vector<double>& written,
                        const std::string& name) {
  ASSERT_EQ(read_back.size(), written.size()) << name;
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_LE(std::abs(read_back[i] - written[i]), 5e-4 * std::abs(written[i]))
        << name << "[" << i << "]: " << read_back[i] << " for " << written[i];
  }
}

TEST_F(McmlFilesTest, McoRoundTripsThroughAConvLikeReader) {
  McmlRun run = small_run();
  run.nz = 7;
  run.nr = 4;
  run.na = 3;
  run.layers.push_back({1.33, 0.01, 250.5, 0.95, 0.25});
  // Values over many decades, signs and exponents of both widths.
  double seed = 0.61803398875;
  auto next = [&seed](int decade) {
    seed = std::fmod(seed * 9301.0 + 0.49297, 1.0);
    return (0.1 + seed) * std::pow(10.0, decade);
  };
  auto values = [&](std::size_t count) {
    std::vector<double> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(next(static_cast<int>(i % 13) - 6));
    return out;
  };
  const auto nz = static_cast<std::size_t>(run.nz), nr = static_cast<std::size_t>(run.nr),
             na = static_cast<std::size_t>(run.na);
  McoResults results;
  results.specular_reflectance = 0.0277777;
  results.diffuse_reflectance = 0.123456789;
  results.absorbed = 0.7;
  results.total_transmittance = 1.5e-5;
  results.absorbed_by_layer = values(run.layers.size());
  results.absorbed_by_depth = values(nz);
  results.absorbed_density = values(nr * nz);
  results.absorbed_density[3] = 1.0e-120;
  results.absorbed_density[4] = 2.5e+150;
  results.reflectance_by_radius = values(nr);
  results.reflectance_by_angle = values(na);
  results.reflectance_by_radius_angle = values(nr * na);
  results.transmittance_by_radius = values(nr);
  results.transmittance_by_angle = values(na);
  results.transmittance_by_radius_angle = values(nr * na);
  const fs::path path = directory_ / "round.mco";
  write_mco(path, run, results, 12.5);
  const std::string text = read(path);

  ConvLikeReader conv(text);
  EXPECT_EQ(conv.data_line().rfind("A1", 0), 0u);  // the version, first data line
  conv.seek("InParm");
  EXPECT_EQ(conv.data_line().substr(0, 10), "small.mco ");  // name and format, skipped by CONV
  EXPECT_EQ(conv.number_line(), 1000.0);
  std::istringstream steps(conv.data_line());
  double dz = 0, dr = 0;
  steps >> dz >> dr;
  EXPECT_EQ(dz, run.dz);
  EXPECT_EQ(dr, run.dr);
  std::istringstream bins(conv.data_line());
  int read_nz = 0, read_nr = 0, read_na = 0;
  bins >> read_nz >> read_nr >> read_na;
  EXPECT_EQ(read_nz, run.nz);
  EXPECT_EQ(read_nr, run.nr);
  EXPECT_EQ(read_na, run.na);
  EXPECT_EQ(conv.number_line(), 3.0);
  EXPECT_EQ(conv.number_line(), run.n_above);
  for (const McmlLayer& layer : run.layers) {
    std::istringstream line(conv.data_line());
    double n = 0, mua = 0, mus = 0, g = 0, d = 0;
    line >> n >> mua >> mus >> g >> d;
    expect_four_digits({n, mua, mus, g, d},
                       {layer.n, layer.mu_a, layer.mu_s, layer.g, layer.thickness}, "layer");
  }
  EXPECT_EQ(conv.number_line(), run.n_below);

  conv.seek("RAT");
  expect_four_digits(conv.numbers_by_line(4),
                     {results.specular_reflectance, results.diffuse_reflectance, results.absorbed,
                      results.total_transmittance},
                     "RAT");
  conv.seek("A_l");
  expect_four_digits(conv.numbers_by_line(run.layers.size()), results.absorbed_by_layer, "A_l");
  conv.seek("A_z");
  expect_four_digits(conv.numbers_by_line(nz), results.absorbed_by_depth, "A_z");
  conv.seek("Rd_r");
  expect_four_digits(conv.numbers_by_line(nr), results.reflectance_by_radius, "Rd_r");
  conv.seek("Rd_a");
  expect_four_digits(conv.numbers_by_line(na), results.reflectance_by_angle, "Rd_a");
  conv.seek("Tt_r");
  expect_four_digits(conv.numbers_by_line(nr), results.transmittance_by_radius, "Tt_r");
  conv.seek("Tt_a");
  expect_four_digits(conv.numbers_by_line(na), results.transmittance_by_angle, "Tt_a");
  conv.seek("A_rz");
  expect_four_digits(conv.free_numbers(nr * nz), results.absorbed_density, "A_rz");
  conv.seek("Rd_ra");
  expect_four_digits(conv.free_numbers(nr * na), results.reflectance_by_radius_angle, "Rd_ra");
  conv.seek("Tt_ra");
  expect_four_digits(conv.free_numbers(nr * na), results.transmittance_by_radius_angle, "Tt_ra");

  // The sections in MCML's order, each keyword once, at the start of its line.
  const std::vector<std::string> keywords = {"InParm", "RAT",  "A_l",  "A_z",   "Rd_r", "Rd_a",
                                             "Tt_r",   "Tt_a", "A_rz", "Rd_ra", "Tt_ra"};
  std::vector<std::string> found;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string word = line.substr(0, line.find_first_of(" \t"));
    for (const std::string& keyword : keywords) {
      if (word == keyword) found.push_back(word);
    }
  }
  EXPECT_EQ(found, keywords);

  // Five numbers to a line in the 2D arrays: A_rz's 28 values on 6 lines, 3 on the last.
  const std::size_t a_rz = text.find("\nA_rz\n") + 6;
  std::istringstream block(text.substr(a_rz));
  std::vector<std::size_t> per_line;
  while (std::getline(block, line) && !line.empty() && line[0] != '#') {
    std::istringstream words(line);
    std::size_t count = 0;
    for (std::string number; words >> number;) ++count;
    per_line.push_back(count);
  }
  EXPECT_EQ(per_line, (std::vector<std::size_t>{5, 5, 5, 5, 5, 3}));
}

TEST_F(McmlFilesTest, McoRefusesResultsThatDoNotFitTheGrid) {
  using Member = std::vector<double> McoResults::*;
  const std::vector<Member> members = {&McoResults::absorbed_by_layer,
                                       &McoResults::absorbed_by_depth,
                                       &McoResults::absorbed_density,
                                       &McoResults::reflectance_by_radius,
                                       &McoResults::reflectance_by_angle,
                                       &McoResults::reflectance_by_radius_angle,
                                       &McoResults::transmittance_by_radius,
                                       &McoResults::transmittance_by_angle,
                                       &McoResults::transmittance_by_radius_angle};
  const fs::path path = directory_ / "refused.mco";
  for (std::size_t i = 0; i < members.size(); ++i) {
    SCOPED_TRACE(i);
    McoResults longer = small_results();
    (longer.*members[i]).push_back(1.0);
    EXPECT_THROW(write_mco(path, small_run(), longer, 1.0), std::invalid_argument);
    McoResults shorter = small_results();
    (shorter.*members[i]).pop_back();
    EXPECT_THROW(write_mco(path, small_run(), shorter, 1.0), std::invalid_argument);
    McoResults not_finite = small_results();
    (not_finite.*members[i]).back() = std::nan("");
    EXPECT_THROW(write_mco(path, small_run(), not_finite, 1.0), std::invalid_argument);
  }
  McmlRun unnamed = small_run();
  unnamed.output_file = "two words.mco";
  EXPECT_THROW(write_mco(path, unnamed, small_results(), 1.0), std::invalid_argument);
  EXPECT_THROW(write_mco(path, small_run(), small_results(), -1.0), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(directory_));  // no temporary left either
}

}  // namespace
}  // namespace scatterlab

// The explorer's API (explore/api.hpp) called without a socket, its text models
// (explore/text_model.hpp), and one request through the HTTP server on a free loopback port.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <thread>

#include "../unit/scratch_directory.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/explore/api.hpp"
#include "scatterlab/explore/server.hpp"
#include "scatterlab/explore/text_model.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/models/lit_sphere_exitance.hpp"
#include "scatterlab/models/parameter_inversion.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/searchlight.hpp"
#if SCATTERLAB_EXPLORE_MESH
#include "scatterlab/render/point_cloud.hpp"
#include "scatterlab/render/point_octree.hpp"
#include "scatterlab/render/render_scene.hpp"
#endif

// Last: httplib includes <resolv.h>, whose macro _res breaks Eigen's headers included after it.
#include <httplib.h>

namespace scatterlab {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

const fs::path kSource = SCATTERLAB_SOURCE_DIR;

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

class ExploreApiTest : public test_support::ScratchDirectoryTest {
 protected:
  void SetUp() override {
    ScratchDirectoryTest::SetUp();
    page_ = directory_ / "page";
    open_ = directory_ / "open";
    models_ = directory_ / "models";
    for (const fs::path& folder : {page_, open_, models_}) fs::create_directories(folder);
    write(page_ / "index.html", "<html>the page</html>");
    write(page_ / "explore.js", "// script");
    write(directory_ / "secret.txt", "not to be served");
    fs::copy_file(kSource / "data/models/dipole_text.toml", models_ / "dipole_text.toml");
  }
  ExploreApi api() const { return ExploreApi({page_, {open_}, models_}); }
  static json body_of(const ApiResponse& response) { return json::parse(response.body); }
  ApiResponse post(const std::string& path, const json& body) const {
    return api().handle("POST", path, {}, body.dump());
  }

  fs::path page_, open_, models_;
};

json medium(double sigma_a, double sigma_s_reduced, double g, double eta) {
  return {{"sigma_a", sigma_a}, {"sigma_s_reduced", sigma_s_reduced}, {"g", g}, {"eta", eta}};
}

TEST_F(ExploreApiTest, ProfilesAreTheModelsValuesAtTheReturnedRadii) {
  const json request{
      {"medium", medium(0.02, 1.5, 0.4, 1.3)},
      {"scale", 2.0},
      {"points", 64},
      {"models", {"dipole", "better_dipole", "quantized_diffusion", "single_scatter"}}};
  const ApiResponse response = post("/api/profiles", request);
  ASSERT_EQ(response.status, 200) << response.body;
  const json answer = body_of(response);
  // The plot's medium: the coefficients times the scale, sigma_s = sigma_s' / (1 - g).
  HalfSpaceMedium m;
  m.sigma_a = 0.04;
  m.sigma_s = 3.0 / 0.6;
  m.g = 0.4;
  m.eta = 1.3;
  const std::vector<double> r = answer["r"].get<std::vector<double>>();
  ASSERT_EQ(r.size(), 64u);
  EXPECT_GT(r.front(), 0.0);
  EXPECT_DOUBLE_EQ(r.back(), answer["r_max"].get<double>());
  ASSERT_EQ(answer["curves"].size(), 4u);
  for (const json& curve : answer["curves"]) {
    const std::string name = curve["model"];
    const std::vector<double> values = curve["values"].get<std::vector<double>>();
    ASSERT_EQ(values.size(), r.size()) << name;
    for (std::size_t k = 0; k < r.size(); k += 9) {
      double expected = 0.0;
      if (name == "single_scatter") {
        const Medium plain = Medium::from_coefficients(m.sigma_a, m.sigma_s, m.g, "mm");
        const double r0 = (1.3 - 1.0) / (1.3 + 1.0);
        expected = half_space_single_scatter_exitance(plain, m.eta, r[k]).value / (1.0 - r0 * r0);
      } else {
        expected = DiffusionProfile(parse_profile_model(name, "model"), m).reflectance(r[k]);
      }
      EXPECT_NEAR(values[k], expected, 1e-12 * std::abs(expected)) << name << " r " << r[k];
    }
    EXPECT_GE(curve["ms"].get<double>(), 0.0);
  }
}

TEST_F(ExploreApiTest, TheDipoleAsATextFileIsTheBuiltInDipole) {
  for (const double eta : {1.0, 1.3, 0.8, 2.0}) {
    for (const double albedo : {0.3, 0.9, 0.999}) {
      HalfSpaceMedium m;
      m.sigma_a = 1.0 - albedo;
      m.sigma_s = albedo / (1.0 - 0.3);
      m.g = 0.3;
      m.eta = eta;
      const TextModel text = TextModel::load(kSource / "data/models/dipole_text.toml");
      std::vector<double> r;
      for (double x = 1e-3; x < 60.0; x *= 1.3) r.push_back(x);
      const std::vector<double> values = text.reflectance(m, {}, r);
      const DiffusionProfile dipole(ProfileModel::dipole, m);
      for (std::size_t k = 0; k < r.size(); ++k) {
        const double expected = dipole.reflectance(r[k]);
        ASSERT_GT(expected, 0.0);
        EXPECT_LE(std::abs(values[k] - expected), 1e-9 * expected)
            << "eta " << eta << " albedo " << albedo << " r " << r[k];
      }
    }
  }
  // And through the API, beside the built-in one.
  const ApiResponse response = post("/api/profiles", {{"medium", medium(0.01, 1.0, 0.0, 1.3)},
                                                      {"points", 50},
                                                      {"models", {"dipole", "dipole_text"}}});
  ASSERT_EQ(response.status, 200) << response.body;
  const json curves = body_of(response)["curves"];
  for (std::size_t k = 0; k < 50; ++k) {
    const double a = curves[0]["values"][k], b = curves[1]["values"][k];
    EXPECT_LE(std::abs(a - b), 1e-9 * a);
  }
}

TEST_F(ExploreApiTest, TextModelParametersAreUsedAndChecked) {
  write(models_ / "scaled.toml", R"toml(name = "scaled"
define = ["w = k * sigma_t_reduced"]
R_d = "w * exp(-r)"
[[parameter]]
name = "k"
min = 0.0
max = 4.0
default = 1.0
)toml");
  HalfSpaceMedium m;
  m.sigma_a = 0.5;
  m.sigma_s = 1.5;
  const TextModel model = TextModel::load(models_ / "scaled.toml");
  const std::vector<double> r{0.0, 1.0};
  EXPECT_DOUBLE_EQ(model.reflectance(m, {}, r)[1], 2.0 * std::exp(-1.0));
  EXPECT_DOUBLE_EQ(model.reflectance(m, {{"k", 3.0}}, r)[0], 6.0);
  const auto field = [&](const std::map<std::string, double>& values) {
    try {
      model.reflectance(m, values, r);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field({{"k", 5.0}}), "parameters.k");
  EXPECT_EQ(field({{"q", 1.0}}), "parameters.q");
  const ApiResponse response = post("/api/profiles", {{"medium", medium(0.5, 1.5, 0.0, 1.0)},
                                                      {"points", 4},
                                                      {"models", {"scaled"}},
                                                      {"parameters", {{"scaled", {{"k", 9.0}}}}}});
  EXPECT_EQ(response.status, 400);
  EXPECT_NE(response.body.find("parameters.k"), std::string::npos) << response.body;
}

// A bad model file: one InputError naming the file, its line and the key.
std::string error_of(const std::string& text) {
  try {
    TextModel::parse(text, "bad.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(TextModel, ABadFileIsOneErrorNamingFileLineAndKey) {
  EXPECT_EQ(error_of("name = \"x\"\nR_d = \"exp(-r\"\n").rfind("bad.toml:2: R_d: ", 0), 0u)
      << error_of("name = \"x\"\nR_d = \"exp(-r\"\n");
  EXPECT_NE(error_of("name = \"x\"\nR_d = \"nosuch * r\"\n").find("nosuch"), std::string::npos);
  EXPECT_EQ(error_of("name = \"x\"\n\nRd = \"r\"\n").rfind("bad.toml:3: Rd: unknown key", 0), 0u);
  EXPECT_EQ(error_of("name = \"x\"\n").rfind("bad.toml:1: R_d: missing", 0), 0u);
  EXPECT_EQ(error_of("name = \"x\"\ndefine = [\"r = 2\"]\nR_d = \"r\"\n")
                .rfind("bad.toml:2: define: \"r\" is already defined", 0),
            0u);
  EXPECT_EQ(error_of("name = \"x\"\ndefine = [\"no assignment\"]\nR_d = \"r\"\n")
                .rfind("bad.toml:2: define", 0),
            0u);
  EXPECT_EQ(error_of("name = \"x\"\n[[parameter]]\nname = \"k\"\nmin = 1\nmax = 0\ndefault = 0\n"
                     "R_d = \"r\"\n")
                .find("min < max"),
            error_of("name = \"x\"\n[[parameter]]\nname = \"k\"\nmin = 1\nmax = 0\ndefault = 0\n"
                     "R_d = \"r\"\n")
                .find("min < max"));
  EXPECT_NE(error_of("name = \"x\"\n[[parameter]]\nname = \"k\"\nmin = 1\nmax = 0\ndefault = 0\n"
                     "R_d = \"r\"\n"),
            "(accepted)");
  EXPECT_EQ(error_of("name = 3\nR_d = \"r\"\n").rfind("bad.toml:1: name: not a string", 0), 0u);
  EXPECT_EQ(error_of("name = [\nR_d").rfind("bad.toml:", 0), 0u);
  EXPECT_EQ(error_of("name = \"ok\"\nR_d = \"exp(-r)\"\n"), "(accepted)");
  // TOML puts keys after a [[parameter]] table into it: the message says where they belong.
  EXPECT_NE(error_of("name = \"x\"\n[[parameter]]\nname = \"k\"\nmin = 0\nmax = 1\ndefault = 0\n"
                     "R_d = \"r\"\n")
                .find("before the first [[parameter]]"),
            std::string::npos);
}

// A name muparser would not take is refused as the file's error, naming its line, not thrown as
// muparser's own exception when the model is first evaluated (tests/fuzz/corpus/text_model/
// crash-long-name.toml).
TEST(TextModel, NamesMuparserRefusesAreTheFilesError) {
  const std::string long_name(101, 'q');
  EXPECT_EQ(error_of("name = \"x\"\ndefine = [\"" + long_name + " = 2\"]\nR_d = \"r\"\n")
                .rfind("bad.toml:2: define: got \"" + long_name + "\"", 0),
            0u)
      << error_of("name = \"x\"\ndefine = [\"" + long_name + " = 2\"]\nR_d = \"r\"\n");
  EXPECT_EQ(error_of("name = \"x\"\nR_d = \"r\"\n[[parameter]]\nname = \"_pi\"\nmin = 0\n"
                     "max = 1\ndefault = 0\n")
                .rfind("bad.toml:4: parameter.name: got \"_pi\"", 0),
            0u);
  const std::string longest(100, 'q');
  EXPECT_EQ(
      error_of("name = \"x\"\ndefine = [\"" + longest + " = 2\"]\nR_d = \"" + longest + " * r\"\n"),
      "(accepted)");
}

TEST_F(ExploreApiTest, ABadModelFileIsRefusedAtStartAndOnReload) {
  const ExploreApi good = api();
  write(models_ / "broken.toml", "name = \"broken\"\nR_d = \"exp(-r\"\n");
  try {
    api();
    FAIL() << "a bad model file accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.toml:2: R_d"), std::string::npos) << e.what();
  }
  // The running explorer keeps its models and answers the reload with the error.
  const ApiResponse reload = good.handle("GET", "/api/models", {}, "");
  EXPECT_EQ(reload.status, 400);
  EXPECT_NE(body_of(reload)["error"].get<std::string>().find("broken.toml:2"), std::string::npos);
  const json info = body_of(good.handle("GET", "/api/info", {}, ""));
  ASSERT_EQ(info["text_models"].size(), 1u);
  EXPECT_EQ(info["text_models"][0]["name"], "dipole_text");
}

TEST_F(ExploreApiTest, BadRequestsGetA4xxAndAMessageNamingTheField) {
  const auto expect = [&](const std::string& path, const std::string& body, int status,
                          const std::string& named) {
    const ApiResponse response = api().handle("POST", path, {}, body);
    EXPECT_EQ(response.status, status) << body << " -> " << response.body;
    const json answer = json::parse(response.body);
    if (status == 200) return;
    EXPECT_NE(answer["error"].get<std::string>().find(named), std::string::npos)
        << body << " -> " << response.body;
  };
  const json ok{{"medium", medium(0.01, 1.0, 0.0, 1.3)}, {"models", {"dipole"}}};
  expect("/api/profiles", "not json", 400, "body");
  expect("/api/profiles", "[1, 2]", 400, "body");
  json bad = ok;
  bad["medium"]["eta"] = 7.0;
  expect("/api/profiles", bad.dump(), 400, "eta");
  bad = ok;
  bad["medium"]["g"] = 1.0;
  expect("/api/profiles", bad.dump(), 400, "g");
  bad = ok;
  bad["medium"]["sigma_a"] = -1.0;
  expect("/api/profiles", bad.dump(), 400, "sigma_a");
  bad = ok;
  bad["medium"]["sigma_a"] = "much";
  expect("/api/profiles", bad.dump(), 400, "medium.sigma_a");
  bad = ok;
  bad["medium"]["sigma_s"] = 1.0;
  expect("/api/profiles", bad.dump(), 400, "medium.sigma_s");
  bad = ok;
  bad["medium"]["colour"] = 1.0;
  expect("/api/profiles", bad.dump(), 400, "medium.colour");
  bad = ok;
  bad["models"] = {"tripole"};
  expect("/api/profiles", bad.dump(), 400, "models");
  bad = ok;
  bad["points"] = 1e9;
  expect("/api/profiles", bad.dump(), 400, "points");
  bad = ok;
  bad["scale"] = 0;
  expect("/api/profiles", bad.dump(), 400, "scale");
  bad = ok;
  bad["r_max"] = -2;
  expect("/api/profiles", bad.dump(), 400, "r_max");
  expect("/api/invert", R"({"R_dr": 2.0, "l_d": 1.0})", 400, "R_dr");
  expect("/api/invert", R"({"R_dr": 0.5, "l_d": 0.0})", 400, "l_d");
  expect("/api/invert", R"({"R_dr": 0.5, "l_d": 1.0, "model": "x"})", 400, "model");
  // tests/fuzz/corpus/explore_request/strict-invert-model-number.txt: 400, not 500.
  expect("/api/invert", R"({"R_dr": 0.5, "l_d": 1.0, "model": 1.3})", 400, "model");
  expect("/api/lit_sphere", ok.dump(), 200, "");
  bad = ok;
  bad["radius"] = -1;
  expect("/api/lit_sphere", bad.dump(), 400, "radius");
  expect("/api/nothing", "{}", 404, "/api/nothing");
  const ApiResponse wrong_method = api().handle("GET", "/api/profiles", {}, "");
  EXPECT_EQ(wrong_method.status, 405);
}

TEST_F(ExploreApiTest, NoFileOutsideThePageOrTheOpenFoldersIsServed) {
  const ExploreApi explorer = api();
  const ApiResponse index = explorer.handle("GET", "/", {}, "");
  ASSERT_EQ(index.status, 200);
  EXPECT_EQ(index.file, fs::canonical(page_ / "index.html"));
  EXPECT_EQ(index.content_type, "text/html; charset=utf-8");
  EXPECT_EQ(explorer.handle("GET", "/explore.js", {}, "").status, 200);
  for (const std::string path : {"/../secret.txt", "/../../etc/passwd", "/./../secret.txt"}) {
    const ApiResponse response = explorer.handle("GET", path, {}, "");
    EXPECT_EQ(response.status, 403) << path;
    EXPECT_TRUE(response.file.empty()) << path;
  }
  EXPECT_EQ(explorer.handle("GET", "/missing.js", {}, "").status, 404);
  // A link inside the page's folder that leads out of it is refused too.
  fs::create_symlink(directory_ / "secret.txt", page_ / "link.txt");
  EXPECT_EQ(explorer.handle("GET", "/link.txt", {}, "").status, 403);
  EXPECT_FALSE(explorer.page_file("/link.txt"));
  // Files of the open folders: only through /api/file, only inside them.
  for (const std::string path : {"0/../secret.txt", "0/../../etc/passwd", "0//etc/passwd"}) {
    const ApiResponse response = explorer.handle("GET", "/api/file", {{"path", path}}, "");
    EXPECT_EQ(response.status, 403) << path << " " << response.body;
  }
  for (const std::string path : {"1/run.h5", "x/run.h5", "0", "0/none.h5", "-1/run.h5"}) {
    const ApiResponse response = explorer.handle("GET", "/api/file", {{"path", path}}, "");
    EXPECT_EQ(response.status, 400) << path << " " << response.body;
    EXPECT_NE(response.body.find("path"), std::string::npos);
  }
  EXPECT_EQ(explorer.handle("GET", "/api/file", {}, "").status, 400);
}

// A path or a query decoded to bytes that are not UTF-8 is refused as any other, in JSON: the
// message quoting them is not lost to an exception (tests/fuzz/corpus/explore_request/
// crash-path-not-utf8.txt).
TEST_F(ExploreApiTest, RequestsThatAreNotUtf8AreRefusedInJson) {
  const ExploreApi explorer = api();
  const auto expect = [](const ApiResponse& response, int status, const std::string& named) {
    EXPECT_EQ(response.status, status) << response.body;
    const json answer = json::parse(response.body);
    EXPECT_NE(answer["error"].get<std::string>().find(named), std::string::npos) << response.body;
  };
  expect(explorer.handle("GET", "/api/\xffile", {}, ""), 404, "no such API path");
  expect(explorer.handle("GET", "/\xfe.js", {}, ""), 404, "no such file of the page");
  expect(explorer.handle("GET", "/api/file", {{"path", "0/\xff.h5"}}, ""), 400, "path");
}

TEST_F(ExploreApiTest, FoldersThatAreNotThereAreRefusedByName) {
  const auto field_of = [](const ExploreOptions& options) {
    try {
      ExploreApi explorer(options);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of({directory_ / "none", {}, {}}), "page");
  EXPECT_EQ(field_of({page_, {directory_ / "none"}, {}}), "open");
  EXPECT_EQ(field_of({page_, {}, directory_ / "none"}), "models");
  EXPECT_EQ(field_of({page_, {open_}, models_}), "(accepted)");
}

TEST_F(ExploreApiTest, ASearchlightFileIsReadWithItsErrorBars) {
  HalfSpaceSpec spec;
  spec.run = RunSettings{2000, 4, 1, 1};
  spec.grid.r = UniformAxis{0.0, 5.0, 10};
  const TransportOutput out = run_half_space(spec);
  fs::create_directories(open_ / "runs");
  write_simulation_file(open_ / "runs/half.h5", spec, out.tallies, run_provenance(out, "test"));
  const ExploreApi explorer = api();
  const json files = body_of(explorer.handle("GET", "/api/files", {}, ""));
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0]["path"], "0/runs/half.h5");
  const ApiResponse response =
      explorer.handle("GET", "/api/file", {{"path", "0/runs/half.h5"}}, "");
  ASSERT_EQ(response.status, 200) << response.body;
  const json file = body_of(response);
  EXPECT_EQ(file["r"].size(), 10u);
  EXPECT_DOUBLE_EQ(file["r"][0].get<double>(), 0.25);
  const double t_in = file["entry_transmittance"];
  EXPECT_NEAR(t_in, 1.0 - std::pow(0.3 / 2.3, 2), 1e-15);
  bool found = false;
  for (const json& tally : file["tallies"]) {
    if (tally["name"] != "reflectance") continue;
    found = true;
    const TallyResult* written = nullptr;
    for (const TallyResult& t : out.tallies) {
      if (t.name == "reflectance") written = &t;
    }
    ASSERT_NE(written, nullptr);
    for (std::size_t i = 0; i < 10; ++i) {
      EXPECT_DOUBLE_EQ(tally["mean"][i].get<double>(), written->mean[i] / t_in);
      EXPECT_DOUBLE_EQ(tally["stderr"][i].get<double>(), written->stderr_of_mean[i] / t_in);
    }
  }
  EXPECT_TRUE(found);
}

TEST_F(ExploreApiTest, APathTracedLitSphereIsReadForTheLitSpherePanel) {
  LitObjectSpec spec;
  spec.radius = 2.0;
  spec.run = RunSettings{2000, 4, 1, 1};
  const TransportOutput out = run_lit_sphere(spec);
  fs::create_directories(open_ / "runs");
  write_simulation_file(open_ / "runs/sphere.h5", spec, out.tallies, run_provenance(out, "test"));
  const ExploreApi explorer = api();
  const ApiResponse response =
      explorer.handle("GET", "/api/file", {{"path", "0/runs/sphere.h5"}}, "");
  ASSERT_EQ(response.status, 200) << response.body;
  const json file = body_of(response);
  EXPECT_EQ(file["kind"], "lit_sphere");
  EXPECT_DOUBLE_EQ(file["radius"].get<double>(), 2.0);
  ASSERT_EQ(file["psi"].size(), 36u);
  EXPECT_DOUBLE_EQ(file["psi"][0].get<double>(), 0.5 * spec.psi.width());
  bool found = false;
  for (const json& tally : file["tallies"]) {
    if (tally["name"] != "exitance_multiple") continue;
    found = true;
    const TallyResult* written = find_tally(out.tallies, "exitance_multiple");
    ASSERT_NE(written, nullptr);
    for (std::size_t i = 0; i < 36; ++i) {
      EXPECT_EQ(tally["mean"][i].get<double>(), written->mean[i]);
      EXPECT_EQ(tally["stderr"][i].get<double>(), written->stderr_of_mean[i]);
    }
  }
  EXPECT_TRUE(found);

  // A beam's sphere is not azimuthally symmetric: the panel's curves are not for it.
  spec.light = ObjectLight::pole_beam;
  spec.azimuth = UniformAxis{0.0, 2.0 * std::numbers::pi, 4};
  const TransportOutput beam = run_lit_sphere(spec);
  write_simulation_file(open_ / "runs/beam.h5", spec, beam.tallies, run_provenance(beam, "test"));
  const ApiResponse refused = explorer.handle("GET", "/api/file", {{"path", "0/runs/beam.h5"}}, "");
  EXPECT_EQ(refused.status, 400);
  EXPECT_NE(refused.body.find("path"), std::string::npos) << refused.body;
}

TEST_F(ExploreApiTest, PresetsAndInversion) {
  const json libraries = body_of(api().handle("GET", "/api/presets", {}, ""));
  ASSERT_GE(libraries.size(), 2u);
  bool skin = false;
  for (const json& library : libraries) {
    for (const json& material : library["materials"]) {
      if (library["id"] == "jensen2001" && material["name"] == "skin1") {
        skin = true;
        EXPECT_EQ(material["sigma_a"].size(), 3u);
      }
    }
  }
  EXPECT_TRUE(skin);
  const ApiResponse response = post(
      "/api/invert", {{"model", "dipole"}, {"R_dr", 0.5}, {"l_d", 2.0}, {"eta", 1.3}, {"g", 0.5}});
  ASSERT_EQ(response.status, 200) << response.body;
  const json c = body_of(response);
  const InvertedCoefficients expected =
      invert_reflectance(HalfSpaceModel::classical_dipole, 0.5, 2.0, 1.3, 0.5);
  EXPECT_EQ(c["sigma_a"].get<double>(), expected.sigma_a);
  EXPECT_EQ(c["sigma_s"].get<double>(), expected.sigma_s);
  EXPECT_DOUBLE_EQ(c["sigma_s_reduced"].get<double>(), expected.sigma_s * 0.5);
}

TEST_F(ExploreApiTest, TheLitSphereCurvesAreTheModelsExitance) {
  const ApiResponse response = post("/api/lit_sphere", {{"medium", medium(0.01, 1.0, 0.0, 1.3)},
                                                        {"radius", 5.0},
                                                        {"bins", 12},
                                                        {"samples", 256},
                                                        {"models", {"better_dipole"}}});
  ASSERT_EQ(response.status, 200) << response.body;
  const json answer = body_of(response);
  HalfSpaceMedium m;
  m.sigma_a = 0.01;
  m.sigma_s = 1.0;
  m.eta = 1.3;
  const std::vector<double> edges = answer["psi_edges"].get<std::vector<double>>();
  const LitSphereExitance expected =
      lit_sphere_exitance(DiffusionProfile(ProfileModel::better_dipole, m), 5.0, edges, 256, 1);
  EXPECT_EQ(answer["curves"][0]["mean"].get<std::vector<double>>(), expected.mean);
}

TEST_F(ExploreApiTest, TheServerAnswersOnALoopbackPort) {
  const ExploreApi explorer = api();
  ExploreServer server(explorer, "127.0.0.1", 0);
  ASSERT_GT(server.port(), 0);
  std::thread serving([&] { server.run(); });
  httplib::Client client("127.0.0.1", server.port());
  client.set_connection_timeout(5);
  // Bound before run(): a connection waits in the backlog until the server accepts it.
  const auto info = client.Get("/api/info");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, 200);
  EXPECT_EQ(json::parse(info->body)["version"], SCATTERLAB_VERSION);
  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->body, "<html>the page</html>");
  const auto traversal = client.Get("/%2e%2e/secret.txt");
  ASSERT_TRUE(traversal);
  EXPECT_GE(traversal->status, 400);
  EXPECT_EQ(traversal->body.find("not to be served"), std::string::npos);
  const auto bad = client.Post("/api/profiles", "{", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(json::parse(bad->body)["error"].get<std::string>().find("body"), std::string::npos);
  // A second server on the same port is refused, naming the port.
  try {
    ExploreServer second(explorer, "127.0.0.1", server.port());
    ADD_FAILURE() << "a second server bound port " << server.port();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "port");
  }
  server.stop();
  serving.join();
}

#if SCATTERLAB_EXPLORE_MESH
// The BSSRDF on a mesh (explore/mesh_view.hpp): skim milk's coefficients per channel in mm (Jensen
// et al. 2001, Table 2) on meshes of a few mm, small clouds so that each request takes
// milliseconds.
json mesh_request(const json& mesh, double azimuth, double elevation, bool occlusion = true) {
  json media = json::array();
  const double sigma_a[] = {0.0014, 0.0025, 0.0142}, sigma_s[] = {0.70, 1.22, 1.90};
  for (int c = 0; c < 3; ++c) media.push_back(medium(sigma_a[c], sigma_s[c], 0.0, 1.3));
  return {{"mesh", mesh},           {"points", 512},
          {"media", media},         {"scale", 1.0},
          {"model", "dipole"},      {"light", {{"azimuth", azimuth}, {"elevation", elevation}}},
          {"occlusion", occlusion}, {"cluster_angle", 0.05}};
}

TEST_F(ExploreApiTest, MeshExitanceAtVerticesIsTheOctreeEvaluatedThere) {
  const json request = mesh_request({{"shape", "sphere"}}, 30.0, 40.0);
  const ApiResponse response = post("/api/mesh_exitance", request);
  ASSERT_EQ(response.status, 200) << response.body;
  const json answer = body_of(response);
  const std::size_t vertices = answer["mesh"]["vertices"];
  ASSERT_EQ(answer["mesh"]["positions"].size(), 3 * vertices);
  ASSERT_EQ(answer["mesh"]["normals"].size(), 3 * vertices);
  ASSERT_EQ(answer["exitance"].size(), 3 * vertices);
  EXPECT_EQ(answer["cloud"]["points"], 512);
  EXPECT_TRUE(answer["units"].contains("exitance"));
  EXPECT_GT(answer["ms"]["total"].get<double>(), 0.0);
  EXPECT_EQ(answer["exit_weight"]["weight"].size(), answer["exit_weight"]["cos_outside"].size());

  // The same steps by hand (point_cloud.hpp, point_octree.hpp): the sphere's edges are shorter
  // than the cloud's spacing, so the page's mesh is the sphere itself.
  const SceneMesh sphere = parse_scene_mesh("[mesh]\nshape = \"sphere\"\n", "test");
  ASSERT_EQ(sphere.mesh.positions.size(), vertices);
  PointCloudOptions options;
  options.points = 512;
  const PointCloud cloud = make_point_cloud(sphere.mesh, options);
  DirectionalLight light;
  const double a = 30.0 * std::numbers::pi / 180.0, e = 40.0 * std::numbers::pi / 180.0;
  light.to_light = Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
  const std::vector<double> irradiance =
      directional_irradiance(sphere.mesh, cloud, light, 1.3, true);
  const PointOctree octree = cloud_octree(cloud, irradiance);
  std::vector<DiffusionProfile> profiles;
  const double sigma_a[] = {0.0014, 0.0025, 0.0142}, sigma_s[] = {0.70, 1.22, 1.90};
  for (int c = 0; c < 3; ++c) {
    profiles.emplace_back(ProfileModel::dipole, HalfSpaceMedium{sigma_a[c], sigma_s[c], 0.0, 1.3});
  }
  const std::vector<RadialKernel> kernels =
      cloud_kernels(profiles, cloud.point_area, sphere.mesh.bounds());
  int lit = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    double m[3];
    OctreeQuery query;
    octree.exitance(sphere.mesh.positions[v], 0.05, kernels, m, query);
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_DOUBLE_EQ(answer["exitance"][3 * v + c].get<double>(), m[c]) << v << " " << c;
    }
    lit += m[0] > 0.0;
  }
  EXPECT_GT(lit, 0);
  // The second request for the same cloud finds it cached; the geometry can be left out.
  json again = request;
  again["geometry"] = false;
  ExploreApi explorer = api();
  explorer.handle("POST", "/api/mesh_exitance", {}, request.dump());
  const json second = body_of(explorer.handle("POST", "/api/mesh_exitance", {}, again.dump()));
  EXPECT_TRUE(second["cloud"]["cached"].get<bool>());
  EXPECT_FALSE(second["mesh"].contains("positions"));
  EXPECT_EQ(second["exitance"], answer["exitance"]);
}

TEST_F(ExploreApiTest, ATextModelRendersOnTheMeshAsItsBuiltInTwin) {
  // The dipole written as a text file (data/models/dipole_text.toml) gives, vertex by vertex, the
  // built-in dipole's exitance: the tables' nodes agree to the models' 1e-9, and the average over
  // one point's disc (closed form for the built-in, Gauss-Legendre for the text) to 1e-8.
  json request = mesh_request({{"shape", "sphere"}}, 30.0, 40.0);
  const json built_in = body_of(post("/api/mesh_exitance", request));
  request["model"] = "dipole_text";
  const ApiResponse response = post("/api/mesh_exitance", request);
  ASSERT_EQ(response.status, 200) << response.body;
  const json text = body_of(response);
  ASSERT_EQ(text["exitance"].size(), built_in["exitance"].size());
  double worst = 0.0;
  for (std::size_t k = 0; k < text["exitance"].size(); ++k) {
    const double a = text["exitance"][k], b = built_in["exitance"][k];
    if (b > 0.0) worst = std::max(worst, std::abs(a / b - 1.0));
  }
  EXPECT_LT(worst, 1e-7);
  request["model"] = "no_such_model";
  const ApiResponse refused = post("/api/mesh_exitance", request);
  EXPECT_EQ(refused.status, 400);
  EXPECT_NE(refused.body.find("dipole_text"), std::string::npos) << refused.body;
}

TEST_F(ExploreApiTest, MeshLitFromTheOppositeSideIsShadowedWithOcclusion) {
  // A bumpy sphere: its bumps shadow one another at a grazing light.
  const json mesh{{"shape", "bumpy_sphere"}, {"amplitude", 0.15}, {"frequency", 4}};
  const auto answer = [&](double azimuth, bool occlusion) {
    const ApiResponse response =
        post("/api/mesh_exitance", mesh_request(mesh, azimuth, 5.0, occlusion));
    EXPECT_EQ(response.status, 200) << response.body;
    return body_of(response);
  };
  const json east = answer(0.0, true), west = answer(180.0, true), open = answer(180.0, false);
  EXPECT_NE(east["exitance"], west["exitance"]);
  EXPECT_LT(west["cloud"]["lit_points"].get<int>(), open["cloud"]["lit_points"].get<int>());
  // Vertices facing +x are brighter lit from +x than from -x, and the other way round (skim
  // milk carries the light around a sphere of 1 mm: not ten times).
  const json& positions = east["mesh"]["positions"];
  double east_side[2] = {0, 0}, west_side[2] = {0, 0};
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    const double x = positions[3 * v];
    double* side = x > 0.5 ? east_side : x < -0.5 ? west_side : nullptr;
    if (side == nullptr) continue;
    side[0] += east["exitance"][3 * v].get<double>();
    side[1] += west["exitance"][3 * v].get<double>();
  }
  EXPECT_GT(east_side[0], 1.5 * east_side[1]);
  EXPECT_GT(west_side[1], 1.5 * west_side[0]);
}

TEST_F(ExploreApiTest, MeshFromAnObjFileOfAnOpenFolder) {
  // A unit cube, counter-clockwise seen from outside.
  write(open_ / "cube.obj",
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
        "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
  const json listed = body_of(api().handle("GET", "/api/meshes", {}, ""));
  ASSERT_EQ(listed["obj_files"].size(), 1u);
  EXPECT_EQ(listed["obj_files"][0]["path"], "0/cube.obj");
  const ApiResponse response = post(
      "/api/mesh_exitance", mesh_request({{"shape", "obj"}, {"path", "0/cube.obj"}}, 0.0, 30.0));
  ASSERT_EQ(response.status, 200) << response.body;
  const json answer = body_of(response);
  // Flat facets: the page's mesh splits them until its edges are below the points' spacing.
  EXPECT_GT(answer["mesh"]["triangles"].get<int>(), 12);
  EXPECT_EQ(answer["mesh"]["mesh_triangles"], 12);
}

// Every shape the page lists, sent as the page sends it (web/mesh_view.js: with its normals).
TEST_F(ExploreApiTest, EveryListedShapeIsAcceptedAsThePageSendsIt) {
  const json listed = body_of(api().handle("GET", "/api/meshes", {}, ""));
  ASSERT_FALSE(listed["shapes"].empty());
  for (const json& shape : listed["shapes"]) {
    for (const char* normals : {"interpolated", "flat"}) {
      const ApiResponse response = post(
          "/api/mesh_exitance", mesh_request({{"shape", shape}, {"normals", normals}}, 30.0, 40.0));
      EXPECT_EQ(response.status, 200) << shape << " " << normals << ": " << response.body;
    }
  }
}

TEST_F(ExploreApiTest, BadMeshRequestsNameTheirField) {
  write(directory_ / "outside.obj", "v 0 0 0\n");
  const auto refused = [&](json request, int status, const std::string& field) {
    const ApiResponse response = post("/api/mesh_exitance", request);
    EXPECT_EQ(response.status, status) << response.body;
    EXPECT_NE(body_of(response)["error"].get<std::string>().find(field), std::string::npos)
        << response.body;
  };
  const json good = mesh_request({{"shape", "sphere"}}, 0.0, 45.0);
  json bad = good;
  bad["mesh"]["shape"] = "teapot";
  refused(bad, 400, "mesh.shape");
  bad = good;
  bad["mesh"] = {{"shape", "obj"}, {"path", "0/../outside.obj"}};
  refused(bad, 403, "mesh.path");
  bad["mesh"]["path"] = "7/cube.obj";
  refused(bad, 400, "mesh.path");
  bad = good;
  bad["light"]["elevation"] = 120;
  refused(bad, 400, "light.elevation");
  bad = good;
  bad["light"]["azimuth"] = "east";
  refused(bad, 400, "light.azimuth");
  bad = good;
  bad["media"].erase(1);
  refused(bad, 400, "media");
  bad = good;
  bad["model"] = "measured";
  refused(bad, 400, "model");
  bad = good;
  bad["points"] = 3;
  refused(bad, 400, "points");
  bad = good;
  bad["mesh"]["radius"] = -1;
  refused(bad, 400, "mesh.radius");
  EXPECT_EQ(api().handle("GET", "/api/mesh_exitance", {}, "").status, 405);
}
#endif

}  // namespace
}  // namespace scatterlab

#pragma once
// A radial profile model written as a text file (Bitterli 2013, Appendix A.2: an analytic,
// radial BSSRDF described by a human-readable file that declares its parameters and defines its
// profile), here as TOML with the profile an expression that muparser evaluates:
//
//   name        = "dipole_text"              # letters, digits, '_'; unique in the folder
//   description = "..."                      # optional, shown in the legend's hover text
//   reference   = "Jensen et al. 2001, ..."  # optional: where the formula comes from
//   [[parameter]]                            # optional, any number: a slider of the page
//   name = "k"; min = 0.0; max = 2.0; default = 1.0
//   define = ["D = 1 / (3 * sigma_t_reduced)", "z_r = 1 / sigma_t_reduced", ...]  # in order
//   R_d = "alpha_reduced / (4 * pi) * (...)"   # the profile at distance r
//
// The expressions see the material of the channel being plotted (lengths in its unit, after the
// page's scale): sigma_a, sigma_s, g, eta; the derived sigma_t, albedo, sigma_s_reduced
// (sigma_s (1 - g)), sigma_t_reduced, alpha_reduced (Bitterli eqs. 2.23-2.24); the boundary terms
// of models/boundary_reflection.hpp, F_dr, C_1, C_2 (the project's fits, so that a text model
// uses the same ones as the built-in models); pi; r; every parameter; and each name defined
// earlier in `define`. muparser's functions (sqrt, exp, ...) and operators (^, ?:) apply.
//
// A bad file is one InputError whose field is "<file>:<line>: <key>" and that says what is
// accepted (unknown keys, a missing R_d, a parameter whose default lies outside [min, max], an
// expression muparser rejects, naming the position in it).

#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct TextModelParameter {
  std::string name;
  double min = 0.0, max = 1.0, default_value = 0.0;
};

class TextModel {
 public:
  // `origin` names the text in errors (the file's name).
  static TextModel parse(std::string_view toml_text, const std::string& origin);
  static TextModel load(const std::filesystem::path& path);

  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  const std::string& reference() const { return reference_; }
  const std::string& origin() const { return origin_; }
  const std::vector<TextModelParameter>& parameters() const { return parameters_; }

  // R_d at each r for `medium` (validated first), the parameters by name (unset ones take their
  // default; a value outside [min, max] or an unknown name is an InputError naming
  // "parameters.<name>"). A value that is not finite is returned as it is (the page draws a gap).
  std::vector<double> reflectance(const HalfSpaceMedium& medium,
                                  const std::map<std::string, double>& parameter_values,
                                  std::span<const double> r) const;

 private:
  std::string name_, description_, reference_, origin_;
  std::vector<TextModelParameter> parameters_;
  struct Line {
    std::string name;  // empty for R_d
    std::string expression;
    int line = 0;
  };
  std::vector<Line> definitions_;  // in order
  Line profile_;
};

// Every *.toml file of `folder`, in name order; a bad file or two files with the same name is an
// InputError (TextModel::parse's).
std::vector<TextModel> load_text_models(const std::filesystem::path& folder);

}  // namespace scatterlab

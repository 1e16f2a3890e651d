#include "scatterlab/explore/text_model.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <regex>
#include <set>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/text_file.hpp"
#include "scatterlab/io/toml_reader.hpp"
#include "scatterlab/models/boundary_reflection.hpp"

namespace scatterlab {
namespace {

using toml_reading::TomlReader;

// The material's quantities every expression sees, in this order (text_model.hpp).
constexpr std::string_view kMaterialNames[] = {"r",
                                               "sigma_a",
                                               "sigma_s",
                                               "g",
                                               "eta",
                                               "sigma_t",
                                               "albedo",
                                               "sigma_s_reduced",
                                               "sigma_t_reduced",
                                               "alpha_reduced",
                                               "F_dr",
                                               "C_1",
                                               "C_2",
                                               "pi"};
constexpr std::size_t kMaterialCount = std::size(kMaterialNames);

const std::regex& identifier() {
  static const std::regex pattern("[A-Za-z_][A-Za-z0-9_]*");
  return pattern;
}

// The values of kMaterialNames for one medium (r left at 0).
std::vector<double> material_values(const HalfSpaceMedium& m) {
  // Similarity relations (Bitterli 2013 eqs. 2.23-2.24): sigma_s' = sigma_s (1 - g),
  // sigma_t' = sigma_a + sigma_s', alpha' = sigma_s' / sigma_t'.
  return {0.0,
          m.sigma_a,
          m.sigma_s,
          m.g,
          m.eta,
          m.sigma_t(),
          m.sigma_t() > 0.0 ? m.sigma_s / m.sigma_t() : 0.0,
          m.reduced_sigma_s(),
          m.reduced_sigma_t(),
          m.reduced_albedo(),
          diffuse_fresnel_reflectance(m.eta),
          fresnel_moment1(m.eta),
          fresnel_moment2(m.eta),
          std::numbers::pi};
}

// Parsers over one set of variables: the material's, the parameters', and the definitions'.
class Evaluator {
 public:
  Evaluator(const std::vector<std::string>& names, std::size_t expressions)
      : names_(names), values_(names.size(), 0.0), parsers_(expressions) {
    for (mu::Parser& parser : parsers_) {
      for (std::size_t i = 0; i < names_.size(); ++i) parser.DefineVar(names_[i], &values_[i]);
    }
  }
  double& value(std::size_t i) { return values_[i]; }
  mu::Parser& parser(std::size_t i) { return parsers_[i]; }

 private:
  std::vector<std::string> names_;
  std::vector<double> values_;  // never resized: the parsers hold pointers into it
  std::vector<mu::Parser> parsers_;
};

}  // namespace

TextModel TextModel::parse(std::string_view toml_text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& error) {
    const auto& begin = error.source().begin;
    throw InputError(fmt::format("{}:{}", origin, begin.line),
                     fmt::format("not TOML: {}", error.description()),
                     "a TOML file (docs/guide/explorer.md: the model file format)");
  }
  const TomlReader reader(origin);
  const auto where = [&](const toml::node* node, std::string_view key) {
    const int line = node != nullptr ? static_cast<int>(node->source().begin.line) : 1;
    return fmt::format("{}:{}: {}", origin, line, key);
  };
  // Keys first, so that a misspelt key is named before anything it would have set.
  for (auto&& [key, node] : root) {
    static const std::set<std::string_view> accepted{"name",      "description", "reference",
                                                     "parameter", "define",      "R_d"};
    if (!accepted.contains(key.str())) {
      throw InputError(where(&node, key.str()), "unknown key",
                       "name, description, reference, [[parameter]], define, R_d");
    }
  }
  TextModel model;
  model.origin_ = origin;
  const auto text = [&](std::string_view key, bool required) -> std::string {
    const toml::node* node = root.get(key);
    if (node == nullptr) {
      if (required) throw InputError(where(nullptr, key), "missing", "a string");
      return "";
    }
    if (!node->is_string()) throw InputError(where(node, key), "not a string", "a string");
    return node->as_string()->get();
  };
  model.name_ = text("name", true);
  if (!std::regex_match(model.name_, identifier())) {
    throw InputError(where(root.get("name"), "name"), fmt::format("got \"{}\"", model.name_),
                     "letters, digits and '_', not starting with a digit");
  }
  model.description_ = text("description", false);
  model.reference_ = text("reference", false);

  std::set<std::string> taken(std::begin(kMaterialNames), std::end(kMaterialNames));
  const auto take = [&](const std::string& name, const toml::node* node, std::string_view key) {
    if (!std::regex_match(name, identifier())) {
      throw InputError(where(node, key), fmt::format("got \"{}\"", name),
                       "a name of letters, digits and '_', not starting with a digit");
    }
    if (!taken.insert(name).second) {
      throw InputError(where(node, key), fmt::format("\"{}\" is already defined", name),
                       "a name that no material quantity, parameter or earlier definition has");
    }
    // muparser refuses some names of the pattern above (longer than its limit, or one of its
    // constants, _pi and _e): asked here, so that the refusal names the file and the line.
    try {
      double value = 0.0;
      mu::Parser().DefineVar(name, &value);
    } catch (const mu::Parser::exception_type& error) {
      throw InputError(where(node, key), fmt::format("got \"{}\": {}", name, error.GetMsg()),
                       fmt::format("a name of at most {} characters that is not one of "
                                   "muparser's constants (_pi, _e)",
                                   mu::MaxLenIdentifier));
    }
  };

  if (const toml::node* list = root.get("parameter")) {
    const toml::array* parameters = list->as_array();
    if (parameters == nullptr || !parameters->is_array_of_tables()) {
      throw InputError(where(list, "parameter"), "not an array of tables",
                       "[[parameter]] tables with name, min, max, default");
    }
    for (const toml::node& node : *parameters) {
      const toml::table& table = *node.as_table();
      for (auto&& [key, value] : table) {
        if (key.str() != "name" && key.str() != "min" && key.str() != "max" &&
            key.str() != "default") {
          const bool top = key.str() == "define" || key.str() == "R_d" ||
                           key.str() == "description" || key.str() == "reference";
          throw InputError(where(&value, "parameter." + std::string(key.str())),
                           top ? "unknown key (TOML reads every key after a [[parameter]] line "
                                 "into that parameter: write name, description, reference, "
                                 "define and R_d before the first [[parameter]])"
                               : "unknown key",
                           "name, min, max, default");
        }
      }
      TextModelParameter parameter;
      const toml::node* name = table.get("name");
      if (name == nullptr || !name->is_string()) {
        throw InputError(where(&node, "parameter.name"), "missing or not a string", "a name");
      }
      parameter.name = name->as_string()->get();
      take(parameter.name, name, "parameter.name");
      const std::string path = "parameter." + parameter.name;
      const auto number = [&](std::string_view key) {
        const toml::node* value = table.get(key);
        const auto got = reader.number(table, key, path, "a finite number");
        if (!got || !std::isfinite(*got)) {
          throw InputError(where(value != nullptr ? value : &node, path + "." + std::string(key)),
                           got ? "not finite" : "missing", "a finite number");
        }
        return *got;
      };
      parameter.min = number("min");
      parameter.max = number("max");
      parameter.default_value = number("default");
      if (!(parameter.min < parameter.max) || parameter.default_value < parameter.min ||
          parameter.default_value > parameter.max) {
        throw InputError(where(&node, path),
                         fmt::format("min {}, max {}, default {}", parameter.min, parameter.max,
                                     parameter.default_value),
                         "min < max and min <= default <= max");
      }
      model.parameters_.push_back(parameter);
    }
  }

  if (const toml::node* list = root.get("define")) {
    const toml::array* definitions = list->as_array();
    if (definitions == nullptr) {
      throw InputError(where(list, "define"), "not an array", "an array of \"name = expression\"");
    }
    static const std::regex assignment(R"(\s*([A-Za-z_][A-Za-z0-9_]*)\s*=(?!=)(.*))");
    for (const toml::node& node : *definitions) {
      std::smatch match;
      const std::string* line = node.is_string() ? &node.as_string()->get() : nullptr;
      if (line == nullptr || !std::regex_match(*line, match, assignment)) {
        throw InputError(where(&node, "define"), "not \"name = expression\"",
                         "strings such as \"D = 1 / (3 * sigma_t_reduced)\"");
      }
      take(match[1].str(), &node, "define");
      model.definitions_.push_back(
          {match[1].str(), match[2].str(), static_cast<int>(node.source().begin.line)});
    }
  }

  const toml::node* profile = root.get("R_d");
  if (profile == nullptr || !profile->is_string()) {
    throw InputError(where(profile, "R_d"), profile == nullptr ? "missing" : "not a string",
                     "an expression in r and the material's quantities");
  }
  model.profile_ = {"", profile->as_string()->get(),
                    static_cast<int>(profile->source().begin.line)};

  // Every expression compiled once here, on a plausible material, so that a syntax error or an
  // unknown name is reported when the file is loaded, not when it is first plotted.
  HalfSpaceMedium probe;
  probe.sigma_a = 0.1;
  probe.sigma_s = 1.0;
  probe.eta = 1.3;
  std::map<std::string, double> defaults;
  const std::vector<double> r{1.0};
  (void)model.reflectance(probe, defaults, r);
  return model;
}

TextModel TextModel::load(const std::filesystem::path& path) {
  const std::string text = read_scene_file(path, path.filename().string());
  return parse(text, path.filename().string());
}

std::vector<double> TextModel::reflectance(const HalfSpaceMedium& medium,
                                           const std::map<std::string, double>& parameter_values,
                                           std::span<const double> r) const {
  medium.validate();
  for (const auto& [name, value] : parameter_values) {
    // Captured under a name of its own: clang 14 cannot capture a structured binding.
    const auto known = std::find_if(parameters_.begin(), parameters_.end(),
                                    [&wanted = name](const auto& p) { return p.name == wanted; });
    if (known == parameters_.end()) {
      std::string names;
      for (const auto& p : parameters_) names += (names.empty() ? "" : ", ") + p.name;
      throw InputError("parameters." + name, "not a parameter of " + name_,
                       names.empty() ? "none: this model has no parameters" : names);
    }
    if (!(value >= known->min && value <= known->max)) {
      throw InputError("parameters." + name, fmt::format("got {}", value),
                       fmt::format("a number in [{}, {}]", known->min, known->max));
    }
  }
  std::vector<std::string> names(std::begin(kMaterialNames), std::end(kMaterialNames));
  for (const auto& p : parameters_) names.push_back(p.name);
  for (const auto& d : definitions_) names.push_back(d.name);
  Evaluator evaluator(names, definitions_.size() + 1);

  const std::vector<double> material = material_values(medium);
  for (std::size_t i = 0; i < kMaterialCount; ++i) evaluator.value(i) = material[i];
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    const auto set = parameter_values.find(parameters_[i].name);
    evaluator.value(kMaterialCount + i) =
        set != parameter_values.end() ? set->second : parameters_[i].default_value;
  }
  const std::size_t first_definition = kMaterialCount + parameters_.size();
  const auto compile = [&](std::size_t i, const Line& line) {
    try {
      evaluator.parser(i).SetExpr(line.expression);
    } catch (const mu::Parser::exception_type& error) {
      throw InputError(fmt::format("{}:{}: {}", origin_, line.line,
                                   line.name.empty() ? "R_d" : "define " + line.name),
                       error.GetMsg(), "a muparser expression (docs/guide/explorer.md)");
    }
  };
  for (std::size_t i = 0; i < definitions_.size(); ++i) compile(i, definitions_[i]);
  compile(definitions_.size(), profile_);

  std::vector<double> values(r.size());
  for (std::size_t k = 0; k < r.size(); ++k) {
    evaluator.value(0) = r[k];
    std::size_t i = 0;
    try {
      for (; i < definitions_.size(); ++i) {
        evaluator.value(first_definition + i) = evaluator.parser(i).Eval();
      }
      values[k] = evaluator.parser(i).Eval();
    } catch (const mu::Parser::exception_type& error) {
      const Line& line = i < definitions_.size() ? definitions_[i] : profile_;
      throw InputError(
          fmt::format("{}:{}: {}", origin_, line.line,
                      line.name.empty() ? "R_d" : "define " + line.name),
          fmt::format("{} (at position {} of \"{}\")", error.GetMsg(), error.GetPos(),
                      line.expression),
          "a muparser expression in r, the material's quantities, the parameters and earlier "
          "definitions");
    }
  }
  return values;
}

std::vector<TextModel> load_text_models(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw InputError("models", fmt::format("{} is not a folder", folder.string()),
                     "a folder of model files (*.toml)");
  }
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".toml") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<TextModel> models;
  for (const auto& file : files) {
    TextModel model = TextModel::load(file);
    for (const TextModel& other : models) {
      if (other.name() == model.name()) {
        throw InputError(model.origin() + ": name",
                         fmt::format("\"{}\" is also the name in {}", model.name(), other.origin()),
                         "one model per name in the folder");
      }
    }
    models.push_back(std::move(model));
  }
  return models;
}

}  // namespace scatterlab

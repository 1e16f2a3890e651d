#include "scatterlab/fit/lobe_model.hpp"

#include <cmath>

#include "scatterlab/core/error.hpp"

namespace scatterlab::fit {

namespace {
constexpr const char* kAccepted =
    "a comma-separated list of sg, sg_free, dexp_paper, dexp, adexp, asg, adexp_ridge, "
    "adexp2_ridge";
}

std::string to_string(LobeModel model) {
  switch (model) {
    case LobeModel::sg:
      return "sg";
    case LobeModel::sg_free:
      return "sg_free";
    case LobeModel::dexp_paper:
      return "dexp_paper";
    case LobeModel::dexp:
      return "dexp";
    case LobeModel::adexp:
      return "adexp";
    case LobeModel::asg:
      return "asg";
    case LobeModel::adexp_ridge:
      return "adexp_ridge";
    case LobeModel::adexp2_ridge:
      return "adexp2_ridge";
  }
  return "unknown";
}

LobeModel parse_lobe_model(const std::string& name) {
  for (const LobeModel model : kAllLobeModels) {
    if (to_string(model) == name) return model;
  }
  throw InputError("models", "unknown model '" + name + "'", kAccepted);
}

std::vector<LobeModel> parse_lobe_models(const std::string& list) {
  std::vector<LobeModel> models;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const LobeModel model = parse_lobe_model(list.substr(start, end - start));
    for (const LobeModel seen : models) {
      if (seen == model) throw InputError("models", "'" + to_string(model) + "' twice", kAccepted);
    }
    models.push_back(model);
    start = end + 1;
  }
  return models;
}

std::string describe(LobeModel model) {
  switch (model) {
    case LobeModel::sg:
      return "spherical Gaussian mu exp(lambda (v.p - 1)), p = E/|E| fixed (Vavassori 4.2.1)";
    case LobeModel::sg_free:
      return "spherical Gaussian mu exp(lambda (v.p - 1)), p free on the sphere (Vavassori 4.2.1)";
    case LobeModel::dexp_paper:
      return "double exponential alpha exp(beta exp(gamma sqrt(1 - p.w))) from the four-step "
             "estimate, not solved (Vavassori 4.2.2)";
    case LobeModel::dexp:
      return "double exponential alpha exp(beta exp(gamma sqrt(1 - p.w))) (Vavassori 4.2.2)";
    case LobeModel::adexp:
      return "anisotropic double exponential alpha exp(beta exp(gamma s_eta)), s_eta^2 = "
             "(e^eta (w.t1)^2 + e^-eta (w.t2)^2 + (1 - w.p)^2) / 2, t1 in the phi = 0 plane";
    case LobeModel::asg:
      return "anisotropic spherical Gaussian c max(v.p, 0) exp(-lambda (v.t1)^2 - mu (v.t2)^2), "
             "t1 in the phi = 0 plane (Xu et al. 2013)";
    case LobeModel::adexp_ridge:
      return "adexp plus the ridge of once-scattered light on phi = 0, density across it "
             "c e^a (1 - g^2) / (1 + g^2 - 2 g cos theta)^1.5 e^(-k tan(theta/2)) / "
             "(1 + e^(-(theta - theta_on) / w)), and its spread in phi, spread_c e^a R e^(kappa "
             "(cos phi - 1))";
    case LobeModel::adexp2_ridge:
      return "adexp_ridge plus a second anisotropic double exponential of its own axis and "
             "shape (second_*)";
  }
  return "";
}

int free_parameters(LobeModel model) {
  switch (model) {
    case LobeModel::sg:
      return 2;
    case LobeModel::sg_free:
      return 4;
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
      return 5;
    case LobeModel::adexp:
      return 6;
    case LobeModel::asg:
      return 5;
    case LobeModel::adexp_ridge:
      return 11;
    case LobeModel::adexp2_ridge:
      return 17;
  }
  return 0;
}

std::vector<std::string> parameter_names(LobeModel model) {
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      return {"lambda", "mu", "p_r", "p_phi", "p_z"};
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
      return {"alpha", "beta", "gamma", "log_peak", "slope", "p_r", "p_phi", "p_z"};
    case LobeModel::adexp:
      return {"alpha", "beta", "gamma", "eta", "log_peak", "slope", "p_r", "p_phi", "p_z"};
    case LobeModel::asg:
      return {"c", "lambda", "mu", "p_r", "p_phi", "p_z"};
    case LobeModel::adexp_ridge:
      return {"alpha",       "beta",    "gamma",          "eta",         "log_peak",
              "slope",       "p_r",     "p_phi",          "p_z",         "ridge_c",
              "ridge_g",     "ridge_k", "ridge_theta_on", "ridge_width", "spread_c",
              "spread_kappa"};
    case LobeModel::adexp2_ridge: {
      std::vector<std::string> names = parameter_names(LobeModel::adexp_ridge);
      for (const std::string& name : parameter_names(LobeModel::adexp)) {
        names.push_back("second_" + name);
      }
      return names;
    }
  }
  return {};
}

std::vector<double> reported_parameters(LobeModel model, const LobeParameters& parameters) {
  const auto& s = parameters.shape;
  // beta = b / gamma, log alpha = a - beta: infinite for gamma = 0 (the writers store 0 then).
  const double beta = s[1] / s[2], alpha = std::exp(s[0] - beta);
  std::vector<double> values;
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      values = {s[0], std::exp(s[1])};
      break;
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
      values = {alpha, beta, s[2], s[0], s[1]};
      break;
    case LobeModel::adexp:
    case LobeModel::adexp_ridge:
    case LobeModel::adexp2_ridge:
      values = {alpha, beta, s[2], s[3], s[0], s[1]};
      break;
    case LobeModel::asg:
      values = {std::exp(s[0]), s[1], s[2]};
      break;
  }
  if (model == LobeModel::adexp2_ridge) {
    values = reported_parameters(LobeModel::adexp_ridge, parameters);
    LobeParameters second;
    second.axis = parameters.second_axis;
    second.shape = parameters.second_shape;
    const std::vector<double> more = reported_parameters(LobeModel::adexp, second);
    values.insert(values.end(), more.begin(), more.end());
    return values;
  }
  for (int i = 0; i < 3; ++i) values.push_back(parameters.axis[i]);
  if (model == LobeModel::adexp_ridge) {
    values.insert(values.end(), parameters.ridge.begin(), parameters.ridge.end());
  }
  return values;
}

std::array<double, 4> double_exponential_shape(double log_alpha, double beta, double gamma,
                                               double eta) {
  return {log_alpha + beta, beta * gamma, gamma, eta};
}

double log_model_value(LobeModel model, const LobeParameters& parameters,
                       const Eigen::Vector3d& direction) {
  const double* axis = parameters.axis.data();
  const double* shape = parameters.shape.data();
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      return SphericalGaussian::log_value(axis, shape, direction);
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
      return DoubleExponential::log_value(axis, shape, direction);
    case LobeModel::adexp:
    case LobeModel::adexp_ridge:
      return AnisotropicDoubleExponential::log_value(axis, shape, direction);
    case LobeModel::asg:
      return AnisotropicSphericalGaussian::log_value(axis, shape, direction);
    case LobeModel::adexp2_ridge: {
      const double one = AnisotropicDoubleExponential::log_value(axis, shape, direction);
      const double two = AnisotropicDoubleExponential::log_value(
          parameters.second_axis.data(), parameters.second_shape.data(), direction);
      return detail::log_add_exp(one, two);
    }
  }
  return 0.0;
}

}  // namespace scatterlab::fit

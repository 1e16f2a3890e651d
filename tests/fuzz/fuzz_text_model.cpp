// The explorer's text models (explore/text_model.hpp): a model file's text parsed (every
// expression compiled by muparser and evaluated once), then its profile evaluated as the page asks
// for it, on media of the kinds the page sends and at the parameters' bounds.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "scatterlab/explore/text_model.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scatterlab::fuzz::limit_memory();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace scatterlab;
  fuzz::expect_clean([&] {
    const TextModel model = TextModel::parse(fuzz::text_of(data, size), "fuzz.toml");
    const std::vector<double> r = {1e-6, 0.5, 3.0, 1e3};
    HalfSpaceMedium thin;  // no absorption, forward scattering, matched index
    thin.sigma_a = 0.0;
    thin.sigma_s = 0.2;
    thin.g = 0.9;
    thin.eta = 1.0;
    HalfSpaceMedium dense;
    dense.sigma_a = 2.0;
    dense.sigma_s = 50.0;
    dense.g = -0.3;
    dense.eta = 1.5;
    std::map<std::string, double> lowest, highest;
    for (const TextModelParameter& p : model.parameters()) {
      lowest[p.name] = p.min;
      highest[p.name] = p.max;
    }
    for (const HalfSpaceMedium& medium : {thin, dense}) {
      (void)model.reflectance(medium, {}, r);
      (void)model.reflectance(medium, lowest, r);
      (void)model.reflectance(medium, highest, r);
    }
  });
  return 0;
}

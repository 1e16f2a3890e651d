// MCML input files (.mci) as `scatterlab mcml` reads them: every run parsed, then each as the
// layered slab's spec, validated and its memory checked as before a run (io/mcml_input.hpp).

#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scatterlab/io/mcml_input.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/layered_slab.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scatterlab::fuzz::limit_memory();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace scatterlab;
  fuzz::expect_clean([&] {
    for (const McmlRun& run : parse_mcml_input(fuzz::text_of(data, size), "fuzz.mci")) {
      const LayeredSlabSpec spec = layered_slab_spec(run);
      spec.validate();
      check_transport_memory(transport_problem(spec), /*ranks=*/1, /*resuming=*/false);
    }
  });
  return 0;
}

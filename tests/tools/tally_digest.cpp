// Usage: tally_digest FILE.h5
// Prints one line per tally, "<name> <digest>", where the digest is a 64-bit FNV-1a hash of the
// shape and the bytes of its mean and stderr. Two files print the same lines exactly when their
// tallies are the same bit for bit; tests/bitwise keeps the lines of reference runs.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <exception>
#include <string>
#include <string_view>

#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace {

std::string_view bytes_of(const scatterlab::hdf5::Array& a) {
  return {reinterpret_cast<const char*>(a.values.data()), a.values.size() * sizeof(double)};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    fmt::print(stderr, "usage: tally_digest FILE.h5\n");
    return 2;
  }
  try {
    const auto file = scatterlab::hdf5::File::open_read_only(argv[1]);
    const auto tallies = file.root().open_group("tallies");
    for (const std::string& name : tallies.member_names()) {
      const auto mean = tallies.read_dataset(name + "/mean");
      const auto error = tallies.read_dataset(name + "/stderr");
      std::string canonical = fmt::format("{}|", fmt::join(mean.shape, ","));
      canonical += bytes_of(mean);
      canonical += bytes_of(error);
      fmt::print("{} {}\n", name, scatterlab::fingerprint_of(canonical));
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "tally_digest: {}\n", e.what());
    return 2;
  }
  return 0;
}

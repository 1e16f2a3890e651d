// Usage: same_tallies A.h5 B.h5 [C.h5 ...]
// Exits 0 when every file has the same tallies as A, bit for bit (mean and stderr of each), and
// 1 naming the first difference otherwise. Tests use it to check reproducibility across thread
// and rank counts and across a kill and --resume.
#include <fmt/format.h>

#include <cstring>
#include <exception>
#include <string>

#include "scatterlab/io/hdf5_file.hpp"

namespace {

bool bitwise_equal(const scatterlab::hdf5::Array& a, const scatterlab::hdf5::Array& b) {
  return a.shape == b.shape && a.values.size() == b.values.size() &&
         std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(double)) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  using scatterlab::hdf5::File;
  if (argc < 3) {
    fmt::print(stderr, "usage: same_tallies A.h5 B.h5 [C.h5 ...]\n");
    return 2;
  }
  try {
    const File reference = File::open_read_only(argv[1]);
    const auto reference_tallies = reference.root().open_group("tallies");
    const auto names = reference_tallies.member_names();
    for (int i = 2; i < argc; ++i) {
      const File other = File::open_read_only(argv[i]);
      const auto tallies = other.root().open_group("tallies");
      if (tallies.member_names() != names) {
        fmt::print("{} and {} hold different tallies\n", argv[1], argv[i]);
        return 1;
      }
      for (const std::string& name : names) {
        for (const char* dataset : {"mean", "stderr"}) {
          const std::string path = name + "/" + dataset;
          if (!bitwise_equal(reference_tallies.read_dataset(path), tallies.read_dataset(path))) {
            fmt::print("{} and {} differ in tallies/{}\n", argv[1], argv[i], path);
            return 1;
          }
        }
      }
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "same_tallies: {}\n", e.what());
    return 2;
  }
  fmt::print("same tallies, bit for bit, in {} files\n", argc - 1);
  return 0;
}

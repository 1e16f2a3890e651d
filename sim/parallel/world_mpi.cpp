// The world of a build with MPI: every collective the batch runner needs, over MPI_COMM_WORLD.
#include <mpi.h>

#include <climits>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "launcher.hpp"
#include "scatterlab/parallel/world.hpp"

namespace scatterlab {
namespace {

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// MPI counts and displacements are int: a run whose per-rank messages exceed 2^31 doubles
// (a 16 GiB slice) must use more ranks.
std::vector<int> as_int(const std::vector<std::size_t>& counts) {
  std::vector<int> result;
  for (const std::size_t count : counts) {
    if (count > static_cast<std::size_t>(INT_MAX)) {
      throw std::runtime_error("MPI: a message of " + std::to_string(count) +
                               " values exceeds the 2^31 MPI allows; use more ranks");
    }
    result.push_back(static_cast<int>(count));
  }
  return result;
}

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> offsets(counts.size(), 0);
  long long offset = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (offset > INT_MAX) throw std::runtime_error("MPI: displacement exceeds 2^31 values");
    offsets[i] = static_cast<int>(offset);
    offset += counts[i];
  }
  return offsets;
}

class MpiCommunicator final : public Communicator {
 public:
  MpiCommunicator() {
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void all_to_all(std::span<const double> send, const std::vector<std::size_t>& send_counts,
                  std::span<double> receive,
                  const std::vector<std::size_t>& receive_counts) override {
    const std::vector<int> sc = as_int(send_counts), rc = as_int(receive_counts);
    const std::vector<int> sd = displacements(sc), rd = displacements(rc);
    check(MPI_Alltoallv(send.data(), sc.data(), sd.data(), MPI_DOUBLE, receive.data(), rc.data(),
                        rd.data(), MPI_DOUBLE, MPI_COMM_WORLD),
          "MPI_Alltoallv");
  }

  std::vector<double> gather_to_root(std::span<const double> local,
                                     const std::vector<std::size_t>& counts) override {
    const std::vector<int> c = as_int(counts), d = displacements(c);
    std::vector<double> all;
    if (is_root()) all.resize(static_cast<std::size_t>(d.back()) + counts.back());
    check(MPI_Gatherv(local.data(), static_cast<int>(local.size()), MPI_DOUBLE, all.data(),
                      c.data(), d.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD),
          "MPI_Gatherv");
    return all;
  }

  std::vector<double> scatter_from_root(std::span<const double> full,
                                        const std::vector<std::size_t>& counts) override {
    const std::vector<int> c = as_int(counts), d = displacements(c);
    std::vector<double> part(counts[static_cast<std::size_t>(rank_)]);
    check(MPI_Scatterv(full.data(), c.data(), d.data(), MPI_DOUBLE, part.data(),
                       static_cast<int>(part.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD),
          "MPI_Scatterv");
    return part;
  }

  std::uint64_t sum(std::uint64_t value) override { return reduce(value, MPI_SUM); }
  std::uint64_t bitwise_or(std::uint64_t value) override { return reduce(value, MPI_BOR); }
  std::uint64_t broadcast_from_root(std::uint64_t value) override {
    check(MPI_Bcast(&value, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
    return value;
  }

 private:
  std::uint64_t reduce(std::uint64_t value, MPI_Op op) {
    std::uint64_t result = 0;
    check(MPI_Allreduce(&value, &result, 1, MPI_UINT64_T, op, MPI_COMM_WORLD), "MPI_Allreduce");
    return result;
  }

  int rank_ = 0;
  int size_ = 1;
};

bool mpi_initialised() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  return initialised != 0;
}

}  // namespace

World::World(int& argc, char**& argv) {
  if (detail::launched_ranks() == 0) {
    communicator_ = std::make_unique<SerialCommunicator>();
    return;
  }
  // The batch runner's collectives are made by whichever thread folds the next group of batches,
  // one thread at a time.
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw std::runtime_error(
        "MPI: this MPI library cannot be called from several threads, one at a time "
        "(MPI_THREAD_SERIALIZED)");
  }
  communicator_ = std::make_unique<MpiCommunicator>();
}

World::~World() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (mpi_initialised() && !finalised) MPI_Finalize();
}

void World::abort(int exit_code) {
  if (mpi_initialised()) MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::exit(exit_code);
}

bool World::built_with_mpi() {
  return true;
}

}  // namespace scatterlab

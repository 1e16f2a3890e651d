// The world of a build without MPI: this process alone.
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "launcher.hpp"
#include "scatterlab/parallel/world.hpp"

namespace scatterlab {

World::World(int&, char**&) : communicator_(std::make_unique<SerialCommunicator>()) {
  const int ranks = detail::launched_ranks();
  if (ranks > 1) {
    throw std::runtime_error(
        "started as " + std::to_string(ranks) +
        " MPI ranks, but this scatterlab was built without MPI: each rank would run the whole "
        "job; rebuild with libopenmpi-dev installed (SCATTERLAB_WITH_MPI=ON) or run one process");
  }
}

World::~World() = default;

void World::abort(int exit_code) {
  std::exit(exit_code);
}

bool World::built_with_mpi() {
  return false;
}

}  // namespace scatterlab

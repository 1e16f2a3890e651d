#pragma once
// The processes of this run. Started by mpirun (or another MPI launcher) in a build with MPI, the
// world spans every rank; otherwise it is this process alone, and MPI is never initialised, so
// that a plain run pays nothing for it. The one place that knows about MPI: the batch runner
// only sees the Communicator.

#include <memory>

#include "scatterlab/transport/communicator.hpp"

namespace scatterlab {

class World {
 public:
  // Initialises MPI when launched by an MPI launcher. Throws std::runtime_error when launched as
  // several ranks by a build without MPI (each would run the whole job alone), and InputError
  // naming the variable when a launcher's rank count is set without a launcher (a stray
  // OMPI_COMM_WORLD_SIZE, say), in either build.
  World(int& argc, char**& argv);
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  ~World();  // finalises MPI when it was initialised

  Communicator& communicator() { return *communicator_; }
  bool is_root() const { return communicator_->is_root(); }
  int size() const { return communicator_->size(); }

  // Ends every rank after an unrecoverable error on one (the others may be waiting on it).
  [[noreturn]] void abort(int exit_code);

  static bool built_with_mpi();

 private:
  std::unique_ptr<Communicator> communicator_;
};

}  // namespace scatterlab

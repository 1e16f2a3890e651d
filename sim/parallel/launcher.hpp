#pragma once
// How many ranks the launcher started, from the environment it sets (Open MPI, MPICH/PMI, PMIx);
// 0 when the process was not started by an MPI launcher.
//
// A launcher sets a rank count and also the address of the server its ranks connect to
// (PMIX_SERVER_URI*; PMI_FD, PMI_PORT or Cray's PMI_CONTROL_PORT; OMPI_MCA_orte_hnp_uri). A rank
// count without one was not set by a launcher: exported by hand, or inherited from a job script.
// MPI_Init would then start a singleton (Open MPI: one process, whatever the count said), and a
// build without MPI would take the count for ranks it does not have; both builds refuse it
// alike, naming the variable. Running as one process instead would hide that the run is not the
// one asked for.

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "scatterlab/core/error.hpp"

namespace scatterlab::detail {

inline bool launcher_server_known() {
  for (const char* name : {"PMI_FD", "PMI_PORT", "PMI_CONTROL_PORT", "OMPI_MCA_orte_hnp_uri"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  for (char** entry = environ; *entry != nullptr; ++entry) {
    if (std::strncmp(*entry, "PMIX_SERVER_URI", std::strlen("PMIX_SERVER_URI")) == 0) return true;
  }
  return false;
}

// Throws InputError naming the variable when a rank count is set without a launcher, or is not
// a count.
inline int launched_ranks() {
  const char* name = nullptr;
  const char* value = nullptr;
  for (const char* candidate :
       {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS", "PMIX_RANK"}) {
    if ((value = std::getenv(candidate)) != nullptr) {
      name = candidate;
      break;
    }
  }
  if (name == nullptr) return 0;
  const std::string text = value;
  const char* accepted =
      "a rank count set by an MPI launcher (mpirun, mpiexec, srun) for the processes it starts; "
      "unset it to run one process, or start scatterlab with mpirun";
  if (!launcher_server_known()) {
    throw InputError(name,
                     "set to '" + text +
                         "' in the environment, but no MPI launcher started this process (no "
                         "launcher's server address is set beside it)",
                     accepted);
  }
  if (std::strcmp(name, "PMIX_RANK") == 0) return 1;  // a PMIx launch that does not say its size
  char* end = nullptr;
  errno = 0;
  const long ranks = std::strtol(value, &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || ranks < 1 || ranks > 1 << 24) {
    throw InputError(name, "set to '" + text + "', which is not a number of ranks", accepted);
  }
  return static_cast<int>(ranks);
}

}  // namespace scatterlab::detail

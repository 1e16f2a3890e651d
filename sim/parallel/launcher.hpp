#pragma once
// How many ranks the launcher started, from the environment it sets (Open MPI, MPICH/PMI, PMIx);
// 0 when the process was not started by an MPI launcher.

#include <cstdlib>
#include <string>

namespace scatterlab::detail {

inline int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    if (const char* value = std::getenv(name)) return std::atoi(value);
  }
  return std::getenv("PMIX_RANK") != nullptr ? 1 : 0;
}

}  // namespace scatterlab::detail

#pragma once
// The one step every writing command takes before any work: its OutputPlan is checked (an
// InputError naming the flag when an output would destroy an input or another output, or names
// something that is not a file), and the temporaries a killed run left beside its outputs are
// removed and reported. The output directories are made later, by plan.make_output_directories(),
// once every input has been read and checked: bad input leaves no directory behind.

#include "scatterlab/io/output_plan.hpp"

namespace scatterlab::cli {

// `root`: whether this process is the one that writes and prints (MPI rank 0, or the only one).
void prepare_outputs(const OutputPlan& plan, bool root = true);

}  // namespace scatterlab::cli

#pragma once
// HDF5 dimension scales for a run file's tallies and model curves, so that general tools label
// their axes: xarray (engine "h5netcdf", group "tallies/fluence") reads named dimensions with
// bin-centre coordinates, and h5py (`mean.dims[0].label`, `mean.dims[0][0]`) and HDFView show
// the same. The `dims` attributes stay, for readers that do not know dimension scales.
//
// Each dimension named in a `dims` attribute gets a 1-D scale dataset of that name in the group
// of the data it labels: the bin centres of /grid/<name> (with the axis's units; the edges stay
// in /grid) when the grid has that axis with finite edges, else the bin index 0, 1, ..., n - 1
// (flux's `component`, a semi-infinite slab's `layer`). The scales sit beside the data rather
// than in /grid because netCDF-4 readers look a dimension's coordinates up by name in the
// variable's own group and its parents.

#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/io/hdf5_file.hpp"

namespace scatterlab {

// Scales for /tallies/<name>/{mean,stderr} (dims on the tally's group) and every
// /models/<model>/<curve> (dims on the curve), read from the file being written.
void write_dimension_scales(hdf5::Group& root);

// The names in a `dims` attribute ("r,z,theta,phi"); none for a scalar's "".
std::vector<std::string> split_dims(const std::string& dims);

// The members of a /models/<model> group that are curves, not the scales of their dimensions.
std::vector<std::string> curve_names(const hdf5::Group& model);

// Attributes that HDF5 keeps for dimension scales (DIMENSION_LIST, CLASS, ...): references that
// are re-made, not copied, when a file is rewritten.
bool is_dimension_scale_attribute(std::string_view name);

}  // namespace scatterlab

#pragma once
// Internal to casefile/: the reader of [[node_set]] (parse_sets.cpp), called
// by parse_case_string after [[region]]. Same conventions as parse_case.cpp:
// unknown keys first, then the keys in turn; the first problem throws
// InputError "FILE:LINE:COL: key 'PATH': ...".

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// The names of the sets that every box mesh has (node, face or cell sets),
/// in any dimension: xmin, xmax, ymin, ymax, zmin, zmax, boundary, all.
const std::vector<std::string>& mesh_set_names();

/// [[node_set]] into c.node_sets; needs c.mesh and c.regions read first (a
/// node set's name may not be a mesh set's or a region's).
void read_node_sets(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

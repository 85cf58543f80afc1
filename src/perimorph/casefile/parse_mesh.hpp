#pragma once
// Internal to casefile/: the reader of [mesh] (parse_mesh.cpp), called first
// by parse_case_string. Same conventions as parse_case.cpp.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [mesh] (with [[mesh.hole]] and [[mesh.cut]]) into c.mesh; needs c.path.
void read_mesh(const Table& root, CaseConfig& c);

/// Reads `lower` and `upper` of a box (mesh or region) and checks that upper
/// exceeds lower along every axis.
void read_box(const Table& t, int dim, Vec3& lower, Vec3& upper);

}  // namespace perimorph::casefile::detail

#pragma once
// Internal to casefile/: the readers of [[dirichlet]] and [[traction]]
// (parse_boundary.cpp), called by parse_case_string after the mesh, sets and
// model. Same conventions as parse_case.cpp: unknown keys first, then the
// keys in turn; the first problem throws InputError "FILE:LINE:COL: key
// 'PATH': ...".

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [[dirichlet]] into c.dirichlet and [[traction]] into c.tractions; needs
/// c.mesh read first (the dimension).
void read_boundary(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

#pragma once
// Internal to casefile/: the reader of [[material]] (parse_material.cpp),
// called by parse_case_string after [model]. Same conventions as
// parse_case.cpp: unknown keys first, then the keys in turn; the first problem
// throws InputError "FILE:LINE:COL: key 'PATH': ...".

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [[material]] into c.materials (at least one); needs c.mesh, c.regions and
/// c.nonlocal.enabled (whether [nonlocal] is present: it makes the values
/// that central forces determine optional and allows `cauchy`) set first.
void read_materials(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

#pragma once
// Internal to casefile/: the readers of the non-local sections [nonlocal] and
// [alpha] / [[alpha.region]] (parse_nonlocal.cpp), called by
// parse_case_string after [[material]]. Same conventions as parse_case.cpp:
// unknown keys first, then the keys in turn; the first problem throws
// InputError "FILE:LINE:COL: key 'PATH': ...".

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [nonlocal] into c.nonlocal (enabled = the section is present).
void read_nonlocal(const Table& root, CaseConfig& c);

/// [alpha] into c.alpha; needs c.nonlocal and c.mesh read first. Absent:
/// value 0, no regions.
void read_alpha(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

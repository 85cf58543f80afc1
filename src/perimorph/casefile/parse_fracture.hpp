#pragma once
// Internal to casefile/: the reader of [fracture] (parse_fracture.cpp), bond
// failure by critical stretch (THEORY §5), called by parse_case_string after
// [nonlocal] and [alpha]. Same conventions as parse_case.cpp: unknown keys
// first, then the keys in turn; the first problem throws InputError
// "FILE:LINE:COL: key 'PATH': ...".

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [fracture] into c.fracture (enabled = the section is present); needs
/// c.nonlocal read first ([fracture] without [nonlocal] is an error).
void read_fracture(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

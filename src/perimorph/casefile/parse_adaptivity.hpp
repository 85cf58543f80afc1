#pragma once
// Internal to casefile/: the reader of [adaptivity] (parse_adaptivity.cpp),
// the non-local zone that grows with the crack (THEORY §5), called by
// parse_case_string after [fracture]. Same conventions as parse_case.cpp.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [adaptivity] into c.adaptivity; needs c.nonlocal, c.alpha and c.fracture
/// read first (it needs both sections, and an α that can grow).
void read_adaptivity(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

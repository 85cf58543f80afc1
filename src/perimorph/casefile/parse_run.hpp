#pragma once
// Internal to casefile/: the readers of [loading], [solver] and [output]
// (parse_run.cpp), how a case is run; called by parse_case_string last. Same
// conventions as parse_case.cpp: unknown keys first, then the keys in turn;
// the first problem throws InputError "FILE:LINE:COL: key 'PATH': ...".

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// [loading] into c.loading (needs c.mesh for the body force's dimension).
void read_loading(const Table& root, CaseConfig& c);
/// [solver] into c.solver; petsc_options must read as PETSc options: each word
/// '-' and a letter, followed by at most one value.
void read_solver(const Table& root, CaseConfig& c);
/// [output] into c.output (basename defaults to the case file's stem).
void read_output(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

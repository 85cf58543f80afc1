#pragma once
// Where a case-file value came from (casefile/case_config.hpp).

#include <string>

namespace perimorph::casefile {

/// Where a value came from, for messages raised after parsing (e.g. a set name
/// that the mesh does not have).
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string key;               ///< dotted path, e.g. "dirichlet[2].set"
  std::string describe() const;  ///< "case.toml:12:5: key 'dirichlet[2].set'"
};

}  // namespace perimorph::casefile

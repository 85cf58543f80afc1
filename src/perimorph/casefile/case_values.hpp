#pragma once
// Every value of a case file by its dotted path, to tell two versions of a
// case apart (a restart refuses a changed case, run/checkpoint.hpp) by the
// keys that differ, not by a checksum.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile {

/// "section.key" → its value as TOML text, for every value (arrays element by
/// element: "mesh.cells[1]"; arrays of tables: "material[2].E"), in document
/// order. `text` is a case that parsed (CaseConfig::text); `path` names it in
/// errors.
std::vector<std::pair<std::string, std::string>> case_values(std::string_view text, const std::string& path);

/// The keys whose values differ between `a` and `b`, or that one of them
/// lacks, sorted.
std::vector<std::string> differing_keys(const std::vector<std::pair<std::string, std::string>>& a,
                                        const std::vector<std::pair<std::string, std::string>>& b);

}  // namespace perimorph::casefile

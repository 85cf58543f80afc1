#pragma once
// Case-file parsing of the local damage (THEORY §6): a material's
// [material.damage] table (the law) and the [damage] section (its nonlinear
// solve). Internal to casefile/; format in docs/case-file.md.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

namespace perimorph::casefile::detail {

/// Reads `material`'s [material.damage] (table `t` is the material's entry)
/// into m.damage; throws InputError naming the key for a missing or
/// impossible value, an unknown key, or damage on a non-isotropic material.
void read_material_damage(const Table& t, MaterialSpec& m);

/// Reads [damage] and checks what the damage of the case's materials needs of
/// the other sections (d_c < 1 with [nonlocal]). Call after [nonlocal].
void read_damage(const Table& root, CaseConfig& c);

}  // namespace perimorph::casefile::detail

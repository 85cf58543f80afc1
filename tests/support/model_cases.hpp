#pragma once
// Models that exercise a process's part and piece of a model (issue 17):
// a mixed CG/DG plate, a 3D ball of DG degree 0 with the partial volume, a
// plate with a cut (CG) and the flagship with its holes (DG).

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace perimorph::testing {

struct NamedCase {
  std::string name;
  casefile::CaseConfig config;
};

inline std::vector<NamedCase> model_part_cases() {
  const std::string examples = std::string(PERIMORPH_SOURCE_DIR) + "/examples/";
  auto ball3d = box_case(3, {6, 6, 6}, Vec3(3.0, 3.0, 3.0), 100.0, 0.25);
  add_nonlocal(ball3d, casefile::KernelKind::constant, 1.0, 0.0, 2,
               casefile::Discretization::discontinuous_constant);
  ball3d.alpha.regions = {alpha_ball(Vec3(1.5, 1.5, 1.5), 1.0, 0.6)};
  ball3d.nonlocal.horizon_edge = casefile::HorizonEdge::partial_volume;
  // B3's mesh, cut and α, with 3 × 3 points a cell instead of its 6 × 6: 3·10⁶
  // bonds instead of 47·10⁶, which made these tests long under AddressSanitizer.
  auto b3 = casefile::parse_case_file(examples + "b3_cracked_plate_2d/case.toml");
  b3.nonlocal.quadrature = 3;
  return {{"mixed CG/DG plate", mixed_cg_dg_plate()},
          {"3D ball, DG degree 0, partial volume", ball3d},
          {"b3 (cut, CG)", b3},
          {"flagship (holes, DG)", casefile::parse_case_file(examples + "hole_plate_2d/case.toml")}};
}

/// The cases with loads and supports: a plate with a cut (CG), the flagship
/// (holes; α = 0 at the start) and the mixed CG/DG plate pulled along x.
inline std::vector<NamedCase> loaded_model_cases() {
  auto cases = model_part_cases();
  std::vector<NamedCase> out;
  for (auto& c : cases)
    if (c.name.rfind("b3", 0) == 0 || c.name.rfind("flagship", 0) == 0) out.push_back(std::move(c));
  auto plate = mixed_cg_dg_plate();
  plate.dirichlet = {fixed("xmin", 0), fixed("xmin", 1), fixed("xmax", 0, 0.01)};
  out.push_back({"mixed CG/DG plate pulled", plate});
  return out;
}

/// ModelPart::share_flags, simulated on one process: each part's own flags
/// (the computed cells', 0 elsewhere) are checked against the whole model's
/// and kept for their maximum over the parts; the whole model's flags are
/// given back, as the maximum over the processes would be.
struct SharedFlags {
  const std::vector<char>* whole = nullptr;
  std::vector<char> over_parts;  // the elementwise maximum of the parts' own flags
  std::function<std::vector<char>(std::vector<char>)> share() {
    return [this](std::vector<char> mine) {
      EXPECT_EQ(mine.size(), whole->size());
      if (over_parts.empty()) over_parts.assign(mine.size(), 0);
      for (std::size_t c = 0; c < mine.size() && c < whole->size(); ++c) {
        EXPECT_LE(mine[c], (*whole)[c]) << "cell " << c;
        over_parts[c] = std::max(over_parts[c], mine[c]);
      }
      return *whole;
    };
  }
};

}  // namespace perimorph::testing

#pragma once
// Test support for the same-answer tests of distributed runs (issue 17,
// tests/mpi/): bit-for-bit comparison of values and of the records of two
// runs with bond failure.

#include "perimorph/core/types.hpp"
#include "perimorph/run/static_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>

namespace perimorph::testing {

inline bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}
inline bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
}

/// The records of a run with bond failure or damage (`got`) against
/// another's (`expected`), increment by increment from `got`'s first: the
/// same failed bonds, floating parts, cell mechanisms, damaged and critical
/// points, α's balls, dofs, DG and non-local cells; the energies (the
/// ledger's model change too), largest damage, crack area and
/// iteration counts the same bits where `bitwise`, else within 1e-10 of the
/// largest of the record's energies (the areas of their own) and the
/// iterations (and damage updates) within one. Then the failed bonds' positions, in the order
/// they failed, the same bits.
inline void expect_same_fracture_run(const run::RunSummary& got, const run::RunSummary& expected,
                                     bool bitwise) {
  ASSERT_FALSE(got.history.empty());
  ASSERT_GE(expected.history.size(), got.history.size());
  const std::size_t skipped = expected.history.size() - got.history.size();
  for (std::size_t i = 0; i < got.history.size(); ++i) {
    const auto &a = got.history[i], &b = expected.history[i + skipped];
    SCOPED_TRACE("increment " + std::to_string(b.increment));
    EXPECT_EQ(a.increment, b.increment);
    EXPECT_EQ(a.bonds_broken, b.bonds_broken);
    EXPECT_EQ(a.bonds_broken_increment, b.bonds_broken_increment);
    EXPECT_EQ(a.floating_parts, b.floating_parts);
    EXPECT_EQ(a.cell_mechanisms, b.cell_mechanisms);
    EXPECT_EQ(a.damaged_points, b.damaged_points);
    EXPECT_EQ(a.critical_points, b.critical_points);
    EXPECT_EQ(a.alpha_balls, b.alpha_balls);
    EXPECT_EQ(a.dofs, b.dofs);
    EXPECT_EQ(a.dg_cells, b.dg_cells);
    EXPECT_EQ(a.nonlocal_cells, b.nonlocal_cells);
    EXPECT_LE(std::abs(a.damage_iterations - b.damage_iterations), bitwise ? 0 : 1);
    // The overshoot is a difference at round-off: scaled by the energies.
    const double energy = std::max({std::abs(b.external_work), std::abs(b.strain_energy),
                                    std::abs(b.dissipated), std::abs(b.damage_dissipated)});
    for (auto [mine, theirs, scale] :
         {std::tuple{a.strain_energy, b.strain_energy, energy},
          {a.external_work, b.external_work, energy},
          {a.dissipated, b.dissipated, energy},
          {a.damage_dissipated, b.damage_dissipated, energy},
          {a.max_damage, b.max_damage, 1.0},
          {a.overshoot, b.overshoot, energy},
          {a.model_change, b.model_change, energy},
          {a.crack_area, b.crack_area, std::abs(b.crack_area)},
          {a.broken_face_area, b.broken_face_area, std::abs(b.broken_face_area)}}) {
      if (bitwise) {
        EXPECT_TRUE(same_bits(mine, theirs) || (std::isnan(mine) && std::isnan(theirs)))
            << mine << " " << theirs;
      } else if (!std::isnan(theirs)) {
        EXPECT_NEAR(mine, theirs, 1e-10 * scale);
      }
    }
    EXPECT_LE(std::abs(a.iterations - b.iterations), bitwise ? 0 : 1);
  }
  ASSERT_EQ(got.failed_bond_points.size(), expected.failed_bond_points.size());
  for (std::size_t k = 0; k < got.failed_bond_points.size(); ++k)
    ASSERT_TRUE(same_bits(got.failed_bond_points[k].first, expected.failed_bond_points[k].first) &&
                same_bits(got.failed_bond_points[k].second, expected.failed_bond_points[k].second))
        << "failed bond " << k;
}

}  // namespace perimorph::testing

// s_crit, derived in one place (setup/critical_stretch.hpp, THEORY §5): the
// order of its sources, the closed form from G_c, and the same value for the
// model a run builds.

#include "perimorph/setup/critical_stretch.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace perimorph {
namespace {

TEST(CriticalStretch, ComesFromTheOptionThenTheCase) {
  using setup::StretchSource;
  casefile::FractureSpec f;
  const double kappa = 0.25;
  auto s = setup::resolve_critical_stretch(f, kappa, std::nullopt);
  EXPECT_EQ(s.source, StretchSource::unit);
  EXPECT_EQ(s.value, 1.0);
  f.enabled = true;
  f.G_c = 1e-6;
  s = setup::resolve_critical_stretch(f, kappa, std::nullopt);
  EXPECT_EQ(s.source, StretchSource::case_G_c);
  EXPECT_NEAR(kappa * s.value * s.value, f.G_c, 1e-20);
  EXPECT_THROW(setup::resolve_critical_stretch(f, std::numeric_limits<double>::quiet_NaN(), std::nullopt),
               InputError);
  f.G_c = 0.0;
  f.s_crit = 3e-3;
  s = setup::resolve_critical_stretch(f, kappa, std::nullopt);
  EXPECT_EQ(s.source, StretchSource::case_s_crit);
  EXPECT_EQ(s.value, 3e-3);
  s = setup::resolve_critical_stretch(f, kappa, 2e-3);
  EXPECT_EQ(s.source, StretchSource::option);
  EXPECT_EQ(s.value, 2e-3);
  EXPECT_THROW(setup::resolve_critical_stretch(f, kappa, 0.0), InputError);
  EXPECT_THROW(setup::resolve_critical_stretch(f, kappa, -1e-3), InputError);
}

/// A run's s_crit from G_c is sqrt(G_c / κ) of the model's own calibration
/// (after the discrete factor), the value `gc` uses for the same case.
TEST(CriticalStretch, ModelFromGcUsesItsCalibration) {
  auto c = testing::box_case(2, {6, 4, 1}, Vec3(3.0, 2.0, 0.0), 1.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::constant, 0.75, 0.0, 2);
  c.alpha.value = 1.0;
  c.fracture.enabled = true;
  c.fracture.G_c = 2e-4;
  const setup::Discretization model = setup::build_discretization(c);
  const double kappa = model.nonlocal->calibration.gc_factor;
  ASSERT_GT(kappa, 0.0);
  const double s = setup::critical_stretch(model);
  EXPECT_DOUBLE_EQ(s, std::sqrt(c.fracture.G_c / kappa));
  EXPECT_EQ(s, setup::resolve_critical_stretch(c.fracture, kappa).value);
  c.fracture.G_c = 0.0;
  c.fracture.s_crit = 5e-3;
  EXPECT_EQ(setup::critical_stretch(setup::build_discretization(c)), 5e-3);
}

}  // namespace
}  // namespace perimorph

// The material of a non-local case resolved for central forces (issue 4,
// item 2; THEORY §2.1): shear moduli left out are set from the Cauchy
// relations, a given inconsistent one is an error naming the relation, the
// key, by how much and the nearest representable material, and
// cauchy = "nearest" accepts that material.

#include "perimorph/setup/nonlocal_material.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/peridynamics/anisotropy.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>

namespace perimorph {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

casefile::CaseConfig orthotropic_case(int dim) {
  auto c = testing::box_case(dim, {4, 4, 4}, Vec3::Ones(), 1.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::exponential, 0.75, 0.15, 2);
  auto& m = c.materials.front();
  m.kind = casefile::MaterialKind::orthotropic;
  m.E1 = 60e3;
  m.E2 = 90e3;
  m.E3 = 150e3;
  m.nu12 = 0.3;
  m.nu13 = 0.1;
  m.nu23 = 0.2;
  m.G12 = m.G13 = m.G23 = nan;
  m.where = {"case.toml", 7, 1, "material[1]"};
  for (int s = 0; s < 3; ++s) m.shear_where[static_cast<std::size_t>(s)] = m.where;
  return c;
}

std::string error_of(const casefile::CaseConfig& c) {
  try {
    (void)setup::nonlocal_material(c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(NonlocalMaterial, ShearModuliLeftOutFollowCauchy3D) {
  const auto mat = setup::nonlocal_material(orthotropic_case(3));
  EXPECT_EQ(mat.kind, peridynamics::AngularKind::orthotropic);
  EXPECT_DOUBLE_EQ(mat.C0(5, 5), mat.C0(0, 1));
  EXPECT_DOUBLE_EQ(mat.C0(4, 4), mat.C0(0, 2));
  EXPECT_DOUBLE_EQ(mat.C0(3, 3), mat.C0(1, 2));
  EXPECT_TRUE(peridynamics::cauchy_violations(mat.C0, 3, 1e-14).empty());
  EXPECT_EQ(mat.notes.size(), 3u);
  // The normal block is the given material's (compliance inverse).
  const Voigt6 given = fem::stiffness_voigt(
      fem::OrthotropicElasticity{60e3, 90e3, 150e3, 0.3, 0.1, 0.2, 1.0, 1.0, 1.0, Mat3::Identity()});
  EXPECT_LT((mat.C0.topLeftCorner(3, 3) - given.topLeftCorner(3, 3)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(NonlocalMaterial, InconsistentShearModulusNamesRelationKeyAndNearestMaterial) {
  auto c = orthotropic_case(3);
  auto& m = c.materials.front();
  m.G12 = 30e3;
  m.shear_where[2] = {"case.toml", 12, 7, "material[1].G12"};
  const std::string msg = error_of(c);
  EXPECT_NE(msg.find("case.toml:12:7"), std::string::npos) << msg;
  EXPECT_NE(msg.find("material[1].G12"), std::string::npos) << msg;
  EXPECT_NE(msg.find("C1212 = C1122"), std::string::npos) << msg;
  EXPECT_NE(msg.find("C1212 = 30000"), std::string::npos) << msg;
  EXPECT_NE(msg.find("off by -25.7 %"), std::string::npos) << msg;
  EXPECT_NE(msg.find("leave G12 out"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cauchy = \"nearest\""), std::string::npos) << msg;
  // Accepting the nearest material: the totally symmetric part.
  m.cauchy = casefile::CauchyRule::nearest;
  const auto mat = setup::nonlocal_material(c);
  const double C1122 = mat.C0(0, 1);
  EXPECT_DOUBLE_EQ(mat.C0(5, 5), C1122);
  const Voigt6 given = fem::stiffness_voigt(
      fem::OrthotropicElasticity{60e3, 90e3, 150e3, 0.3, 0.1, 0.2, 30e3, 1.0, 1.0, Mat3::Identity()});
  EXPECT_NEAR(C1122, (given(0, 1) + 2.0 * 30e3) / 3.0, 1e-9);
}

TEST(NonlocalMaterial, TwoDimensionalRelationHoldsOnTheReducedTensor) {
  for (const PlaneMode mode : {PlaneMode::strain, PlaneMode::stress}) {
    auto c = orthotropic_case(2);
    c.model.plane = mode;
    c.materials.front().axes = Mat3(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
    const auto mat = setup::nonlocal_material(c);
    EXPECT_EQ(mat.kind, peridynamics::AngularKind::planar);
    EXPECT_TRUE(peridynamics::cauchy_violations(mat.C0, 2, 1e-12).empty())
        << (mode == PlaneMode::strain ? "strain" : "stress") << "\n"
        << mat.C0;
  }
  // Plane stress: G12 = the plane-stress C1122 = C1122 − C1133 C2233 / C3333.
  auto c = orthotropic_case(2);
  c.model.plane = PlaneMode::stress;
  const auto mat = setup::nonlocal_material(c);
  const Voigt6& C = mat.C_material;
  EXPECT_NEAR(C(5, 5), C(0, 1) - C(0, 2) * C(1, 2) / C(2, 2), 1e-9);
}

TEST(NonlocalMaterial, TransverselyIsotropicInPlanePoissonRatioFromCentralForces) {
  auto c = orthotropic_case(3);
  auto& m = c.materials.front();
  m.kind = casefile::MaterialKind::transversely_isotropic;
  m.E1 = m.E2 = 60e3;
  m.E3 = 150e3;
  m.nu13 = m.nu23 = 0.1;
  m.nu12 = nan;
  const auto mat = setup::nonlocal_material(c);
  EXPECT_EQ(mat.kind, peridynamics::AngularKind::transversely_isotropic);
  EXPECT_NEAR(mat.C0(0, 1), mat.C0(0, 0) / 3.0, 1e-9 * mat.C0(0, 0));
  EXPECT_NE(mat.notes.front().find("nu_in = 0.3"), std::string::npos) << mat.notes.front();
  // A given nu_in that breaks C1122 = C1111/3 names nu_in.
  m.nu12 = 0.25;
  m.G12 = m.E1 / (2.0 * 1.25);
  const std::string msg = error_of(c);
  EXPECT_NE(msg.find("nu_in"), std::string::npos) << msg;
  EXPECT_NE(msg.find("C1212 = C1122"), std::string::npos) << msg;
}

TEST(NonlocalMaterial, IsotropicPoissonRatioNearestOption) {
  auto c = testing::box_case(3, {4, 4, 4}, Vec3::Ones(), 100.0, 0.3);
  testing::add_nonlocal(c, casefile::KernelKind::constant, 0.75, 0.75, 2);
  EXPECT_NE(error_of(c).find("nu = 0.3 cannot be represented"), std::string::npos);
  c.materials.front().cauchy = casefile::CauchyRule::nearest;
  const auto mat = setup::nonlocal_material(c);
  const double lambda = 100.0 * 0.3 / (1.3 * 0.4), mu = 100.0 / 2.6;
  EXPECT_NEAR(mat.C0(0, 1), (lambda + 2 * mu) / 3, 1e-12);
  EXPECT_NEAR(mat.C0(5, 5), (lambda + 2 * mu) / 3, 1e-12);
  EXPECT_DOUBLE_EQ(mat.nu, 0.25);
}

}  // namespace
}  // namespace perimorph

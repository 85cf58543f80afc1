// [[material]] parsing: orthotropic engineering constants and stiffness
// components, transversely isotropic input, the values that [nonlocal] makes
// optional (NaN) and the `cauchy` rule. Error files: tests/data/bad_cases.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <string>

namespace perimorph::casefile {
namespace {

/// A 2D box, then `material` (lines 9 on), then [nonlocal] when `nonlocal`.
std::string case_with(const std::string& material, bool nonlocal) {
  return std::string(R"([mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]

[[material]]
name = "m"
)") + material +
         (nonlocal ? "\n[nonlocal]\nkernel = \"constant\"\nhorizon = 1.5\n" : "");
}

/// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text) {
  try {
    parse_case_string(text, "m.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

constexpr const char* kNormalStiffness = R"(type = "orthotropic"
C1111 = 150
C2222 = 90
C3333 = 80
C1122 = 30
C1133 = 25
C2233 = 20
)";

TEST(CaseFileMaterial, StiffnessWithShearsLeftOutInNonlocal) {
  const CaseConfig c = parse_case_string(case_with(kNormalStiffness, true), "s.toml");
  const MaterialSpec& m = c.materials.at(0);
  EXPECT_EQ(m.kind, MaterialKind::orthotropic);
  EXPECT_TRUE(m.by_stiffness);
  EXPECT_EQ(m.stiffness(0, 0), 150.0);
  EXPECT_EQ(m.stiffness(1, 1), 90.0);
  EXPECT_EQ(m.stiffness(2, 2), 80.0);
  EXPECT_EQ(m.stiffness(0, 1), 30.0);
  EXPECT_EQ(m.stiffness(1, 0), 30.0);
  EXPECT_EQ(m.stiffness(0, 2), 25.0);
  EXPECT_EQ(m.stiffness(2, 0), 25.0);
  EXPECT_EQ(m.stiffness(1, 2), 20.0);
  EXPECT_EQ(m.stiffness(2, 1), 20.0);
  for (int d = 3; d < 6; ++d) EXPECT_TRUE(std::isnan(m.stiffness(d, d))) << d;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (i != j && (i >= 3 || j >= 3)) {
        EXPECT_EQ(m.stiffness(i, j), 0.0) << i << "," << j;
      }
  EXPECT_TRUE(std::isnan(m.G12) && std::isnan(m.G13) && std::isnan(m.G23));
  // Left out: the material's header (line 7) with the key.
  EXPECT_EQ(m.shear_where[0].describe(), "s.toml:7:1: key 'material[1].C2323'");
  EXPECT_EQ(m.shear_where[1].describe(), "s.toml:7:1: key 'material[1].C1313'");
  EXPECT_EQ(m.shear_where[2].describe(), "s.toml:7:1: key 'material[1].C1212'");
  // The engineering fields are those of the normal block's inverse.
  const Mat3 S = m.stiffness.topLeftCorner<3, 3>().inverse();
  EXPECT_NEAR(m.E1, 1 / S(0, 0), 1e-12);
  EXPECT_NEAR(m.E2, 1 / S(1, 1), 1e-12);
  EXPECT_NEAR(m.E3, 1 / S(2, 2), 1e-12);
  EXPECT_NEAR(m.nu12, -S(0, 1) / S(0, 0), 1e-12);
  EXPECT_NEAR(m.nu13, -S(0, 2) / S(0, 0), 1e-12);
  EXPECT_NEAR(m.nu23, -S(1, 2) / S(1, 1), 1e-12);
  EXPECT_EQ(m.cauchy, CauchyRule::exact);
  EXPECT_EQ(m.cauchy_where.describe(), "s.toml:7:1: key 'material[1].cauchy'");
}

TEST(CaseFileMaterial, StiffnessWithShearsAndRotation) {
  const CaseConfig c = parse_case_string(
      case_with(std::string(kNormalStiffness) +
                    "C2323 = 21\nC1313 = 26\nC1212 = 31\nrotation = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]\n",
                false),
      "s.toml");
  const MaterialSpec& m = c.materials.at(0);
  EXPECT_TRUE(m.by_stiffness);
  EXPECT_EQ(m.stiffness(3, 3), 21.0);
  EXPECT_EQ(m.stiffness(4, 4), 26.0);
  EXPECT_EQ(m.stiffness(5, 5), 31.0);
  EXPECT_EQ(m.G23, 21.0);
  EXPECT_EQ(m.G13, 26.0);
  EXPECT_EQ(m.G12, 31.0);
  EXPECT_EQ(m.shear_where[0].describe(), "s.toml:16:9: key 'material[1].C2323'");
  EXPECT_EQ(m.shear_where[2].describe(), "s.toml:18:9: key 'material[1].C1212'");
  EXPECT_TRUE(m.axes.col(0).isApprox(Vec3(0, 1, 0)));  // e1 along y
}

TEST(CaseFileMaterial, EngineeringShearsLeftOutInNonlocal) {
  const CaseConfig c = parse_case_string(
      case_with("type = \"orthotropic\"\nE1 = 140\nE2 = 10\nE3 = 10\nnu12 = 0.3\nnu13 = 0.3\nnu23 = 0.45\n"
                "G13 = 5\n",
                true),
      "e.toml");
  const MaterialSpec& m = c.materials.at(0);
  EXPECT_FALSE(m.by_stiffness);
  EXPECT_EQ(m.stiffness, Voigt6::Zero());
  EXPECT_EQ(m.E1, 140.0);
  EXPECT_EQ(m.nu23, 0.45);
  EXPECT_TRUE(std::isnan(m.G12));
  EXPECT_EQ(m.G13, 5.0);
  EXPECT_TRUE(std::isnan(m.G23));
  EXPECT_EQ(m.shear_where[0].describe(), "e.toml:7:1: key 'material[1].G23'");
  EXPECT_EQ(m.shear_where[1].describe(), "e.toml:16:7: key 'material[1].G13'");
  EXPECT_EQ(m.shear_where[2].describe(), "e.toml:7:1: key 'material[1].G12'");
}

TEST(CaseFileMaterial, TransverselyIsotropicFillsOrthotropicFields) {
  const CaseConfig c = parse_case_string(
      case_with("type = \"transversely-isotropic\"\nE_in = 60\nE_axis = 150\nnu_axial = 0.1\nnu_in = 0.3\n"
                "G_axial = 20\nrotation = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]\n",
                false),
      "t.toml");
  const MaterialSpec& m = c.materials.at(0);
  EXPECT_EQ(m.kind, MaterialKind::transversely_isotropic);
  EXPECT_FALSE(m.by_stiffness);
  EXPECT_EQ(m.E1, 60.0);
  EXPECT_EQ(m.E2, 60.0);
  EXPECT_EQ(m.E3, 150.0);
  EXPECT_EQ(m.nu12, 0.3);
  EXPECT_EQ(m.nu13, 0.1);
  EXPECT_EQ(m.nu23, 0.1);
  EXPECT_DOUBLE_EQ(m.G12, 60.0 / 2.6);
  EXPECT_EQ(m.G13, 20.0);
  EXPECT_EQ(m.G23, 20.0);
  EXPECT_EQ(m.shear_where[0].describe(), "t.toml:14:11: key 'material[1].G_axial'");
  EXPECT_EQ(m.shear_where[1].describe(), "t.toml:14:11: key 'material[1].G_axial'");
  EXPECT_EQ(m.shear_where[2].describe(), "t.toml:13:9: key 'material[1].nu_in'");
  EXPECT_TRUE(m.axes.col(2).isApprox(Vec3(0, 1, 0)));  // e3 (the axis) along y
}

TEST(CaseFileMaterial, TransverselyIsotropicNonlocalLeavesOutNuInAndShear) {
  const CaseConfig c = parse_case_string(case_with("type = \"transversely-isotropic\"\nE_in = 60\nE_axis = "
                                                   "150\nnu_axial = 0.1\ncauchy = \"nearest\"\n",
                                                   true),
                                         "t.toml");
  const MaterialSpec& m = c.materials.at(0);
  EXPECT_EQ(m.E1, 60.0);
  EXPECT_EQ(m.E3, 150.0);
  EXPECT_EQ(m.nu13, 0.1);
  EXPECT_TRUE(std::isnan(m.nu12));
  EXPECT_TRUE(std::isnan(m.G12) && std::isnan(m.G13) && std::isnan(m.G23));
  EXPECT_EQ(m.shear_where[0].describe(), "t.toml:7:1: key 'material[1].G_axial'");
  EXPECT_EQ(m.shear_where[2].describe(), "t.toml:7:1: key 'material[1].nu_in'");
  EXPECT_EQ(m.cauchy, CauchyRule::nearest);
  EXPECT_EQ(m.cauchy_where.describe(), "t.toml:13:10: key 'material[1].cauchy'");
}

TEST(CaseFileMaterial, CauchyOnIsotropic) {
  const CaseConfig c = parse_case_string(case_with("E = 100\ncauchy = \"exact\"\n", true), "i.toml");
  EXPECT_EQ(c.materials.at(0).cauchy, CauchyRule::exact);
  EXPECT_EQ(c.materials.at(0).cauchy_where.describe(), "i.toml:10:10: key 'material[1].cauchy'");
  const CaseConfig n =
      parse_case_string(case_with("E = 100\nnu = 0.3\ncauchy = \"nearest\"\n", true), "i.toml");
  EXPECT_EQ(n.materials.at(0).cauchy, CauchyRule::nearest);
  EXPECT_EQ(n.materials.at(0).nu, 0.3);
}

TEST(CaseFileMaterial, ErrorsNameKeysAndReasons) {
  const std::string engineering =
      "type = \"orthotropic\"\nE1 = 140\nE2 = 10\nE3 = 10\nnu12 = 0.3\nnu13 = 0.3\n"
      "nu23 = 0.45\n";
  std::string msg = error_of(case_with(engineering + "C1122 = 4\n", true));
  EXPECT_TRUE(contains(msg, "key 'material[1].C1122': cannot be combined with material[1].E1")) << msg;
  EXPECT_TRUE(contains(msg, "pick one form")) << msg;

  msg = error_of(case_with(engineering + "G12 = 5\nG13 = 5\n", false));
  EXPECT_TRUE(contains(msg, "key 'material[1].G23': missing required key")) << msg;
  EXPECT_TRUE(contains(msg, "may only be left out with [nonlocal], where central forces determine them"))
      << msg;

  std::string stiffness = kNormalStiffness;
  stiffness.replace(stiffness.find("C2233 = 20"), 10, "C2233 = 90");
  msg = error_of(case_with(stiffness, true));
  EXPECT_TRUE(contains(msg, "key 'material[1].C2233': C2233 = 90 needs |C2233| < sqrt(C2222 C3333)")) << msg;

  msg = error_of(case_with(std::string(kNormalStiffness) + "C1212 = 0\n", true));
  EXPECT_TRUE(contains(msg, "key 'material[1].C1212': must be positive (a shear stiffness component)"))
      << msg;

  stiffness = kNormalStiffness;
  stiffness.replace(stiffness.find("C2222 = 90"), 10, "C2222 = -9");
  msg = error_of(case_with(stiffness, true));
  EXPECT_TRUE(contains(msg, "key 'material[1].C2222': must be positive")) << msg;

  const std::string transverse = "type = \"transversely-isotropic\"\nE_in = 60\nE_axis = 150\n";
  msg = error_of(case_with(transverse + "nu_axial = 0.7\n", true));
  EXPECT_TRUE(
      contains(msg, "key 'material[1].nu_axial': nu_axial = 0.7 needs |nu_axial| < sqrt(E_in / E_axis)"))
      << msg;
  msg = error_of(case_with(transverse + "nu_axial = 0.5\nnu_in = 0.6\n", true));
  EXPECT_TRUE(contains(msg, "key 'material[1].nu_in': nu_in = 0.6 and nu_axial = 0.5 make the compliance"))
      << msg;
  msg = error_of(case_with(transverse + "nu_axial = 0.1\nG_axial = 20\n", false));
  EXPECT_TRUE(contains(msg, "key 'material[1].nu_in': missing required key")) << msg;
  msg = error_of(case_with(transverse + "nu_axial = 0.1\nE = 20\n", true));
  EXPECT_TRUE(contains(msg, "a transversely-isotropic material takes E_in, E_axis")) << msg;
  msg = error_of(case_with(transverse + "nu_axial = 0.1\nC1111 = 20\n", true));
  EXPECT_TRUE(contains(msg, "it belongs to orthotropic materials; set type = \"orthotropic\"")) << msg;

  msg = error_of(case_with("E = 1\nE_axis = 2\n", true));
  EXPECT_TRUE(contains(msg, "set type = \"transversely-isotropic\" (this one is isotropic)")) << msg;
  msg = error_of(case_with("E = 1\nrotation = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n", true));
  EXPECT_TRUE(contains(msg, "only orthotropic and transversely-isotropic materials have axes")) << msg;
  msg = error_of(case_with("type = \"transversely_isotropic\"\n", true));
  EXPECT_TRUE(contains(msg,
                       "unknown material type \"transversely_isotropic\"; did you mean "
                       "\"transversely-isotropic\"?"))
      << msg;
  EXPECT_TRUE(contains(msg, "\"isotropic\" (E, nu), \"orthotropic\" (E1")) << msg;
  msg = error_of(case_with(std::string(kNormalStiffness) + "C121 = 3\n", true));
  EXPECT_TRUE(contains(msg, "unknown key 'material[1].C121'; did you mean 'material[1].C1212'?")) << msg;
  msg = error_of(case_with("E = 1\ncauchy = \"neares\"\n", true));
  EXPECT_TRUE(contains(msg, "unknown cauchy rule \"neares\"; did you mean \"nearest\"?")) << msg;
}

}  // namespace
}  // namespace perimorph::casefile

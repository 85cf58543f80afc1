// [material.damage] and [damage] parsing (THEORY §6, docs/case-file.md): the
// values and defaults, and the errors a user can act on (missing and
// impossible values, unknown keys, damage that the model cannot carry).

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace perimorph::casefile {
namespace {

/// A 2D box with one isotropic material whose [material.damage] holds
/// `damage`, then `rest`.
std::string case_with(const std::string& damage, const std::string& rest = "") {
  return std::string(R"([mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]
[[material]]
name = "m"
E = 300000
nu = 0.25
[material.damage]
)") + damage +
         rest;
}

const std::string kNonlocal = "[nonlocal]\nkernel = \"constant\"\nhorizon = 1.5\n";

std::string error_of(const std::string& text) {
  try {
    parse_case_string(text, "f.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

void expect_error(const std::string& text, std::initializer_list<const char*> parts) {
  const std::string e = error_of(text);
  ASSERT_FALSE(e.empty()) << "no error for:\n" << text;
  for (const char* p : parts) EXPECT_NE(e.find(p), std::string::npos) << "'" << p << "' not in: " << e;
}

TEST(CaseFileDamage, ReadsTheLawAndTheDefaults) {
  const CaseConfig c = parse_case_string(case_with("k0 = 2000\nk1 = 10000\nd_c = 0.2\n"), "f.toml");
  const DamageSpec& d = c.materials[0].damage;
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.k0, 2000.0);
  EXPECT_EQ(d.k1, 10000.0);
  EXPECT_EQ(d.d_c, 0.2);
  EXPECT_EQ(d.where.line, 10);
  EXPECT_TRUE(c.has_damage());
  EXPECT_EQ(c.damage.tolerance, 1e-6);
  EXPECT_EQ(c.damage.max_iterations, 500);
  EXPECT_EQ(parse_case_string(case_with("k0 = 0\nk1 = 1\n"), "f.toml").materials[0].damage.d_c, 1.0);
  const CaseConfig s = parse_case_string(
      case_with("k0 = 1\nk1 = 1\n", "[damage]\ntolerance = 1e-4\nmax_iterations = 50\n"), "f.toml");
  EXPECT_EQ(s.damage.tolerance, 1e-4);
  EXPECT_EQ(s.damage.max_iterations, 50);
  EXPECT_EQ(s.damage.solver, DamageSolver::secant) << "the thesis' fixed point by default";
  EXPECT_EQ(parse_case_string(case_with("k0 = 1\nk1 = 1\n", "[damage]\nsolver = \"newton\"\n"), "f.toml")
                .damage.solver,
            DamageSolver::newton);
  expect_error(case_with("k0 = 1\nk1 = 1\n", "[damage]\nsolver = \"newtn\"\n"),
               {"solver", "newtn", "newton"});
}

TEST(CaseFileDamage, MissingAndImpossibleValuesNameTheKey) {
  expect_error(case_with("k0 = 1\n"), {"f.toml:10", "material[1].damage", "k1"});
  expect_error(case_with("k1 = 1\n"), {"material[1].damage", "k0"});
  expect_error(case_with("k0 = 1\nk1 = 0\n"), {"f.toml:12", "'material[1].damage.k1'", "got 0"});
  expect_error(case_with("k0 = -1\nk1 = 1\n"), {"'material[1].damage.k0'", "got -1", ">= 0"});
  expect_error(case_with("k0 = 1\nk1 = 1\nd_c = 0\n"), {"'material[1].damage.d_c'", "(0, 1]", "got 0"});
  expect_error(case_with("k0 = 1\nk1 = 1\nd_c = 1.2\n"), {"'material[1].damage.d_c'", "got 1.2"});
  expect_error(case_with("k0 = 1\nk_1 = 1\n"), {"k_1", "did you mean", "k1"});
}

TEST(CaseFileDamage, DamageTheModelCannotCarryIsRefusedWithTheReason) {
  // An orthotropic material.
  expect_error(R"([mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]
[[material]]
name = "m"
type = "orthotropic"
E1 = 100
E2 = 50
E3 = 50
nu12 = 0.2
nu13 = 0.2
nu23 = 0.2
G12 = 30
G13 = 30
G23 = 20
[material.damage]
k0 = 1
k1 = 1
)",
               {"material[1].damage", "isotropic"});
  // d_c = 1 with [nonlocal]: no residual branch for the non-local model.
  expect_error(case_with("k0 = 1\nk1 = 1\n", kNonlocal), {"f.toml:10", "d_c = 1", "residual branch"});
  // [damage] without a damaged material.
  expect_error(R"([mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]
[[material]]
name = "m"
E = 1
nu = 0.25
[damage]
tolerance = 1e-3
)",
               {"f.toml:10", "no material has a [material.damage]"});
  expect_error(case_with("k0 = 1\nk1 = 1\n", "[damage]\ntolerance = 0\n"), {"'damage.tolerance'", "got 0"});
  expect_error(case_with("k0 = 1\nk1 = 1\n", "[damage]\nmax_iterations = 0\n"), {"'damage.max_iterations'"});
  expect_error(case_with("k0 = 1\nk1 = 1\n", "[damage]\ntolerence = 1e-3\n"), {"did you mean", "tolerance"});
}

TEST(CaseFileDamage, AdaptivityMayFollowTheDamageWithoutFracture) {
  const CaseConfig c =
      parse_case_string(case_with("k0 = 1\nk1 = 1\nd_c = 0.2\n", kNonlocal + "[adaptivity]\n"), "f.toml");
  EXPECT_TRUE(c.adaptivity.enabled);
  EXPECT_FALSE(c.fracture.enabled);
  expect_error(case_with("k0 = 1\nk1 = 1\nd_c = 0.2\n", kNonlocal + "[adaptivity]\npredictor = true\n"),
               {"'adaptivity.predictor'", "[fracture]"});
}

}  // namespace
}  // namespace perimorph::casefile

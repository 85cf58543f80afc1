// [fracture] parsing (THEORY §5): the criterion (s_crit or G_c), the breaking
// rule and its fraction, max_iterations and the defaults. Error files:
// tests/data/bad_cases/fracture_*.toml.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace perimorph::casefile {
namespace {

/// A 2D box with [nonlocal] (lines 1-12), then `fracture` from line 14 on
/// ("[fracture]" on line 13).
std::string case_with(const std::string& fracture) {
  return std::string(R"([mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]
[[material]]
name = "m"
E = 200
nu = 0.25
[nonlocal]
kernel = "constant"
horizon = 1.5
[fracture]
)") + fracture;
}

/// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text) {
  try {
    parse_case_string(text, "f.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(CaseFileFracture, AbsentSectionIsDisabled) {
  std::string text = case_with("");
  text.erase(text.find("[fracture]"));
  const CaseConfig c = parse_case_string(text, "f.toml");
  EXPECT_FALSE(c.fracture.enabled);
}

TEST(CaseFileFracture, CriticalStretchTakesDefaults) {
  const CaseConfig c = parse_case_string(case_with("s_crit = 0.002\n"), "f.toml");
  const FractureSpec& f = c.fracture;
  EXPECT_TRUE(f.enabled);
  EXPECT_EQ(f.s_crit, 0.002);
  EXPECT_EQ(f.G_c, 0.0);
  EXPECT_EQ(f.rule, BreakRule::all);
  EXPECT_EQ(f.fraction, 1.0);
  EXPECT_EQ(f.max_iterations, 10000);
  EXPECT_TRUE(f.intra_cell_failure);
  EXPECT_TRUE(f.no_fail.empty());
  EXPECT_EQ(f.where.describe(), "f.toml:13:1: key 'fracture'");
}

TEST(CaseFileFracture, IntraCellFailureIsABoolean) {
  EXPECT_FALSE(parse_case_string(case_with("s_crit = 0.002\nintra_cell_failure = false\n"), "f.toml")
                   .fracture.intra_cell_failure);
  const std::string msg = error_of(case_with("s_crit = 0.002\nintra_cell_failure = \"no\"\n"));
  EXPECT_TRUE(contains(msg, "f.toml:15:")) << msg;
  EXPECT_TRUE(contains(msg, "fracture.intra_cell_failure")) << msg;
}

TEST(CaseFileFracture, EnergyReleaseRate) {
  const CaseConfig c = parse_case_string(case_with("G_c = 3  # an integer is a number\n"), "f.toml");
  EXPECT_TRUE(c.fracture.enabled);
  EXPECT_EQ(c.fracture.G_c, 3.0);
  EXPECT_EQ(c.fracture.s_crit, 0.0);
  EXPECT_EQ(c.fracture.rule, BreakRule::all);
}

TEST(CaseFileFracture, FractionRuleAndIterations) {
  const CaseConfig c = parse_case_string(
      case_with("s_crit = 1e-3\nrule = \"fraction\"\nfraction = 0.9\nmax_iterations = 7\n"), "f.toml");
  EXPECT_EQ(c.fracture.rule, BreakRule::fraction);
  EXPECT_EQ(c.fracture.fraction, 0.9);
  EXPECT_EQ(c.fracture.max_iterations, 7);
  const CaseConfig one =
      parse_case_string(case_with("G_c = 0.5\nrule = \"fraction\"\nfraction = 1\n"), "f.toml");
  EXPECT_EQ(one.fracture.fraction, 1.0);
}

TEST(CaseFileFracture, ExplicitRuleAll) {
  const CaseConfig c =
      parse_case_string(case_with("s_crit = 0.01\nrule = \"all\"\nmax_iterations = 1\n"), "f.toml");
  EXPECT_EQ(c.fracture.rule, BreakRule::all);
  EXPECT_EQ(c.fracture.max_iterations, 1);
}

TEST(CaseFileFracture, MessagesAreLocated) {
  // Both criteria: the second one given is blamed, and the first is named.
  std::string msg = error_of(case_with("s_crit = 0.01\nG_c = 2\n"));
  EXPECT_EQ(
      msg.rfind("f.toml:15:7: key 'fracture.G_c': cannot be combined with fracture.s_crit (line 14)", 0), 0u)
      << msg;
  msg = error_of(case_with("G_c = 2\ns_crit = 0.01\n"));
  EXPECT_EQ(msg.rfind("f.toml:15:10: key 'fracture.s_crit': cannot be combined with fracture.G_c", 0), 0u)
      << msg;
  // Neither: at the header.
  msg = error_of(case_with("max_iterations = 3\n"));
  EXPECT_EQ(msg.rfind("f.toml:13:1: key 'fracture': gives no failure criterion", 0), 0u) << msg;
  EXPECT_TRUE(contains(msg, "s_crit") && contains(msg, "G_c")) << msg;
  // Values out of range name the value given.
  msg = error_of(case_with("G_c = 0\n"));
  EXPECT_EQ(msg.rfind("f.toml:14:7: key 'fracture.G_c': must be positive", 0), 0u) << msg;
  EXPECT_TRUE(contains(msg, "got 0")) << msg;
  msg = error_of(case_with("s_crit = \"0.01\"\n"));
  EXPECT_TRUE(contains(msg, "key 'fracture.s_crit': expected a number, got a string")) << msg;
  msg = error_of(case_with("s_crit = 0.01\nrule = \"fraction\"\nfraction = 0\n"));
  EXPECT_TRUE(contains(msg, "key 'fracture.fraction': must lie in (0, 1], got 0")) << msg;
  msg = error_of(case_with("s_crit = 0.01\nmax_iterations = 2.0\n"));
  EXPECT_TRUE(contains(msg, "key 'fracture.max_iterations': expected an integer")) << msg;
  EXPECT_TRUE(contains(msg, "write 2")) << msg;
  msg = error_of(case_with("s_crit = 0.01\nmax_iterations = -4\n"));
  EXPECT_TRUE(contains(msg, "must be an integer of at least 1")) << msg;
  EXPECT_TRUE(contains(msg, "got -4")) << msg;
}

TEST(CaseFileFracture, RuleMessages) {
  std::string msg = error_of(case_with("s_crit = 0.01\nrule = \"fractoin\"\nfraction = 0.5\n"));
  EXPECT_EQ(
      msg.rfind("f.toml:15:8: key 'fracture.rule': unknown rule \"fractoin\"; did you mean \"fraction\"?", 0),
      0u)
      << msg;
  EXPECT_TRUE(contains(msg, "allowed: \"all\", \"fraction\"")) << msg;
  // rule = "fraction" without fraction: at the header, saying what fraction is.
  msg = error_of(case_with("s_crit = 0.01\nrule = \"fraction\"\n"));
  EXPECT_EQ(msg.rfind("f.toml:13:1: key 'fracture.fraction': missing required key", 0), 0u) << msg;
  EXPECT_TRUE(contains(msg, "0 < fraction <= 1")) << msg;
  // fraction with rule = "all", given or by default.
  msg = error_of(case_with("s_crit = 0.01\nrule = \"all\"\nfraction = 0.5\n"));
  EXPECT_EQ(msg.rfind("f.toml:16:12: key 'fracture.fraction': applies only with rule = \"fraction\"", 0), 0u)
      << msg;
  EXPECT_TRUE(contains(msg, "rule is \"all\", line 15")) << msg;
  msg = error_of(case_with("s_crit = 0.01\nfraction = 0.5\n"));
  EXPECT_TRUE(contains(msg, "rule defaults to \"all\"")) << msg;
}

TEST(CaseFileFracture, NoFailNamesRegions) {
  std::string text = case_with("s_crit = 0.01\nno_fail = \"grips\"\n");
  text.insert(text.find("[[material]]"), "[[region]]\nname = \"grips\"\nlower = [0, 0]\nupper = [4, 0.5]\n");
  EXPECT_EQ(parse_case_string(text, "f.toml").fracture.no_fail, std::vector<std::string>{"grips"});
  std::string listed = text;
  listed.replace(listed.find("no_fail = \"grips\""), 17, "no_fail = [\"grips\"]");
  EXPECT_EQ(parse_case_string(listed, "f.toml").fracture.no_fail, std::vector<std::string>{"grips"});
  EXPECT_TRUE(
      contains(error_of(case_with("s_crit = 0.01\nno_fail = [\"grips\"]\n")), "this case defines none"));
  std::string twice = text;
  twice.replace(twice.find("no_fail = \"grips\""), 17, "no_fail = [\"grips\", \"grips\"]");
  EXPECT_TRUE(contains(error_of(twice), "listed twice")) << error_of(twice);
}

TEST(CaseFileFracture, NeedsNonlocalAndKnownKeys) {
  std::string text = case_with("s_crit = 0.01\n");
  text.erase(text.find("[nonlocal]"), text.find("[fracture]") - text.find("[nonlocal]"));
  const std::string msg = error_of(text);
  EXPECT_EQ(msg.rfind("f.toml:10:1: key 'fracture': bond failure needs a [nonlocal] section", 0), 0u) << msg;
  EXPECT_TRUE(contains(error_of(case_with("s_crit = 0.01\nmax_iteration = 5\n")),
                       "unknown key 'fracture.max_iteration'; did you mean 'fracture.max_iterations'?"));
  // A misspelt section name is caught at the top level.
  std::string misspelt = case_with("s_crit = 0.01\n");
  misspelt.replace(misspelt.find("[fracture]"), 10, "[fractur]");
  EXPECT_TRUE(contains(error_of(misspelt), "unknown key 'fractur'; did you mean 'fracture'?"))
      << error_of(misspelt);
}

}  // namespace
}  // namespace perimorph::casefile

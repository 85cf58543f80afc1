// [adaptivity] parsing (THEORY §5, docs/case-file.md): the defaults, every
// key, and the errors a user can act on (unknown key, bad value, theta
// without the predictor, a case that cannot grow α).

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace perimorph::casefile {
namespace {

/// A 2D box with [nonlocal] and [fracture] (lines 1-14), then `rest`.
std::string case_with(const std::string& rest, const std::string& fracture = "[fracture]\ns_crit = 0.01\n") {
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
)") + fracture +
         rest;
}

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

TEST(CaseFileAdaptivity, AbsentSectionIsDisabled) {
  EXPECT_FALSE(parse_case_string(case_with(""), "f.toml").adaptivity.enabled);
}

TEST(CaseFileAdaptivity, DefaultsAreTheThesisRule) {
  const AdaptivitySpec a = parse_case_string(case_with("[adaptivity]\n"), "f.toml").adaptivity;
  EXPECT_TRUE(a.enabled);
  EXPECT_LT(a.core, 0.0);  // the horizon, resolved by the run
  EXPECT_LT(a.transition, 0.0);
  EXPECT_EQ(a.profile, AlphaProfile::cubic);
  EXPECT_EQ(a.update, AdaptivityUpdate::increment);
  EXPECT_TRUE(a.redo);
  EXPECT_FALSE(a.predictor);
}

TEST(CaseFileAdaptivity, EveryKeyIsRead) {
  const AdaptivitySpec a =
      parse_case_string(case_with("[adaptivity]\ncore = 2.0\ntransition = 0.5\nprofile = \"linear\"\n"
                                  "update = \"iteration\"\nredo = false\npredictor = true\ntheta = 0.7\n"),
                        "f.toml")
          .adaptivity;
  EXPECT_EQ(a.core, 2.0);
  EXPECT_EQ(a.transition, 0.5);
  EXPECT_EQ(a.profile, AlphaProfile::linear);
  EXPECT_EQ(a.update, AdaptivityUpdate::iteration);
  EXPECT_FALSE(a.redo);
  EXPECT_TRUE(a.predictor);
  EXPECT_EQ(a.theta, 0.7);
}

TEST(CaseFileAdaptivity, ErrorsNameTheKeyAndWhatIsAllowed) {
  const std::string unknown = error_of(case_with("[adaptivity]\npredicter = true\n"));
  EXPECT_TRUE(contains(unknown, "f.toml:16")) << unknown;
  EXPECT_TRUE(contains(unknown, "predictor")) << unknown;
  const std::string update = error_of(case_with("[adaptivity]\nupdate = \"iterations\"\n"));
  EXPECT_TRUE(contains(update, "did you mean \"iteration\"")) << update;
  const std::string theta = error_of(case_with("[adaptivity]\ntheta = 0.5\n"));
  EXPECT_TRUE(contains(theta, "predictor = true")) << theta;
  const std::string range = error_of(case_with("[adaptivity]\npredictor = true\ntheta = 1.5\n"));
  EXPECT_TRUE(contains(range, "(0, 1]")) << range;
  const std::string core = error_of(case_with("[adaptivity]\ncore = -1\n"));
  EXPECT_TRUE(contains(core, "length >= 0")) << core;
  const std::string no_fracture = error_of(case_with("[adaptivity]\n", ""));
  EXPECT_TRUE(contains(no_fracture, "no [fracture]")) << no_fracture;
  const std::string constant = error_of(case_with("[alpha]\nvalue = 0.5\n[adaptivity]\n"));
  EXPECT_TRUE(contains(constant, "cannot grow")) << constant;
}

}  // namespace
}  // namespace perimorph::casefile

// PETSc's options database (la/petsc_session.hpp): unused_options lists the
// options nothing has read (a misspelt one, one for a solver not in use),
// with their values, and leaves out -options_left (PETSc reads it at the end)
// and options the solver has read.

#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/linear_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace perimorph {
namespace {

bool listed(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(LaPetscSession, UnusedOptionsListsWhatNothingRead) {
  la::set_option("-ksp_typo_test", "3");
  la::set_option("-options_left");
  la::set_option("-ksp_rtol", "1e-7");
  const la::LinearSolver solver(1e-10, 100);  // reads the KSP's options, -ksp_rtol among them
  const auto unused = la::unused_options();
  EXPECT_TRUE(listed(unused, "-ksp_typo_test 3"));
  EXPECT_FALSE(listed(unused, "-options_left"));
  EXPECT_FALSE(std::any_of(unused.begin(), unused.end(),
                           [](const std::string& s) { return s.rfind("-ksp_rtol", 0) == 0; }));
  for (const char* name : {"-ksp_typo_test", "-options_left", "-ksp_rtol"}) la::clear_option(name);
}

}  // namespace
}  // namespace perimorph

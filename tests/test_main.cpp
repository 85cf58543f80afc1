// GoogleTest entry point. PETSc is initialized once for the whole suite (the
// la/ tests and every test that solves) and finalized after all tests ran.
#include "perimorph/la/petsc_session.hpp"

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  perimorph::la::PetscSession petsc(argc, argv);
  return RUN_ALL_TESTS();
}

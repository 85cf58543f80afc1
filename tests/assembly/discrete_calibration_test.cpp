// Discrete calibration (issue 3, item 7): after scaling ĉ by the factor, the
// lattice bulk tensor matches C₀ (exactly in 1D, in the least-squares sense in
// 2D/3D), and the factor corrects the 1D modulus of a fully non-local bar.

#include "perimorph/assembly/discrete_calibration.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace perimorph {
namespace {

TEST(AssemblyDiscreteCalibration, FactorMakesTheLatticeBulkTensorMatchC0) {
  for (int dim : {1, 2, 3}) {
    mesh::StructuredLayout layout;
    layout.spacing = Vec3::Constant(0.125);
    peridynamics::Micromodulus k{
        dim == 1 ? peridynamics::KernelShape::constant : peridynamics::KernelShape::exponential,
        0.5,
        0.1,
        1.0,
        {}};
    const auto cal = peridynamics::calibrate_isotropic(k, dim, PlaneMode::strain, 1.0);
    k.scale = cal.scale;
    Eigen::MatrixXd C0 = Eigen::MatrixXd::Zero(fem::voigt_size(dim), fem::voigt_size(dim));
    if (dim == 1)
      C0(0, 0) = 1.0;
    else
      C0 = fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{1.0, 0.25}), dim,
                                 PlaneMode::strain);
    const int n = dim == 3 ? 2 : 4;
    const double f = assembly::discrete_calibration_factor(layout, dim, n, k, C0);
    const Eigen::MatrixXd before = assembly::lattice_bulk_tensor(layout, dim, n, k);
    k.scale *= f;
    const Eigen::MatrixXd after = assembly::lattice_bulk_tensor(layout, dim, n, k);
    const double err_before = (before - C0).norm() / C0.norm(), err_after = (after - C0).norm() / C0.norm();
    std::printf("%dD: factor %.8f, |D - C0|/|C0| %.3e -> %.3e\n", dim, f, err_before, err_after);
    EXPECT_NE(f, 1.0);
    EXPECT_LT(err_after, err_before);
    if (dim == 1) {
      EXPECT_NEAR(after(0, 0), 1.0, 1e-13);
    }
  }
}

TEST(AssemblyDiscreteCalibration, FullyNonlocalBarHasTheLocalModulus) {
  // A 1D bar, α ≡ 1, constant kernel, h = δ/4: the discretely calibrated bar
  // carries σ = E₀ ε in its interior (the continuum calibration is 10% off here).
  for (auto rule : {casefile::CalibrationRule::continuum, casefile::CalibrationRule::discrete}) {
    auto c = testing::box_case(1, {160, 1, 1}, Vec3(20.0, 0, 0), 1.0, 0.0);
    c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
    testing::add_nonlocal(c, casefile::KernelKind::constant, 0.5, 0.0, 4);
    c.nonlocal.calibration = rule;
    c.alpha.regions = {};
    casefile::AlphaRegionSpec r;
    r.shape = casefile::AlphaShapeKind::interval;
    r.lower = Vec3(5.0, 0, 0);
    r.upper = Vec3(15.0, 0, 0);
    r.transition = 2.0;
    c.alpha.regions = {r};
    casefile::DirichletSpec left, right;
    left.set = "xmin";
    left.constrained[0] = true;
    right.set = "xmax";
    right.constrained[0] = true;
    right.value = Vec3(0.02, 0, 0);
    c.dirichlet = {left, right};
    const auto model = setup::build_discretization(c);
    const auto dir = (std::filesystem::temp_directory_path() / "perimorph_discrete_cal").string();
    const auto run = run::run_static(model, {dir, true});
    const double stiffness = run.reactions[1].x() / 1e-3;  // σ / ε̄ of the bar
    std::printf("%s calibration: effective modulus %.6f\n",
                rule == casefile::CalibrationRule::discrete ? "discrete" : "continuum", stiffness);
    if (rule == casefile::CalibrationRule::discrete) {
      EXPECT_NEAR(stiffness, 1.0, 1e-4);
    } else {
      EXPECT_GT(std::abs(stiffness - 1.0), 1e-2);
    }
  }
}

}  // namespace
}  // namespace perimorph

// Secant (fixed point) against Newton through PETSc SNES for the local damage
// solve of an increment (issue 15, THEORY §6; docs/benchmarks/damage_solver.md).
//
// The model: a case with a damageable material and no [nonlocal] (the B8
// specimen's local damage model alone: examples/b8_damage_handover_3d/
// local_alone.toml), on a mesh and a load path given here. Each increment
// starts from the last converged one (u, d_prev) and is solved twice:
//
//   secant   what perimorph runs (evolution/local_damage.cpp, thesis fig. 3.22):
//            solve with the secant stiffness (1 − d) C₀, update d at every
//            point, again until max Δd ≤ the case's [damage] tolerance;
//            linear solves = updates + 1.
//   newton   F(u) = K_sec(d(u)) u − λ f = 0 with d(u) = min(d_c, max(d_prev,
//            (Y(ε(u)) − k0)/k1)) (3.41), the consistent tangent of
//            fem::damage_tangent, SNES newtonls (backtracking line search),
//            ||F|| ≤ 1e-6 ||F(u₀)|| (stricter than the secant's
//            stop: its last solve is in equilibrium with d off by ≤ the tolerance); linear solves = Newton
//            steps.
//
// Both solve each linear system with LU (the same factorization cost per
// solve), so the count of solves is the cost to compare; the wall and CPU
// time of each method are printed beside it (assembly included: each
// iteration of either method reassembles K here).
//
//   damage_solver_bench CASE nx ny nz INCREMENTS [d_c]   → JSON on stdout
//
// d_c, if given, overrides the material's (the hybrid's d_c = 0.2: the
// hardening branch the hybrid sees before the handover).

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/damage_law.hpp"
#include "perimorph/la/nonlinear_solver.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/damage_model.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

namespace {

using namespace perimorph;

struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  }
  double cpu_s() const { return static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

/// d at every local point after the step from `d_prev` to the strain of `u`
/// (3.41); `loading` (if given) marks the points on the loading branch.
std::vector<double> damage_at(const setup::Discretization& model, std::span<const double> u,
                              std::span<const double> d_prev, std::vector<char>* loading = nullptr) {
  const setup::DamageModel& dm = *model.damage;
  const int npts = dm.points_per_cell;
  const int nv = fem::voigt_size(model.dim());
  std::vector<double> d(d_prev.begin(), d_prev.end()), strain(static_cast<std::size_t>(npts * nv)),
      volume(static_cast<std::size_t>(npts));
  if (loading) loading->assign(d.size(), 0);
  const auto space = model.local_space();
  for (Index c = 0; c < model.mesh.num_cells(); ++c) {
    const int law = dm.law_of(c);
    if (law < 0) continue;
    const auto& L = dm.laws[static_cast<std::size_t>(law)];
    const double* C0 = dm.C0[static_cast<std::size_t>(law)].data();
    assembly::strains_at_points(space, c, u, strain, volume);
    for (int q = 0; q < npts; ++q) {
      const auto k = static_cast<std::size_t>(c * npts + q);
      const double Y = fem::damage_force(C0, strain.data() + q * nv, nv);
      d[k] = fem::updated_damage(L, Y, d_prev[k]);
      if (loading) (*loading)[k] = fem::damage_loading(L, Y, d_prev[k]) ? 1 : 0;
    }
  }
  return d;
}

/// Reaction along x on the dofs pulled in +x: Σ (K u)_i over prescribed x dofs with a positive value.
double reaction(const setup::Discretization& model, const setup::DirichletData& bc, la::Matrix& K,
                std::span<const double> u) {
  la::Vector uv(static_cast<Index>(u.size()), 1), f(static_cast<Index>(u.size()), 1);
  uv.assign(u);
  K.mult(uv, f);
  const auto fv = f.to_std();
  double r = 0.0;
  for (std::size_t i = 0; i < bc.dofs.size(); ++i)
    if (bc.values[i] > 0 && bc.dofs[i] % model.dim() == 0) r += fv[static_cast<std::size_t>(bc.dofs[i])];
  return r;
}

struct IncrementResult {
  int solves = 0;
  double reaction = 0.0, max_d = 0.0;
  bool converged = true;
  std::string reason;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    fmt::print(stderr, "usage: {} CASE nx ny nz INCREMENTS [d_c]\n", argv[0]);
    return 2;
  }
  la::PetscSession petsc;
  auto config = casefile::parse_case_file(argv[1]);
  config.mesh.box.cells = {static_cast<Index>(std::stoi(argv[2])), static_cast<Index>(std::stoi(argv[3])),
                           static_cast<Index>(std::stoi(argv[4]))};
  const int n = std::stoi(argv[5]);
  config.loading.factors.clear();
  for (int i = 1; i <= n; ++i) config.loading.factors.push_back(static_cast<double>(i) / n);
  if (argc > 6)
    for (auto& m : config.materials)
      if (m.damage.enabled) m.damage.d_c = std::stod(argv[6]);
  config.solver.petsc_options = "";
  la::add_options("-ksp_type preonly -pc_type lu");
  const setup::Discretization model = setup::build_discretization(config);
  PERIMORPH_ASSERT(model.damage.has_value() && !model.nonlocal, "a damageable case without [nonlocal]");
  const setup::DamageModel& dm = *model.damage;
  const int nv = fem::voigt_size(model.dim());
  const int npts = dm.points_per_cell;
  const double tol = config.damage.tolerance;
  const setup::DirichletData bc = setup::build_dirichlet(model);
  const std::vector<double> F = setup::build_external_force(model);
  const Index ndofs = model.dofmap.num_dofs();
  const auto space = model.local_space();
  la::Matrix Ks(assembly::build_sparsity(model.dofmap)), J(assembly::build_sparsity(model.dofmap));

  // ---------------------------------------------------------------- secant
  std::vector<IncrementResult> secant(static_cast<std::size_t>(n)), newton(static_cast<std::size_t>(n));
  Clock secant_clock;
  {
    std::vector<double> d(static_cast<std::size_t>(model.mesh.num_cells() * npts), 0.0);
    la::Vector u(ndofs, model.dim());
    for (int i = 0; i < n; ++i) {
      auto& r = secant[static_cast<std::size_t>(i)];
      for (int it = 0;; ++it) {
        system::ConstrainedSystem sys(model, system::assemble_stiffness(model, nullptr, d).K, bc, F);
        sys.attach_solver();
        sys.solve(config.loading.factors[static_cast<std::size_t>(i)], u);
        ++r.solves;
        const auto uu = u.to_std();
        const auto d_new = damage_at(model, uu, d);
        double change = 0.0;
        for (std::size_t k = 0; k < d.size(); ++k) change = std::max(change, d_new[k] - d[k]);
        if (change <= tol || it >= config.damage.max_iterations) {
          r.converged = change <= tol;
          r.reaction = reaction(model, bc, sys.K(), uu);
          r.max_d = *std::max_element(d.begin(), d.end());
          break;
        }
        d = d_new;
      }
    }
  }
  const double secant_wall = secant_clock.wall_s(), secant_cpu = secant_clock.cpu_s();

  // ---------------------------------------------------------------- newton
  Clock newton_clock;
  {
    std::vector<double> d_prev(static_cast<std::size_t>(model.mesh.num_cells() * npts), 0.0);
    double lambda = 0.0;
    auto assemble_secant = [&](std::span<const double> u, la::Matrix& K) {
      const auto d = damage_at(model, u, d_prev);
      assembly::assemble_elasticity(space, setup::damaged_stiffness(model.stiffness, dm, d), K);
    };
    auto residual = [&](std::span<const double> u, std::span<double> r) {
      Ks.zero_entries();
      assemble_secant(u, Ks);
      Ks.finalize();
      la::Vector uv(ndofs, 1), f(ndofs, 1);
      uv.assign(u);
      Ks.mult(uv, f);
      const auto fv = f.to_std();
      for (std::size_t k = 0; k < r.size(); ++k) r[k] = fv[k] - lambda * F[k];
      for (std::size_t k = 0; k < bc.dofs.size(); ++k) {
        const auto dof = static_cast<std::size_t>(bc.dofs[k]);
        r[dof] = u[dof] - lambda * bc.values[k];
      }
    };
    auto jacobian = [&](std::span<const double> u, la::Matrix& Jm) {
      std::vector<char> loading;
      const auto d = damage_at(model, u, d_prev, &loading);
      fem::ConstitutiveField C = setup::damaged_stiffness(model.stiffness, dm, d);
      std::vector<double> strain(static_cast<std::size_t>(npts * nv)), volume(static_cast<std::size_t>(npts));
      std::vector<Eigen::MatrixXd> T(static_cast<std::size_t>(npts));
      for (Index c = 0; c < model.mesh.num_cells(); ++c) {
        const int law = dm.law_of(c);
        if (law < 0) continue;
        bool any = false;
        for (int q = 0; q < npts; ++q) any = any || loading[static_cast<std::size_t>(c * npts + q)];
        if (!any) continue;
        assembly::strains_at_points(space, c, u, strain, volume);
        for (int q = 0; q < npts; ++q) {
          auto& t = T[static_cast<std::size_t>(q)];
          t.resize(nv, nv);
          fem::damage_tangent(dm.laws[static_cast<std::size_t>(law)],
                              dm.C0[static_cast<std::size_t>(law)].data(), strain.data() + q * nv,
                              d_prev[static_cast<std::size_t>(c * npts + q)], nv, t.data());
          // damage_tangent is the full dσ/dε of the damageable law; add what
          // the field holds beyond (1 − d) C₀ (none for one isotropic material).
          t += C.matrix(c, q) -
               (1.0 - d[static_cast<std::size_t>(c * npts + q)]) * dm.C0[static_cast<std::size_t>(law)];
        }
        C.set_cell_points(c, T);
      }
      assembly::assemble_elasticity(space, C, Jm);
      Jm.finalize();
      la::Vector x(ndofs, 1), rhs(ndofs, 1);
      Jm.eliminate_dirichlet(bc.dofs, x, rhs);
    };
    la::NonlinearSolver snes(J, residual, jacobian, 1e-6, 1e-300, 100, "damage_");
    la::Vector u(ndofs, model.dim());
    for (int i = 0; i < n; ++i) {
      lambda = config.loading.factors[static_cast<std::size_t>(i)];
      auto uu = u.to_std();
      for (std::size_t k = 0; k < bc.dofs.size(); ++k)
        uu[static_cast<std::size_t>(bc.dofs[k])] = lambda * bc.values[k];
      u.assign(uu);
      const auto rep = snes.solve(u);
      auto& r = newton[static_cast<std::size_t>(i)];
      r.solves = rep.linear_solves;
      r.converged = rep.converged;
      r.reason = rep.reason;
      uu = u.to_std();
      d_prev = damage_at(model, uu, d_prev);
      Ks.zero_entries();
      assembly::assemble_elasticity(space, setup::damaged_stiffness(model.stiffness, dm, d_prev), Ks);
      Ks.finalize();
      r.reaction = reaction(model, bc, Ks, uu);
      r.max_d = *std::max_element(d_prev.begin(), d_prev.end());
    }
  }
  const double newton_wall = newton_clock.wall_s(), newton_cpu = newton_clock.cpu_s();

  fmt::print(
      "{{\"case\": \"{}\", \"cells\": [{}, {}, {}], \"increments\": {}, \"d_c\": {}, \"tolerance\": {},\n",
      argv[1], argv[2], argv[3], argv[4], n, dm.laws[0].d_c, tol);
  fmt::print(
      " \"secant\": {{\"wall_s\": {:.3f}, \"cpu_s\": {:.3f}}}, \"newton\": {{\"wall_s\": {:.3f}, \"cpu_s\": "
      "{:.3f}}},\n",
      secant_wall, secant_cpu, newton_wall, newton_cpu);
  fmt::print(" \"increments_table\": [\n");
  for (int i = 0; i < n; ++i) {
    const auto& s = secant[static_cast<std::size_t>(i)];
    const auto& w = newton[static_cast<std::size_t>(i)];
    fmt::print(
        "  {{\"increment\": {}, \"secant_solves\": {}, \"secant_converged\": {}, \"secant_reaction\": "
        "{:.10g}, "
        "\"secant_max_d\": {:.6g}, \"newton_solves\": {}, \"newton_converged\": {}, \"newton_reaction\": "
        "{:.10g}, "
        "\"newton_max_d\": {:.6g}, \"newton_reason\": \"{}\"}}{}\n",
        i + 1, s.solves, s.converged, s.reaction, s.max_d, w.solves, w.converged, w.reaction, w.max_d,
        w.reason, i + 1 < n ? "," : "");
  }
  fmt::print(" ]}}\n");
  return 0;
}

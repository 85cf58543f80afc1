#include "perimorph/evolution/damage_newton.hpp"

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/damage_law.hpp"
#include "perimorph/la/nonlinear_solver.hpp"
#include "perimorph/setup/discretization.hpp"

#include <Eigen/Core>

namespace perimorph::evolution {

namespace {

/// Subtracts each block from J on the free rows and columns only (a
/// prescribed index becomes −1, which Matrix::add skips).
class FreeSubtractInserter final : public assembly::MatrixInserter {
 public:
  FreeSubtractInserter(la::Matrix& J, const system::ConstrainedSystem& system) : J_(J), system_(system) {}
  void add(std::span<const Index> rows, std::span<const Index> /*cols*/,
           std::span<const double> values) override {
    index_.assign(rows.begin(), rows.end());
    for (Index& i : index_)
      if (system_.prescribed(i)) i = -1;
    negative_.resize(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) negative_[k] = -values[k];
    J_.add(index_, index_, negative_);
  }

 private:
  la::Matrix& J_;
  const system::ConstrainedSystem& system_;
  std::vector<Index> index_;
  std::vector<double> negative_;
};

/// Per local point: (d(u) − h) C₀, plus (C₀ε)(C₀ε)ᵀ/k1 at the loading points
/// when `tangent`; `cells` marks the cells where that is not zero. Only the
/// cells flagged in `mine` are looked at (all if empty): on several
/// processes, the cells with a node this process owns, which are all the
/// cells its rows sum.
fem::ConstitutiveField damage_increment_field(const setup::Discretization& disc, std::span<const double> u,
                                              std::span<const double> history, bool tangent,
                                              std::span<const char> mine, std::vector<char>& cells) {
  const setup::DamageModel& dm = *disc.damage;
  const int npts = dm.points_per_cell;
  const int nv = fem::voigt_size(disc.dim());
  const Index ncells = disc.mesh.num_cells();
  fem::ConstitutiveField field(disc.dim(), ncells, npts);
  const int zero = field.add_tensor(Eigen::MatrixXd::Zero(nv, nv));
  cells.assign(static_cast<std::size_t>(ncells), 0);
  const assembly::LocalSpace space = disc.local_space();
  std::vector<double> strain(static_cast<std::size_t>(npts * nv)), volume(static_cast<std::size_t>(npts));
  std::vector<Eigen::MatrixXd> T(static_cast<std::size_t>(npts));
  for (Index c = 0; c < ncells; ++c) {
    field.set_cell(c, zero);
    if (!mine.empty() && mine[static_cast<std::size_t>(c)] == 0) continue;
    const int law = dm.law_of(c);
    if (law < 0 || !disc.has_local_stiffness(c)) continue;
    const fem::DamageLaw& L = dm.laws[static_cast<std::size_t>(law)];
    const Eigen::MatrixXd& C0 = dm.C0[static_cast<std::size_t>(law)];
    assembly::strains_at_points(space, c, u, strain, volume);
    bool any = false;
    for (int q = 0; q < npts; ++q) {
      const double h = setup::DamageModel::at(history, c, q, npts);
      const double* eps = strain.data() + q * nv;
      const double Y = fem::damage_force(C0.data(), eps, nv);
      const double d = fem::updated_damage(L, Y, h);
      auto& t = T[static_cast<std::size_t>(q)];
      t = (d - h) * C0;
      if (tangent && fem::damage_loading(L, Y, h)) {
        const Eigen::VectorXd Ce = C0 * Eigen::Map<const Eigen::VectorXd>(eps, nv);
        t += Ce * Ce.transpose() / L.k1;
      }
      any = any || d > h || (tangent && fem::damage_loading(L, Y, h));
    }
    if (!any) continue;
    field.set_cell_points(c, T);
    cells[static_cast<std::size_t>(c)] = 1;
  }
  return field;
}

}  // namespace

DamageNewtonReport solve_damage_newton(const setup::Discretization& disc,
                                       const system::ConstrainedSystem& system,
                                       std::span<const double> history, double lambda,
                                       std::vector<double>& u) {
  const assembly::LocalSpace space = disc.local_space();
  // Laid out as the system (spread over the processes of a distributed run:
  // each process keeps its own rows of what every process assembles whole).
  const auto& distribution = system.A().distribution();
  const assembly::SparsityPattern local_pattern = assembly::build_sparsity(
      disc.dofmap, nullptr, [&](Index node) { return !distribution || distribution->owns(node); });
  la::Matrix local = distribution ? la::Matrix(local_pattern, distribution)
                                  : la::Matrix(local_pattern);  // K_Δ of the residual
  la::Matrix J = system.A().duplicate();
  la::Vector uv = system.make_vector(), Au = system.make_vector(), fcorr = system.make_vector();
  std::vector<char> cells, mine;
  if (distribution) {
    mine.assign(static_cast<std::size_t>(disc.mesh.num_cells()), 0);
    for (Index c = 0; c < disc.mesh.num_cells(); ++c)
      for (Index node : disc.dofmap.cell_nodes(c))
        if (distribution->owns(node)) mine[static_cast<std::size_t>(c)] = 1;
  }
  // Each process computes its own entries of r (NonlinearSolver): A u, b and
  // K_Δ u at the dofs it owns, u where its cells need it.
  const la::OwnedDofs& owned = system.owned_dofs();
  const std::vector<double> b = system.rhs_unit().at_owned(owned);  // fixed during the solve
  auto residual = [&](std::span<const double> x, std::span<double> r) {
    uv.assign_replicated(x);
    system.A().mult(uv, Au);
    local.zero_entries();
    const auto field = damage_increment_field(disc, x, history, false, mine, cells);
    assembly::assemble_elasticity(space, field, local,
                                  [&](Index c) { return cells[static_cast<std::size_t>(c)] != 0; });
    local.finalize();
    local.mult(uv, fcorr);
    const auto a = Au.at_owned(owned), f = fcorr.at_owned(owned);
    for (std::size_t j = 0; j < owned.size(); ++j)
      r[j] = a[j] - lambda * b[j] - (system.prescribed(owned.dof(j)) ? 0.0 : f[j]);
  };
  auto jacobian = [&](std::span<const double> x, la::Matrix& Jm) {
    Jm.copy_values_from(system.A());
    const auto field = damage_increment_field(disc, x, history, true, mine, cells);
    FreeSubtractInserter subtract(Jm, system);
    assembly::assemble_elasticity(space, field, subtract,
                                  [&](Index c) { return cells[static_cast<std::size_t>(c)] != 0; });
  };
  // Quadratic convergence needs a handful of steps; more means a kink of d(u)
  // (the cap at d_c, a point leaving the loading branch) is in the way.
  // Each step by GMRES with the run's preconditioner as it stands (with
  // -ksp_reuse_preconditioner, the GAMG of an earlier A(h): no set-up here).
  la::NonlinearSolver snes(J, residual, jacobian, 1e-6, 1e-300, 12, "damage_", system.solver());
  snes.read_only(setup::nodes_read(disc), disc.dim());
  PERIMORPH_ASSERT(snes.owned_dofs().size() == owned.size(), "the Newton solver's rows are the system's");
  la::Vector x = system.make_vector();
  x.assign_replicated(u);
  const la::NonlinearReport rep = snes.solve(x);
  DamageNewtonReport out{rep.converged, rep.iterations, rep.reason};
  if (rep.converged) u = x.to_replicated();
  return out;
}

}  // namespace perimorph::evolution

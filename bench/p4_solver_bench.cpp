// P4 solver candidates (issue 16 item 3): the elastic solve of the P4 cube
// (bench/run_p4_bench.py writes the case: DG0, α ≡ 1, pmb kernel, δ = 3.015 h,
// three layers prescribed at each x face) by
//   assembled    the run's system: K assembled, Dirichlet eliminated, CG + GAMG on A;
//   matrix-free  A applied without a matrix (assembly/structured_nonlocal_operator.hpp:
//                one 3 × 3 block per grid offset), CG preconditioned by GAMG built on
//                the same problem with a short horizon (R h, the kernel calibrated
//                for it, so its continuum limit is the same elasticity): a matrix with
//                a small stencil whose symbol matches the non-local one at low
//                frequencies.
// Prints one JSON object: times per phase (wall and CPU), Krylov iterations, the
// true relative residual, peak RSS; with --check, also the assembled operator's
// product and solution against the matrix-free ones (relative differences).
//
//   p4_solver_bench CASE assembled|matrix-free [--short R] [--check] [--write-solution FILE]
//
// --write-solution (matrix-free): the displacement per cell (cell
// c = i + n0 (j + n1 k), 3 components), raw doubles, for an independent check.
//
// PETSc options from PETSC_OPTIONS (e.g. "-ksp_monitor", "-log_view").

#include "perimorph/assembly/structured_nonlocal_operator.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/shell_matrix.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/matrix_free_stiffness.hpp"
#include "perimorph/system/stiffness.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

using namespace perimorph;

namespace {

struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  /// (wall, CPU) seconds since the last lap.
  std::pair<double, double> lap() {
    const auto w = std::chrono::steady_clock::now();
    const std::clock_t c = std::clock();
    const std::pair<double, double> out{std::chrono::duration<double>(w - wall).count(),
                                        static_cast<double>(c - cpu) / CLOCKS_PER_SEC};
    wall = w;
    cpu = c;
    return out;
  }
};

double peak_rss_mb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_maxrss) / 1024.0;
}

std::string phase(const char* name, std::pair<double, double> t) {
  return fmt::format("\"{}\": {{\"wall\": {:.4f}, \"cpu\": {:.4f}}}", name, t.first, t.second);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: {} CASE assembled|matrix-free [--short R] [--check]\n", argv[0]);
    return 2;
  }
  const std::string case_path = argv[1], variant = argv[2];
  double short_factor = 1.5;
  bool check = false;
  std::string solution_path;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--short" && a + 1 < argc) short_factor = std::stod(argv[++a]);
    if (arg == "--check") check = true;
    if (arg == "--write-solution" && a + 1 < argc) solution_path = argv[++a];
  }
  la::PetscSession petsc;
  const casefile::CaseConfig config = casefile::parse_case_file(case_path);
  const double h =
      (config.mesh.box.upper.x() - config.mesh.box.lower.x()) / static_cast<double>(config.mesh.box.cells[0]);
  std::vector<std::string> out{fmt::format("\"case\": \"{}\"", case_path),
                               fmt::format("\"variant\": \"{}\"", variant),
                               fmt::format("\"n\": {}", config.mesh.box.cells[0])};
  Clock clock;
  if (variant == "assembled") {
    const auto model = setup::build_discretization(config);
    out.push_back(phase("discretization", clock.lap()));
    system::ConstrainedSystem sys(model, system::assemble_stiffness(model).K, setup::build_dirichlet(model),
                                  setup::build_external_force(model));
    sys.attach_solver();
    out.push_back(phase("assembly", clock.lap()));
    la::Vector u(model.dofmap.num_dofs(), 3);
    const la::SolveReport rep = sys.solve(1.0, u);
    out.push_back(phase("solve", clock.lap()));
    out.push_back(
        fmt::format("\"dofs\": {}, \"iterations\": {}, \"relative_residual\": {:.3e}, \"nonzeros\": {:.0f}",
                    model.dofmap.num_dofs(), rep.iterations, rep.relative_residual, sys.A().nonzeros()));
  } else if (variant == "matrix-free") {
    // The preconditioner: the same operator with a short horizon (R h, the
    // kernel calibrated for it), assembled on its own pattern. The dof map
    // and the Dirichlet data from the short model (its cell graph is small);
    // both operators' blocks from a patch of the grid (system/matrix_free_stiffness.hpp).
    casefile::CaseConfig short_config = config;
    short_config.nonlocal.horizon = short_factor * h;
    const auto model = setup::build_discretization(short_config);
    out.push_back(phase("discretization", clock.lap()));
    assembly::OffsetBlocks blocks = system::grid_offset_blocks(config, *model.mesh.structure);
    assembly::OffsetBlocks short_blocks = system::grid_offset_blocks(short_config, *model.mesh.structure);
    const std::size_t offsets = blocks.offsets.size();
    out.push_back(phase("offset_blocks", clock.lap()));
    const auto& layout = *model.mesh.structure;
    std::vector<Index> node_of_cell(static_cast<std::size_t>(model.mesh.num_cells()));
    for (Index c = 0; c < model.mesh.num_cells(); ++c)
      node_of_cell[static_cast<std::size_t>(c)] = model.dofmap.cell_nodes(c)[0];
    const assembly::StructuredNonlocalOperator K(std::move(blocks), layout.cells, node_of_cell);
    const assembly::StructuredNonlocalOperator K_short(std::move(short_blocks), layout.cells, node_of_cell);
    const setup::DirichletData bc = setup::build_dirichlet(model);
    const std::vector<double> force = setup::build_external_force(model);
    la::Matrix P(K_short.sparsity());
    K_short.assemble(P);
    P.finalize();
    {
      la::Vector g(model.dofmap.num_dofs(), 3), scratch(model.dofmap.num_dofs(), 3);
      P.eliminate_dirichlet(bc.dofs, g, scratch);
    }
    P = P.without_zero_blocks();  // the eliminated rows and columns
    P.set_spd();
    out.push_back(phase("preconditioner_matrix", clock.lap()));
    const Index n = model.dofmap.num_dofs();
    std::vector<char> fixed(static_cast<std::size_t>(n), 0);
    for (Index d : bc.dofs) fixed[static_cast<std::size_t>(d)] = 1;
    // A x: K on the free rows and columns, the identity on the prescribed ones
    // (la::Matrix::eliminate_dirichlet's convention, diagonal 1).
    std::vector<double> masked(static_cast<std::size_t>(n));
    la::ShellMatrix A(n, 3, [&](std::span<const double> x, std::span<double> y) {
      for (std::size_t k = 0; k < masked.size(); ++k) masked[k] = fixed[k] ? 0.0 : x[k];
      K.apply(masked, y);
      for (std::size_t k = 0; k < masked.size(); ++k)
        if (fixed[k]) y[k] = x[k];
    });
    // b = F − K g on the free rows, g on the prescribed ones.
    std::vector<double> g(static_cast<std::size_t>(n), 0.0), Kg(static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < bc.dofs.size(); ++k) g[static_cast<std::size_t>(bc.dofs[k])] = bc.values[k];
    K.apply(g, Kg);
    std::vector<double> b(static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < b.size(); ++k) b[k] = fixed[k] ? g[k] : force[k] - Kg[k];
    la::Vector rhs(n, 3), u(n, 3);
    rhs.assign(b);
    // The prescribed rows are the identity, decoupled: starting from g there,
    // CG leaves them exact (a residual relative to ||b|| would allow them an
    // error of the stiffness' scale).
    u.assign(g);
    la::LinearSolver solver(config.solver.rtol, config.solver.max_iterations);
    solver.set_operators(A, P, model.dofmap.node_coordinate_on(model.mesh), 3);
    out.push_back(phase("operator", clock.lap()));
    const la::SolveReport rep = solver.solve(rhs, u);
    out.push_back(phase("solve", clock.lap()));
    {  // one product, timed alone
      la::Vector y(n, 3);
      for (int r = 0; r < 3; ++r) A.mult(u, y);
      const auto t = clock.lap();
      out.push_back(phase("apply", {t.first / 3, t.second / 3}));
    }
    if (!solution_path.empty()) {
      const std::vector<double> sol = u.to_std();
      std::vector<double> per_cell;
      for (Index c : node_of_cell)
        for (int d = 0; d < 3; ++d) per_cell.push_back(sol[static_cast<std::size_t>(c * 3 + d)]);
      std::FILE* f = std::fopen(solution_path.c_str(), "wb");
      const bool ok =
          f && std::fwrite(per_cell.data(), sizeof(double), per_cell.size(), f) == per_cell.size();
      if (f) std::fclose(f);
      if (!ok) {
        fmt::print(stderr, "cannot write {}\n", solution_path);
        return 1;
      }
    }
    out.push_back(
        fmt::format("\"dofs\": {}, \"iterations\": {}, \"relative_residual\": {:.3e}, \"offsets\": {}, "
                    "\"short_horizon\": {}, \"preconditioner_nonzeros\": {:.0f}",
                    n, rep.iterations, rep.relative_residual, offsets, short_factor, P.nonzeros()));
    if (check) {
      const auto full = setup::build_discretization(config);
      system::ConstrainedSystem sys(full, system::assemble_stiffness(full).K, setup::build_dirichlet(full),
                                    setup::build_external_force(full));
      la::Vector ya(n, 3), ym(n, 3);
      sys.A().mult(u, ya);
      A.mult(u, ym);
      const std::vector<double> va = ya.to_std(), vm = ym.to_std();
      double diff = 0.0, norm = 0.0;
      for (std::size_t k = 0; k < va.size(); ++k) {
        diff = std::max(diff, std::abs(va[k] - vm[k]));
        norm = std::max(norm, std::abs(va[k]));
      }
      const std::vector<double> rhs_a = sys.rhs_unit().to_std();
      double rdiff = 0.0, rnorm = 0.0;
      for (std::size_t k = 0; k < b.size(); ++k) {
        rdiff = std::max(rdiff, std::abs(rhs_a[k] - b[k]));
        rnorm = std::max(rnorm, std::abs(rhs_a[k]));
      }
      sys.attach_solver();
      la::Vector ua(n, 3);
      sys.solve(1.0, ua);
      const std::vector<double> sa = ua.to_std(), sm = u.to_std();
      double udiff = 0.0, unorm = 0.0;
      for (std::size_t k = 0; k < sa.size(); ++k) {
        udiff = std::max(udiff, std::abs(sa[k] - sm[k]));
        unorm = std::max(unorm, std::abs(sa[k]));
      }
      out.push_back(fmt::format("\"check\": {{\"product\": {:.3e}, \"rhs\": {:.3e}, \"solution\": {:.3e}}}",
                                diff / norm, rdiff / rnorm, udiff / unorm));
    }
  } else {
    fmt::print(stderr, "unknown variant '{}': assembled or matrix-free\n", variant);
    return 2;
  }
  out.push_back(fmt::format("\"peak_rss_mb\": {:.1f}", peak_rss_mb()));
  std::string line = "{";
  for (std::size_t k = 0; k < out.size(); ++k) line += (k ? ", " : "") + out[k];
  fmt::print("{}}}\n", line);
  return 0;
}

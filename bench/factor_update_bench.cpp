// What an exact sparse Cholesky factor costs while bonds fail (issue 16, item 4;
// docs/benchmarks/fracture-update.md, "The floor of a factor-based
// bond-breaking loop"). The run keeps a factor of an earlier A and lets CG
// absorb the failed bonds (la::LinearSolver); the alternative is to keep the
// factor exact: a failed bond changes A by −w wᵀ (its block, THEORY §5, is
// rank one: w = √k ξ ⊗ v on its free dofs, pair_kernel.hpp bond_block), so
// CHOLMOD's cholmod_updown can downdate L D Lᵀ = P A Pᵀ in place and every
// solve is one forward and backward substitution.
//
// The case: a case file given after the benchmark's own options (e.g. B6 at
// h = 0.4δ: bench/run_factor_bench.sh writes it). Per case, once, not timed:
// the model, K, A (K with the constraints eliminated, as the run builds it),
// the elastic solution u at load factor 1 (the case's solver) and the bonds
// between two cells most stretched at u (those that fail first), as w.
//
//   Analyze          cholmod_analyze (fill-reducing ordering, supernodal
//                    symbolic factor): counters nnz_L, flops (of the
//                    numeric factorization), dofs, nnz_A
//   Factorize        cholmod_factorize, supernodal L Lᵀ (what PETSc's
//                    -pc_factor_mat_solver_type cholmod does)
//   SolveSupernodal  one right-hand side with that factor
//   Product          y = A x with PETSc's AIJ matrix (one CG iteration's
//                    product)
//   ToSimplicial     cholmod_change_factor to the simplicial L D Lᵀ that
//                    cholmod_updown needs
//   SolveSimplicial  one right-hand side with the simplicial factor
//   Downdate/k       the k most stretched bonds downdated one at a time
//                    (rank one each), on a fresh copy of the simplicial
//                    factor; counters us_per_bond and rel_residual: ‖(A −
//                    Σ w wᵀ) x − b‖/‖b‖ for x solved with the downdated factor
//                    (round-off when the w are the bonds' blocks)
//   DowndateBatch/k  the same k bonds as one rank-k downdate (CHOLMOD works
//                    on up to 8 columns per pass)
//
// Times: manual (steady_clock), ms, one iteration per repetition. Arguments
// after the case go to PETSc.
//
// Run: bench/run_factor_bench.sh.

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/run_state.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/vector.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <omp.h>
#include <suitesparse/cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace perimorph;
using Clock = std::chrono::steady_clock;

constexpr int kCounts[] = {1, 8, 64, 512};

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string g_case_path;

/// The case's A in CHOLMOD's form (lower triangle, stype −1), the bond
/// vectors w of the most stretched inter-cell bonds (columns of C, in the
/// original dof numbering), a right-hand side, and the supernodal and
/// simplicial factors. Built once, not timed.
struct Setup {
  cholmod_common cm{};
  setup::Discretization model;
  std::unique_ptr<system::ConstrainedSystem> sys;
  cholmod_sparse* A = nullptr;
  cholmod_sparse* C = nullptr;  ///< n × kMax, column j = w of the j-th most stretched bond
  cholmod_dense* b = nullptr;
  cholmod_factor* super = nullptr;
  cholmod_factor* simplicial = nullptr;
  double elastic_iterations = 0;

  explicit Setup(const std::string& path)
      : model(setup::build_discretization(casefile::parse_case_file(path))) {
    cholmod_start(&cm);
    auto bc = setup::build_dirichlet(model);
    std::vector<char> prescribed(static_cast<std::size_t>(model.dofmap.num_dofs()), 0);
    for (Index d : bc.dofs) prescribed[static_cast<std::size_t>(d)] = 1;
    sys = std::make_unique<system::ConstrainedSystem>(
        model, system::assemble_stiffness(model).K, std::move(bc),
        std::vector<double>(static_cast<std::size_t>(model.dofmap.num_dofs()), 0.0));
    sys->attach_solver();
    la::Vector u(model.dofmap.num_dofs(), model.dim());
    u.set_all(0.0);
    elastic_iterations = sys->solve(1.0, u).iterations;
    A = to_cholmod(sys->A());
    b = cholmod_zeros(A->nrow, 1, CHOLMOD_REAL, &cm);
    const auto rhs = sys->rhs_unit().to_std();
    std::copy(rhs.begin(), rhs.end(), static_cast<double*>(b->x));
    C = bond_vectors(u.to_std(), prescribed);
    super = cholmod_analyze(A, &cm);
    cholmod_factorize(A, super, &cm);
    simplicial = cholmod_copy_factor(super, &cm);
    cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, simplicial, &cm);
    if (cm.status != CHOLMOD_OK) throw std::runtime_error(fmt::format("CHOLMOD status {}", cm.status));
  }
  ~Setup() {
    for (cholmod_factor* L : {super, simplicial}) cholmod_free_factor(&L, &cm);
    for (cholmod_sparse* S : {A, C}) cholmod_free_sparse(&S, &cm);
    cholmod_free_dense(&b, &cm);
    cholmod_finish(&cm);
  }
  Setup(const Setup&) = delete;
  Setup& operator=(const Setup&) = delete;

  /// The lower triangle of a symmetric PETSc matrix, as CHOLMOD's compressed
  /// columns (row i's entries j ≤ i are column i's entries of the upper
  /// triangle, hence stype +1 read as columns).
  cholmod_sparse* to_cholmod(const la::Matrix& M) {
    std::vector<long> p{0};
    std::vector<int> rows;
    std::vector<double> values;
    M.visit_rows([&](Index i, std::span<const Index> cols, std::span<const double> vals) {
      for (std::size_t k = 0; k < cols.size(); ++k)
        if (cols[k] <= i) {
          rows.push_back(static_cast<int>(cols[k]));
          values.push_back(vals[k]);
        }
      p.push_back(static_cast<long>(rows.size()));
    });
    const auto n = static_cast<std::size_t>(M.rows());
    cholmod_sparse* S = cholmod_allocate_sparse(n, n, rows.size(), true, true, 1, CHOLMOD_REAL, &cm);
    std::transform(p.begin(), p.end(), static_cast<int*>(S->p), [](long v) { return static_cast<int>(v); });
    std::copy(rows.begin(), rows.end(), static_cast<int*>(S->i));
    std::copy(values.begin(), values.end(), static_cast<double*>(S->x));
    return S;
  }

  /// w = √k (ξ_i v_a) on the free dofs of the most stretched bonds between two
  /// cells (v: −N_g on E's nodes, N_h on F's; bond_block's layout), sorted
  /// by row, as the columns of an n × kMax sparse matrix.
  cholmod_sparse* bond_vectors(const std::vector<double>& u, const std::vector<char>& prescribed) {
    const evolution::BondFailure failure(model);
    evolution::RunState state(model);
    auto bonds = assembly::bonds_over(failure.space(state), u, 0.0);
    std::erase_if(bonds, [](const assembly::StretchedBond& s) { return s.id.e == s.id.f; });
    const std::size_t keep = std::min<std::size_t>(kCounts[std::size(kCounts) - 1], bonds.size());
    std::partial_sort(bonds.begin(), bonds.begin() + static_cast<std::ptrdiff_t>(keep), bonds.end(),
                      [](const auto& x, const auto& y) { return x.stretch > y.stretch; });
    bonds.resize(keep);
    const int dim = model.dim();
    std::vector<int> p{0}, rows;
    std::vector<double> values;
    evolution::BondFailure::BondShape shape;
    for (const auto& bond : bonds) {
      failure.shape_of(bond, shape);
      std::vector<std::pair<int, double>> column;
      const double root_k = std::sqrt(bond.k);
      for (std::size_t a = 0; a < shape.dofs.size(); ++a) {
        const int node = static_cast<int>(a) / dim, i = static_cast<int>(a) % dim;
        const double va = node < shape.nE ? -shape.Ng[node] : 0.0;
        const double vb = shape.same_cell ? (node < shape.nE ? shape.Nh[node] : 0.0)
                                          : (node >= shape.nE ? shape.Nh[node - shape.nE] : 0.0);
        const double w = root_k * bond.xi[i] * (va + vb);
        const Index dof = shape.dofs[a];
        if (w != 0.0 && !prescribed[static_cast<std::size_t>(dof)])
          column.emplace_back(static_cast<int>(dof), w);
      }
      std::sort(column.begin(), column.end());
      for (const auto& [r, w] : column) {
        rows.push_back(r);
        values.push_back(w);
      }
      p.push_back(static_cast<int>(rows.size()));
    }
    cholmod_sparse* S = cholmod_allocate_sparse(A->nrow, keep, rows.size(), true, true, 0, CHOLMOD_REAL, &cm);
    std::copy(p.begin(), p.end(), static_cast<int*>(S->p));
    std::copy(rows.begin(), rows.end(), static_cast<int*>(S->i));
    std::copy(values.begin(), values.end(), static_cast<double*>(S->x));
    return S;
  }

  /// ‖(A − C_k C_kᵀ) x − b‖ / ‖b‖, x solved with `L`.
  double residual_after(cholmod_factor* L, int k) {
    std::vector<int> cols(static_cast<std::size_t>(k));
    std::iota(cols.begin(), cols.end(), 0);
    cholmod_sparse* Ck = cholmod_submatrix(C, nullptr, -1, cols.data(), k, true, true, &cm);
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, L, b, &cm);
    cholmod_dense* r = cholmod_copy_dense(b, &cm);
    double one[2] = {1, 0}, minus_one[2] = {-1, 0}, zero[2] = {0, 0};  // CHOLMOD takes them non-const
    cholmod_sdmult(A, false, one, minus_one, x, r, &cm);               // r = A x − b
    cholmod_dense* t = cholmod_zeros(static_cast<std::size_t>(k), 1, CHOLMOD_REAL, &cm);
    cholmod_sdmult(Ck, true, one, zero, x, t, &cm);        // t = Cᵀ x
    cholmod_sdmult(Ck, false, minus_one, one, t, r, &cm);  // r −= C t
    const double rel = cholmod_norm_dense(r, 2, &cm) / cholmod_norm_dense(b, 2, &cm);
    for (cholmod_dense* d : {x, r, t}) cholmod_free_dense(&d, &cm);
    cholmod_free_sparse(&Ck, &cm);
    return rel;
  }
};

std::unique_ptr<Setup> g_setup;

Setup& setup() {
  if (!g_setup) {
    const auto t0 = Clock::now();
    g_setup = std::make_unique<Setup>(g_case_path);
    const Setup& s = *g_setup;
    std::fprintf(stderr, "%s: %zu dofs, nnz(A) %.0f, nnz(L) %.0f, %zu bond vectors; set-up %.1f s\n",
                 g_case_path.c_str(), s.A->nrow, s.sys->A().nonzeros(), s.cm.lnz, s.C->ncol,
                 seconds_since(t0));
  }
  return *g_setup;
}

void common_counters(benchmark::State& state, const Setup& s) {
  state.counters["dofs"] = static_cast<double>(s.A->nrow);
  state.counters["nnz_A"] = s.sys->A().nonzeros();
  state.counters["threads"] = omp_get_max_threads();
}

template <class Body>
void timed(benchmark::State& state, Body body) {
  Setup& s = setup();
  for (auto _ : state) {
    const auto t0 = Clock::now();
    body(s);
    state.SetIterationTime(seconds_since(t0));
  }
  common_counters(state, s);
}

void BM_Analyze(benchmark::State& state) {
  double lnz = 0, flops = 0;
  timed(state, [&](Setup& s) {
    cholmod_factor* L = cholmod_analyze(s.A, &s.cm);
    lnz = s.cm.lnz;
    flops = s.cm.fl;
    cholmod_free_factor(&L, &s.cm);
  });
  state.counters["nnz_L"] = lnz;
  state.counters["flops"] = flops;
}

void BM_Factorize(benchmark::State& state) {
  timed(state, [](Setup& s) { cholmod_factorize(s.A, s.super, &s.cm); });
}

void BM_SolveSupernodal(benchmark::State& state) {
  timed(state, [](Setup& s) {
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, s.super, s.b, &s.cm);
    cholmod_free_dense(&x, &s.cm);
  });
}

void BM_Product(benchmark::State& state) {
  Setup& s = setup();
  la::Vector x(s.sys->A().rows(), s.model.dim()), y(s.sys->A().rows(), s.model.dim());
  x.copy_from(s.sys->rhs_unit());
  timed(state, [&](Setup& t) { t.sys->A().mult(x, y); });
}

void BM_ToSimplicial(benchmark::State& state) {
  Setup& s = setup();
  for (auto _ : state) {
    cholmod_factor* L = cholmod_copy_factor(s.super, &s.cm);
    const auto t0 = Clock::now();
    cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, L, &s.cm);
    state.SetIterationTime(seconds_since(t0));
    cholmod_free_factor(&L, &s.cm);
  }
  common_counters(state, s);
}

void BM_SolveSimplicial(benchmark::State& state) {
  timed(state, [](Setup& s) {
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, s.simplicial, s.b, &s.cm);
    cholmod_free_dense(&x, &s.cm);
  });
}

/// k bonds downdated in groups of `rank` columns on a fresh copy of the
/// simplicial factor.
void downdate(benchmark::State& state, int rank) {
  Setup& s = setup();
  const int k = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(state.range(0)), s.C->ncol));
  double rel = 0.0, seconds = 0.0;
  for (auto _ : state) {
    cholmod_factor* L = cholmod_copy_factor(s.simplicial, &s.cm);
    std::vector<cholmod_sparse*> groups;
    for (int first = 0; first < k; first += rank) {
      std::vector<int> cols(static_cast<std::size_t>(std::min(rank, k - first)));
      std::iota(cols.begin(), cols.end(), first);
      groups.push_back(cholmod_submatrix(s.C, static_cast<int*>(s.super->Perm), static_cast<long>(s.A->nrow),
                                         cols.data(), static_cast<long>(cols.size()), true, true, &s.cm));
    }
    const auto t0 = Clock::now();
    for (cholmod_sparse* G : groups) cholmod_updown(false, G, L, &s.cm);
    const double t = seconds_since(t0);
    state.SetIterationTime(t);
    seconds += t;
    rel = s.residual_after(L, k);
    for (cholmod_sparse* G : groups) cholmod_free_sparse(&G, &s.cm);
    cholmod_free_factor(&L, &s.cm);
  }
  common_counters(state, s);
  state.counters["k"] = k;
  state.counters["us_per_bond"] = 1e6 * seconds / static_cast<double>(state.iterations()) / k;
  state.counters["rel_residual"] = rel;
}

void BM_Downdate(benchmark::State& state) {
  downdate(state, 1);
}
void BM_DowndateBatch(benchmark::State& state) {
  downdate(state, static_cast<int>(state.range(0)));
}

void register_all() {
  auto add = [](const char* name, void (*fn)(benchmark::State&), std::vector<int64_t> args, int reps) {
    benchmark::RegisterBenchmark(name, fn)
        ->Args(args)
        ->UseManualTime()
        ->Iterations(1)
        ->Repetitions(reps)
        ->Unit(benchmark::kMillisecond);
  };
  add("Analyze", BM_Analyze, {}, 3);
  add("Factorize", BM_Factorize, {}, 3);
  add("SolveSupernodal", BM_SolveSupernodal, {}, 10);
  add("Product", BM_Product, {}, 10);
  add("ToSimplicial", BM_ToSimplicial, {}, 3);
  add("SolveSimplicial", BM_SolveSimplicial, {}, 10);
  for (int k : kCounts) add("Downdate", BM_Downdate, {k}, k >= 64 ? 2 : 5);
  for (int k : kCounts) add("DowndateBatch", BM_DowndateBatch, {k}, k >= 64 ? 2 : 5);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc < 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: %s [benchmark options] CASE.toml [PETSc options]\n", argv[0]);
    return 2;
  }
  g_case_path = argv[1];
  int petsc_argc = argc - 1;
  char** petsc_argv = argv + 1;
  la::PetscSession petsc(petsc_argc, petsc_argv);
  benchmark::AddCustomContext("omp_threads", std::to_string(omp_get_max_threads()));
  benchmark::AddCustomContext("case", g_case_path);
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_setup.reset();  // PETSc objects before PetscFinalize
  return 0;
}

// Benchmark P1 (docs/benchmarks/nonlocal-assembly.md): the non-local stiffness
// assembly on the unit cube, α ≡ 1, N³ hex cells (h = 1/N), δ = 3h,
// exponential kernel with l = δ/5 (calibrated to E = 1), n×n×n Gauss points
// per cell, CG or DG (degree 1: every cell owns its 8 nodes; α ≡ 1 makes every
// cell purely non-local, which is where the program uses DG).
//
//   assemble/N/q/dg              assemble_nonlocal with the default options (all
//                                the structural optimizations on); dg = 0 CG, 1 DG
//   study/N/q/stage/discard      CG, the optimizations switched on one by one:
//                                stage 0 plain (precomputed_points,
//                                unit_alpha_shortcut and translation_cache off),
//                                1 + precomputed points, 2 + α-free unit pairs,
//                                3 + translation cache (= the default);
//                                discard = 0 into the matrix, 1 into an inserter
//                                that drops the blocks (the element matrices
//                                alone, the thesis' measure)
//
// Timed: assemble_nonlocal into a la::Matrix made from build_sparsity with the
// cell graph (exact preallocation), then finalize; the matrix is zeroed before
// each repetition (not timed). Set-up (mesh, points, cell graph, pattern,
// matrix) is not timed. Counters (means over the repetitions):
//   assemble_s, finalize_s   wall seconds of the two parts
//   matrix_create_s          build_sparsity + la::Matrix (once, not timed)
//   bonds, cell_pairs, distinct_blocks, reused_pairs   NonlocalStats
//   bonds_per_s              bonds / assemble_s (with the cache, bonds of reused
//                            pairs count without being recomputed)
//   graph_pairs              unordered cell pairs of the cell graph
//   cells, dofs, nnz         nnz = Matrix::nonzeros()
//   matrix_gb                nnz × 12 bytes (AIJ: value + 32-bit column index)
//   threads                  omp_get_max_threads()
//   core_ms_per_cell         assemble_s × threads / cells, in ms (the thesis'
//                            unit: 1 core-hour per million cells = 3.6 ms)
//   peak_rss_mb, rss_reset   as in local_elasticity_bench.cpp: ru_maxrss after
//                            the benchmark with the peak reset before it
//   est_matrix_gb, est_seconds   the estimates below
// A configuration whose matrix is estimated (before anything large is built)
// above PERIMORPH_BENCH_MAX_GB (default 10, capped at 60 % of MemAvailable) or
// whose time is estimated above PERIMORPH_BENCH_MAX_S (default 180) is skipped
// with the message "not run: estimated ...". DG nnz is exact from the cell graph
// (576 per directed cell pair); CG nnz is exact from the pattern.
// PERIMORPH_BENCH_MAX_S=0 gives the estimates of every configuration and runs
// nothing.
//
// Before any timing (unless PERIMORPH_BENCH_NO_CHECK is set), main() checks
// that the plain version gives the same matrix as the precomputed one, bit for
// bit, and measures how far the translation cache moves it, through a CSR
// accumulator over the same pattern; the results go to the JSON context
// (check_*) and stdout.
//
// Run: bench/run_nonlocal_bench.sh. Arguments after the benchmark's own go to PETSc.

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <omp.h>

#include <sys/resource.h>

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace perimorph;

constexpr int kDim = 3;
constexpr double kBytesPerNonzero = 12.0;  // PetscScalar + 32-bit PetscInt column

bool reset_peak_rss() {
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

double env_double(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atof(v) : fallback;
}

double mem_available_gb() {
  std::ifstream f("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (f >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb / (1024.0 * 1024.0);
  return 1e9;
}

/// Matrix memory limit: PERIMORPH_BENCH_MAX_GB (10), at most 60 % of what is available now.
double memory_limit_gb() {
  return std::min(env_double("PERIMORPH_BENCH_MAX_GB", 10.0), 0.6 * mem_available_gb());
}

std::vector<dofs::Continuity> continuity(Index cells, bool dg) {
  if (!dg) return {};
  return std::vector<dofs::Continuity>(static_cast<std::size_t>(cells), dofs::Continuity::discontinuous);
}

peridynamics::Micromodulus kernel_for(double h) {
  peridynamics::Micromodulus k;
  k.shape = peridynamics::KernelShape::exponential;
  k.horizon = 3.0 * h;
  k.length = k.horizon / 5.0;
  k.scale = peridynamics::calibrate_isotropic(k, kDim, PlaneMode::strain, 1.0).scale;
  return k;
}

/// The reference coordinates of an n-per-direction Gauss rule (the points'
/// boxes decide the cell graph, as in setup::build_discretization).
std::vector<Vec3> reference_points(int n) {
  std::vector<Vec3> out;
  for (const auto& p : fem::gauss_legendre(kDim, n)) out.push_back(p.xi);
  return out;
}

/// Everything the non-local assembly reads, for one configuration.
struct Problem {
  mesh::Mesh mesh;
  alpha::AlphaField alpha;
  peridynamics::Micromodulus kernel;
  bonds::NonlocalPoints points;
  bonds::CellGraph graph;
  dofs::DofMap dofmap;

  Problem(Index n, int q, bool dg, alpha::AlphaField a)
      : mesh(mesh::make_box({kDim, Vec3::Zero(), Vec3::Ones(), {n, n, n}})),
        alpha(std::move(a)),
        kernel(kernel_for(1.0 / static_cast<double>(n))),
        points(bonds::make_nonlocal_points(mesh, q, 1.0, alpha)),
        graph(bonds::find_cell_neighbors(mesh, bonds::point_boxes(mesh, reference_points(q)), kernel.horizon,
                                         [this](Index e, Index f) {
                                           return points.cell_alpha_max[static_cast<std::size_t>(e)] > 0.0 ||
                                                  points.cell_alpha_max[static_cast<std::size_t>(f)] > 0.0;
                                         })),
        dofmap(mesh, kDim, continuity(mesh.num_cells(), dg)) {}

  assembly::NonlocalSpace space() const { return {mesh, dofmap, points, graph, kernel, &alpha, 1.0}; }
};

assembly::NonlocalOptions stage_options(int stage) {
  assembly::NonlocalOptions o;
  o.precomputed_points = stage >= 1;
  o.unit_alpha_shortcut = stage >= 2;
  o.translation_cache = stage >= 3;
  return o;
}

/// Size and cost estimates made before the matrix exists.
struct Estimate {
  double nnz = 0.0;       ///< exact (see the header)
  double inserted = 0.0;  ///< matrix values added by the assembly (pairs × block size²)
  double bonds = 0.0;     ///< point pairs computed (rough: all point pairs of computed cell pairs within δ)
  double seconds = 0.0;
  double gb() const { return nnz * kBytesPerNonzero / 1e9; }
};

// Cost model (seconds per unit), measured at N = 10 on the 2-core EPYC; only
// used to skip configurations. Insertion dominates: ~9 ns per added value with
// the direct CSR insertion of la::Matrix (it was ~40 ns in CG rows and ~85 ns
// in DG rows through MatSetValues).
constexpr double kSecondsPerInsertedValueCG = 10e-9;
constexpr double kSecondsPerInsertedValueDG = 10e-9;
constexpr double kSecondsPerNonzero = 30e-9;  // pattern, matrix creation with explicit zeros
constexpr double kSecondsPerBond = 150e-9;    // one thread

Estimate estimate(const Problem& p, int q, bool dg, const assembly::NonlocalOptions& o, bool into_matrix,
                  const assembly::SparsityPattern* pattern) {
  Estimate e;
  const double block = 8.0 * kDim;  // dofs per cell (CG and DG degree 1)
  double pairs = 0.0;
  for (Index c = 0; c < p.graph.num_cells(); ++c)
    for (Index f : p.graph.row(c)) pairs += f >= c ? 1.0 : 0.0;
  if (dg)
    e.nnz = block * block * static_cast<double>(p.graph.neighbors.size());
  else
    e.nnz = static_cast<double>(pattern->columns.size()) * kDim * kDim;
  e.inserted = into_matrix ? pairs * 4.0 * block * block : 0.0;
  // Bonds per point: the points within δ = 3h at q³ points per h³.
  const double per_point = 4.0 / 3.0 * M_PI * 27.0 * q * q * q;
  const double points = static_cast<double>(p.mesh.num_cells()) * q * q * q;
  const double cached = o.translation_cache ? 0.0 : 1.0;
  e.bonds = cached * 0.5 * points * per_point;
  const double threads = static_cast<double>(omp_get_max_threads());
  e.seconds = e.inserted * (dg ? kSecondsPerInsertedValueDG : kSecondsPerInsertedValueCG) +
              (into_matrix ? e.nnz * kSecondsPerNonzero : 0.0) + e.bonds * kSecondsPerBond / threads;
  return e;
}

/// Skips the benchmark if the estimate is over the limits; returns true if skipped.
bool skip_if_too_big(benchmark::State& state, const Estimate& e, bool into_matrix) {
  const double limit_gb = memory_limit_gb();
  const double limit_s = env_double("PERIMORPH_BENCH_MAX_S", 180.0);
  state.counters["est_matrix_gb"] = e.gb();
  state.counters["est_seconds"] = e.seconds;
  if (into_matrix && e.gb() > limit_gb) {
    state.SkipWithError(
        fmt::format("not run: estimated {:.1f} GB of matrix ({:.3g} non-zeros) > limit {:.1f} GB", e.gb(),
                    e.nnz, limit_gb)
            .c_str());
    return true;
  }
  if (e.seconds > limit_s) {
    state.SkipWithError(fmt::format("not run: estimated {:.0f} s > limit {:.0f} s ({:.2f} GB of matrix)",
                                    e.seconds, limit_s, e.gb())
                            .c_str());
    return true;
  }
  return false;
}

/// Discards the blocks (keeps one value so the work is not optimized away):
/// the element matrices alone, the thesis' measure.
class DiscardInserter final : public assembly::MatrixInserter {
 public:
  void add(std::span<const Index>, std::span<const Index>, std::span<const double> values) override {
    if (!values.empty()) sum_ += values[0];
  }
  double sum() const { return sum_; }

 private:
  double sum_ = 0.0;
};

enum class Sink { matrix, discard };

void run(benchmark::State& state, Index n, int q, bool dg, const assembly::NonlocalOptions& options,
         Sink sink) {
  using clock = std::chrono::steady_clock;
  auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  const bool reset = reset_peak_rss();
  const bool into_matrix = sink == Sink::matrix;
  const Problem p(n, q, dg, alpha::AlphaField::constant(1.0));
  auto t = clock::now();
  std::optional<assembly::SparsityPattern> pattern;
  if (!dg) pattern = assembly::build_sparsity(p.dofmap, &p.graph);
  const Estimate est = estimate(p, q, dg, options, into_matrix, pattern ? &*pattern : nullptr);
  state.counters["cells"] = static_cast<double>(p.mesh.num_cells());
  state.counters["dofs"] = static_cast<double>(p.dofmap.num_dofs());
  state.counters["graph_pairs"] = static_cast<double>(p.graph.num_pairs());
  if (skip_if_too_big(state, est, into_matrix)) {
    state.counters["nnz"] = est.nnz;
    for (auto _ : state) {
    }
    return;
  }
  std::optional<la::Matrix> K;
  DiscardInserter discard;
  if (into_matrix) {
    if (!pattern) pattern = assembly::build_sparsity(p.dofmap, &p.graph);
    K.emplace(*pattern);
    state.counters["matrix_create_s"] = since(t);
  }
  pattern.reset();
  assembly::MatrixInserter& sink_ref = K ? static_cast<assembly::MatrixInserter&>(*K) : discard;

  assembly::NonlocalStats stats;
  double assemble_s = 0.0, finalize_s = 0.0;
  int reps = 0;
  for (auto _ : state) {
    if (K) {
      state.PauseTiming();
      K->zero_entries();
      state.ResumeTiming();
    }
    t = clock::now();
    stats = assembly::assemble_nonlocal(p.space(), sink_ref, options);
    assemble_s += since(t);
    t = clock::now();
    if (K) K->finalize();
    finalize_s += since(t);
    ++reps;
  }
  benchmark::DoNotOptimize(discard.sum());
  assemble_s /= reps;
  finalize_s /= reps;
  const double threads = static_cast<double>(omp_get_max_threads());
  const double cells = static_cast<double>(p.mesh.num_cells());
  if (K) {
    state.counters["nnz"] = K->nonzeros();
    state.counters["matrix_gb"] = K->nonzeros() * kBytesPerNonzero / 1e9;
  }
  state.counters["assemble_s"] = assemble_s;
  state.counters["finalize_s"] = finalize_s;
  state.counters["bonds"] = static_cast<double>(stats.bonds);
  state.counters["bonds_per_s"] = static_cast<double>(stats.bonds) / assemble_s;
  state.counters["cell_pairs"] = static_cast<double>(stats.cell_pairs);
  state.counters["distinct_blocks"] = static_cast<double>(stats.distinct_blocks);
  state.counters["reused_pairs"] = static_cast<double>(stats.reused_pairs);
  state.counters["threads"] = threads;
  state.counters["core_ms_per_cell"] = assemble_s * threads / cells * 1e3;
  state.counters["peak_rss_mb"] = peak_rss_mb();
  state.counters["rss_reset"] = reset ? 1.0 : 0.0;
}

void assemble(benchmark::State& state) {
  run(state, static_cast<Index>(state.range(0)), static_cast<int>(state.range(1)), state.range(2) != 0, {},
      Sink::matrix);
}

void study(benchmark::State& state) {
  run(state, static_cast<Index>(state.range(0)), static_cast<int>(state.range(1)), false,
      stage_options(static_cast<int>(state.range(2))), state.range(3) != 0 ? Sink::discard : Sink::matrix);
}

// ---------------------------------------------------------------------------
// Checks before timing: the plain version against the precomputed one.

/// A MatrixInserter that sums into plain CSR storage over a sparsity pattern,
/// entry by entry in the order of the add() calls, as PETSc's ADD_VALUES does.
class CsrInserter final : public assembly::MatrixInserter {
 public:
  explicit CsrInserter(assembly::SparsityPattern pattern) : p_(std::move(pattern)) {
    const auto bs = static_cast<std::size_t>(p_.block_size);
    values_.assign(p_.columns.size() * bs * bs, 0.0);
  }
  void add(std::span<const Index> rows, std::span<const Index> cols, std::span<const double> v) override {
    const Index bs = p_.block_size;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i] < 0) continue;
      const Index br = rows[i] / bs, k = rows[i] % bs;
      const auto row = p_.row(br);
      const std::size_t start = static_cast<std::size_t>(p_.row_offsets[static_cast<std::size_t>(br)]) *
                                    static_cast<std::size_t>(bs * bs) +
                                static_cast<std::size_t>(k) * row.size() * static_cast<std::size_t>(bs);
      for (std::size_t j = 0; j < cols.size(); ++j) {
        if (cols[j] < 0) continue;
        const auto it = std::lower_bound(row.begin(), row.end(), cols[j] / bs);
        if (it == row.end() || *it != cols[j] / bs)
          throw std::runtime_error("CsrInserter: entry outside the pattern");
        const auto pos = static_cast<std::size_t>(it - row.begin());
        values_[start + pos * static_cast<std::size_t>(bs) + static_cast<std::size_t>(cols[j] % bs)] +=
            v[i * cols.size() + j];
      }
    }
  }
  std::vector<double>& values() { return values_; }

 private:
  assembly::SparsityPattern p_;
  std::vector<double> values_;
};

struct Assembled {
  std::vector<double> v;
  assembly::NonlocalStats stats;
};

Assembled assemble_values(const Problem& p, const assembly::NonlocalOptions& o) {
  CsrInserter K(assembly::build_sparsity(p.dofmap, &p.graph));
  Assembled a;
  a.stats = assembly::assemble_nonlocal(p.space(), K, o);
  a.v = std::move(K.values());
  return a;
}

/// "bitwise identical" or the number of entries that differ and the largest
/// difference relative to the largest entry.
std::string compare(const Assembled& a, const Assembled& b) {
  if (a.v.size() != b.v.size()) return fmt::format("different sizes {} and {}", a.v.size(), b.v.size());
  std::size_t differ = 0;
  double max_diff = 0.0, max_abs = 0.0;
  for (std::size_t i = 0; i < a.v.size(); ++i) {
    max_abs = std::max(max_abs, std::abs(a.v[i]));
    if (a.v[i] != b.v[i]) {
      ++differ;
      max_diff = std::max(max_diff, std::abs(a.v[i] - b.v[i]));
    }
  }
  std::string s = differ == 0 ? std::string("bitwise identical")
                              : fmt::format("{} of {} entries differ, max |diff| / max |K| = {:.2e}", differ,
                                            a.v.size(), max_diff / max_abs);
  if (a.stats.bonds != b.stats.bonds || a.stats.cell_pairs != b.stats.cell_pairs)
    s += fmt::format("; bonds {} vs {}, cell pairs {} vs {}", a.stats.bonds, b.stats.bonds,
                     a.stats.cell_pairs, b.stats.cell_pairs);
  return s;
}

void check(const std::string& key, const std::string& label, const Assembled& a, const Assembled& b) {
  const std::string result = compare(a, b);
  fmt::print("check {}: {}: {}\n", key, label, result);
  benchmark::AddCustomContext("check_" + key, label + ": " + result);
}

void run_checks() {
  const auto t0 = std::chrono::steady_clock::now();
  {
    // α ≡ 1, CG: every stage against the previous one.
    const Problem p(10, 3, false, alpha::AlphaField::constant(1.0));
    std::vector<Assembled> s;
    for (int stage = 0; stage < 4; ++stage) s.push_back(assemble_values(p, stage_options(stage)));
    check("cg10_q3_precomputed",
          "N=10, 3 points, CG, alpha=1: stage 1 (precomputed points) vs stage 0 (plain)", s[1], s[0]);
    check("cg10_q3_unit", "N=10, 3 points, CG, alpha=1: stage 2 (+unit pairs) vs stage 1", s[2], s[1]);
    check("cg10_q3_cache", "N=10, 3 points, CG, alpha=1: stage 3 (+translation cache) vs stage 2", s[3],
          s[2]);
    assembly::NonlocalOptions all_plain_cache = stage_options(3);
    all_plain_cache.precomputed_points = false;
    check("cg10_q3_plain_default",
          "N=10, 3 points, CG, alpha=1: default options with precomputed_points=false vs default",
          assemble_values(p, all_plain_cache), s[3]);
  }
  {
    const Problem p(8, 4, false, alpha::AlphaField::constant(1.0));
    const Assembled plain = assemble_values(p, stage_options(0)), pre = assemble_values(p, stage_options(1)),
                    cached = assemble_values(p, stage_options(3));
    check("cg8_q4_precomputed", "N=8, 4 points, CG, alpha=1: stage 1 vs stage 0 (plain)", pre, plain);
    check("cg8_q4_cache", "N=8, 4 points, CG, alpha=1: stage 3 (all on) vs stage 0 (plain)", cached, plain);
  }
  {
    // A non-constant α (a cubic ball), DG: α is really read; unit and α-zero
    // pairs are mixed.
    alpha::Region ball{alpha::Ball{Vec3(0.5, 0.5, 0.5), 0.15}, 0.2, alpha::Profile::cubic};
    const Problem p(8, 2, true, alpha::AlphaField::regions({ball}, kDim));
    check("dg8_q2_ball_plain", "N=8, 2 points, DG, alpha ball r=0.15 + cubic 0.2: stage 0 vs stage 1",
          assemble_values(p, stage_options(0)), assemble_values(p, stage_options(1)));
    assembly::NonlocalOptions plain_all = stage_options(3);
    plain_all.precomputed_points = false;
    check("dg8_q2_ball_default",
          "N=8, 2 points, DG, alpha ball: default with precomputed_points=false vs default",
          assemble_values(p, plain_all), assemble_values(p, stage_options(3)));
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  benchmark::AddCustomContext("check_seconds", fmt::format("{:.1f}", s));
  fmt::print("checks took {:.1f} s\n", s);
}

// ---------------------------------------------------------------------------

void register_all() {
  for (int n : {10, 16, 24})
    for (int dg : {0, 1})
      for (int q : {2, 3, 4})
        benchmark::RegisterBenchmark("assemble", assemble)
            ->Args({n, q, dg})
            ->ArgNames({"N", "q", "dg"})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MeasureProcessCPUTime()
            ->Iterations(1);
  for (int n : {10, 16})
    for (int q : {3, 4})
      for (int discard : {0, 1})
        for (int stage = 0; stage < 4; ++stage)
          benchmark::RegisterBenchmark("study", study)
              ->Args({n, q, stage, discard})
              ->ArgNames({"N", "q", "stage", "discard"})
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime()
              ->MeasureProcessCPUTime()
              ->Iterations(1);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  la::PetscSession petsc(argc, argv);
  benchmark::AddCustomContext("omp_threads", std::to_string(omp_get_max_threads()));
  benchmark::AddCustomContext("memory_limit_gb", fmt::format("{:.1f}", memory_limit_gb()));
  if (!std::getenv("PERIMORPH_BENCH_NO_CHECK")) run_checks();
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

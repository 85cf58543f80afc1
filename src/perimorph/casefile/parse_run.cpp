#include "perimorph/casefile/parse_run.hpp"

#include "perimorph/casefile/choose_option.hpp"

#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace perimorph::casefile::detail {

namespace {
constexpr int kMaxInt = std::numeric_limits<int>::max();
}  // namespace

void read_loading(const Table& root, CaseConfig& c) {
  const auto t = root.table("loading");
  if (!t) return;
  t->check_keys({"increments", "factors", "body_force"});
  const auto increments = t->get("increments");
  const auto factors = t->get("factors");
  if (increments && factors)
    factors->fail(
        fmt::format("cannot be combined with loading.increments (line {}); give either increments = N "
                    "(factors 1/N, 2/N, ..., 1) or an explicit list factors = [...]",
                    increments->where().line));
  if (increments) {
    const int n = increments->integer(1, 1000000);
    c.loading.factors.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
      c.loading.factors[static_cast<std::size_t>(i)] = static_cast<double>(i + 1) / n;
  }
  if (factors) {
    const std::vector<Value> items = factors->elements();
    if (items.empty()) factors->fail("must list at least one load factor, e.g. factors = [0.5, 1.0]");
    c.loading.factors.clear();
    for (const Value& item : items) c.loading.factors.push_back(item.number());
  }
  if (auto v = t->get("body_force"))
    c.loading.body_force = v->vector(c.dim(), fmt::format("for dim = {}", c.dim()));
}

void read_solver(const Table& root, CaseConfig& c) {
  const auto t = root.table("solver");
  if (!t) return;
  t->check_keys({"petsc_options", "rtol", "max_iterations", "operator", "preconditioner_horizon"});
  c.solver.operator_where = t->where();
  if (auto v = t->get("petsc_options")) {
    c.solver.petsc_options = v->string();
    // The words as PETSc (and la::add_options) reads them: an option is '-'
    // and a letter; the word after it, if not an option, is its value.
    std::istringstream in(c.solver.petsc_options);
    const std::vector<std::string> words{std::istream_iterator<std::string>(in),
                                         std::istream_iterator<std::string>()};
    auto is_option = [](const std::string& w) {
      return w.size() >= 2 && w[0] == '-' && std::isalpha(static_cast<unsigned char>(w[1]));
    };
    for (std::size_t i = 0; i < words.size(); ++i) {
      if (!is_option(words[i]))
        v->fail(fmt::format(
            "must be PETSc command-line options, each starting with '-' and a letter and followed by at "
            "most one value, e.g. "
            "\"-ksp_type cg -pc_type gamg\"; {:?} is {} in {:?}",
            words[i], i == 0 ? "not an option" : fmt::format("a second value after {:?}", words[i - 1]),
            c.solver.petsc_options));
      if (i + 1 < words.size() && !is_option(words[i + 1])) ++i;
    }
  }
  if (auto v = t->get("rtol")) {
    c.solver.rtol = v->number();
    if (!(c.solver.rtol > 0 && c.solver.rtol < 1))
      v->fail(fmt::format("the relative residual tolerance must lie strictly between 0 and 1, got {}",
                          c.solver.rtol));
  }
  if (auto v = t->get("max_iterations")) c.solver.max_iterations = v->integer(1, kMaxInt);
  if (auto v = t->get("operator")) {
    static const detail::Options<SolverOperator> kOperators{{"assembled", SolverOperator::assembled},
                                                            {"matrix-free", SolverOperator::matrix_free}};
    c.solver.op = detail::choose(*v, kOperators, "operator");
    c.solver.operator_where = v->where();
  }
  if (auto v = t->get("preconditioner_horizon")) {
    if (c.solver.op != SolverOperator::matrix_free)
      v->fail(
          "is the horizon of the matrix-free operator's preconditioner: it needs operator = "
          "\"matrix-free\" in this table (the assembled operator has no such preconditioner)");
    c.solver.preconditioner_horizon = v->number();
    // At least the face neighbours (1 h), below the horizons where the
    // short operator would cost what the full one does.
    if (!(c.solver.preconditioner_horizon >= 1.0 && c.solver.preconditioner_horizon <= 10.0))
      v->fail(
          fmt::format("the preconditioner's horizon is in cell sizes and must lie in [1, 10] (it must "
                      "reach the face neighbours; 1.5 reaches the edge neighbours too), got {}",
                      c.solver.preconditioner_horizon));
  }
}

void read_output(const Table& root, CaseConfig& c) {
  std::string stem = std::filesystem::path(c.path).stem().string();
  c.output.basename = stem.empty() ? "case" : stem;
  const auto t = root.table("output");
  if (!t) return;
  t->check_keys({"directory", "basename", "vtu", "every", "failed_bonds", "checkpoint_every"});
  if (auto v = t->get("directory")) c.output.directory = v->name();
  if (auto v = t->get("basename")) {
    c.output.basename = v->name();
    if (c.output.basename.find_first_of("/\\") != std::string::npos)
      v->fail(
          fmt::format("must be a plain file-name stem without '/', got {:?}; put folders in output.directory",
                      c.output.basename));
  }
  if (auto v = t->get("vtu")) c.output.vtu = v->boolean();
  if (auto v = t->get("every")) c.output.every = v->integer(1, kMaxInt);
  if (auto v = t->get("failed_bonds")) c.output.failed_bonds = v->boolean();
  if (auto v = t->get("checkpoint_every")) c.output.checkpoint_every = v->integer(0, kMaxInt);
}

}  // namespace perimorph::casefile::detail

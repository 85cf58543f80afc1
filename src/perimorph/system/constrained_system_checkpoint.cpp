// ConstrainedSystem::save and ::restored (constrained_system.hpp): the system
// of a checkpoint, bit for bit, on any number of processes (the matrices and
// vectors saved in the assembly's numbering; collective).

#include "perimorph/core/binary_stream.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"

#include <fmt/format.h>

namespace perimorph::system {

namespace {

/// The matrix in the assembly's numbering, whatever the number of processes
/// (collective): a checkpoint written on P processes restarts on any number.
void save_matrix(core::BinaryWriter& out, const la::Matrix& M) {
  const la::Matrix::Replicated r = M.replicated();
  out.put<int>(r.pattern.block_size);
  out.put_vector(r.pattern.row_offsets);
  out.put_vector(r.pattern.columns);
  out.put_vector(r.values);
}

/// Spread over the processes as the model's stiffness is
/// (system::distribution_over_processes; collective).
la::Matrix load_matrix(core::BinaryReader& in, const setup::Discretization& model) {
  const Index rows = model.dofmap.num_dofs();
  la::Matrix::Replicated r;
  assembly::SparsityPattern& p = r.pattern;
  p.block_size = in.get<int>();
  p.row_offsets = in.get_vector<Index>();
  p.columns = in.get_vector<Index>();
  if (p.block_size < 1 || p.row_offsets.empty() || p.num_block_rows() * p.block_size != rows)
    in.fail(fmt::format("a matrix of {} rows where the model has {} dofs",
                        p.row_offsets.empty() ? 0 : p.num_block_rows() * p.block_size, rows));
  if (p.row_offsets.front() != 0 || static_cast<std::size_t>(p.row_offsets.back()) != p.columns.size())
    in.fail("a matrix pattern that does not add up");
  for (std::size_t k = 0; k + 1 < p.row_offsets.size(); ++k)
    if (p.row_offsets[k] > p.row_offsets[k + 1]) in.fail("a matrix pattern that does not add up");
  for (Index c : p.columns)
    if (c < 0 || c >= p.num_block_rows()) in.fail("a matrix column out of range");
  r.values = in.get_vector<double>();
  if (r.values.size() != p.columns.size() * static_cast<std::size_t>(p.block_size * p.block_size))
    in.fail("matrix values that do not fit its pattern");
  return la::Matrix::from_replicated(r, distribution_over_processes(model));
}

}  // namespace

void ConstrainedSystem::save(core::BinaryWriter& out) const {
  if (free_) {
    // Nothing changes a matrix-free system: the case rebuilds it.
    out.tag("matrix-free system");
    return;
  }
  out.tag("system");
  save_matrix(out, K_);
  save_matrix(out, A_);
  out.put_vector(rhs_unit_.to_replicated());
  out.put_vector(owned_.whole(initial_diagonal_));
  out.put<std::uint64_t>(downdates_);
  out.put_vector(last_downdated_);
}

std::unique_ptr<ConstrainedSystem> ConstrainedSystem::restored(const setup::Discretization& model,
                                                               setup::DirichletData bc,
                                                               std::span<const double> F,
                                                               core::BinaryReader& in) {
  if (model.config.solver.op == casefile::SolverOperator::matrix_free) {
    in.expect("matrix-free system");
    return std::make_unique<ConstrainedSystem>(model, build_matrix_free_stiffness(model), std::move(bc), F);
  }
  in.expect("system");
  const Index n = model.dofmap.num_dofs();
  la::Matrix K = load_matrix(in, model);
  auto system = std::make_unique<ConstrainedSystem>(model, std::move(K), std::move(bc), F);
  system->A_ = load_matrix(in, model);
  system->A_.set_spd();
  const std::vector<double> rhs = in.get_vector<double>();
  const std::vector<double> reference = in.get_vector<double>();
  if (rhs.size() != static_cast<std::size_t>(n) || reference.size() != rhs.size())
    in.fail(fmt::format("vectors of {} and {} values where the model has {} dofs", rhs.size(),
                        reference.size(), n));
  system->initial_diagonal_ = system->owned_.of(reference);
  system->rhs_unit_.assign_replicated(rhs);
  system->downdates_ = in.get<std::uint64_t>();
  system->last_downdated_ = in.get_vector<Index>();
  return system;
}

}  // namespace perimorph::system

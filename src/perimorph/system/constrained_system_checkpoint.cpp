// ConstrainedSystem::save and ::restored (constrained_system.hpp): the system
// of a checkpoint, bit for bit, on any number of processes (the matrices and
// vectors saved in the whole model's numbering: the assembly's on a part of
// the model, WholeNumbering's on a piece; collective).

#include "perimorph/core/binary_stream.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "perimorph/system/whole_numbering.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace perimorph::system {

namespace {

/// The matrix in the whole model's numbering, whatever the number of
/// processes (collective): a checkpoint written on P processes restarts on any
/// number, on parts or pieces.
void save_matrix(core::BinaryWriter& out, const la::Matrix& M, const WholeNumbering* whole) {
  const la::Matrix::Replicated r = whole ? whole->whole(M) : M.replicated();
  out.put<int>(r.pattern.block_size);
  out.put_vector(r.pattern.row_offsets);
  out.put_vector(r.pattern.columns);
  out.put_vector(r.values);
}

/// Spread over the processes as the model's stiffness is
/// (system::distribution_over_processes; collective); `rows`: the whole model's
/// dofs. On a piece only its owned rows are read (WholeNumbering::piece_of).
la::Matrix load_matrix(core::BinaryReader& in, const setup::Discretization& model, Index rows,
                       const WholeNumbering* whole) {
  StoredMatrix stored;
  stored.block_size = in.get<int>();
  stored.row_offsets = in.get_stored<Index>();
  stored.columns = in.get_stored<Index>();
  stored.values = in.get_stored<double>();
  const auto bs = static_cast<Index>(stored.block_size);
  const auto block_rows = static_cast<Index>(stored.row_offsets.size()) - 1;
  if (bs < 1 || stored.row_offsets.empty() || block_rows * bs != rows)
    in.fail(fmt::format("a matrix of {} rows where the model has {} dofs",
                        stored.row_offsets.empty() ? 0 : block_rows * bs, rows));
  if (stored.values.size() != stored.columns.size() * static_cast<std::size_t>(bs * bs))
    in.fail("matrix values that do not fit its pattern");
  if (stored.row_offsets[0] != 0 ||
      static_cast<std::size_t>(stored.row_offsets[stored.row_offsets.size() - 1]) != stored.columns.size())
    in.fail("a matrix pattern that does not add up");
  if (whole) {
    // Each process checks the rows it reads: every process stops if one finds a bad one.
    la::Matrix::Replicated mine;
    std::string bad;
    try {
      mine = whole->piece_of(stored);
    } catch (const InputError& e) {
      bad = e.what();
    }
    if (la::any_over_processes(!bad.empty()))
      in.fail(bad.empty() ? "a matrix row another process read is bad" : bad);
    return la::Matrix::from_replicated(mine, distribution_over_processes(model));
  }
  la::Matrix::Replicated r;
  assembly::SparsityPattern& p = r.pattern;
  p.block_size = stored.block_size;
  stored.row_offsets.append_to(p.row_offsets, 0, stored.row_offsets.size());
  stored.columns.append_to(p.columns, 0, stored.columns.size());
  for (std::size_t k = 0; k + 1 < p.row_offsets.size(); ++k)
    if (p.row_offsets[k] > p.row_offsets[k + 1]) in.fail("a matrix pattern that does not add up");
  for (Index c : p.columns)
    if (c < 0 || c >= p.num_block_rows()) in.fail("a matrix column out of range");
  stored.values.append_to(r.values, 0, stored.values.size());
  return la::Matrix::from_replicated(r, distribution_over_processes(model));
}

/// On a piece of the model, its whole numbering: `given`, else one built in
/// `built` (collective); else null.
const WholeNumbering* whole_numbering(const setup::Discretization& model, const WholeNumbering* given,
                                      std::optional<WholeNumbering>& built) {
  if (!model.piece) return nullptr;
  if (given) return given;
  return &built.emplace(model.piece->dofs, model.dim());
}

/// The dofs last downdated on every process, in the whole numbering: on a
/// piece each process's (those of the bonds its piece holds) gathered by
/// name onto the processes the numbering's Onto names.
std::vector<Index> whole_dofs(const setup::Discretization& model, const std::vector<Index>& dofs,
                              const WholeNumbering* whole) {
  if (!whole) return dofs;
  std::vector<double> names;
  for (Index d : dofs) names.push_back(static_cast<double>(setup::dof_name(model, d)));  // exact below 2^53
  const std::vector<double> all = la::gather_onto(names, whole->onto());
  std::vector<Index> out(all.size());
  std::transform(all.begin(), all.end(), out.begin(),
                 [&](double name) { return whole->whole_of_name(static_cast<Index>(name)); });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

void ConstrainedSystem::save(core::BinaryWriter& out, const WholeNumbering* given) const {
  if (free_) {
    // Nothing changes a matrix-free system: the case rebuilds it.
    out.tag("matrix-free system");
    return;
  }
  out.tag("system");
  std::optional<WholeNumbering> built;
  const WholeNumbering* whole = whole_numbering(model_, given, built);
  save_matrix(out, K_, whole);
  save_matrix(out, A_, whole);
  out.put_vector(whole ? whole->whole(rhs_unit_.at_owned(owned_)) : rhs_unit_.to_replicated());
  out.put_vector(whole ? whole->whole(initial_diagonal_) : owned_.whole(initial_diagonal_));
  out.put<std::uint64_t>(downdates_);
  out.put_vector(whole_dofs(model_, last_downdated_, whole));
}

std::unique_ptr<ConstrainedSystem> ConstrainedSystem::restored(const setup::Discretization& model,
                                                               setup::DirichletData bc,
                                                               std::span<const double> F,
                                                               core::BinaryReader& in,
                                                               const WholeNumbering* given) {
  if (model.config.solver.op == casefile::SolverOperator::matrix_free) {
    in.expect("matrix-free system");
    return std::make_unique<ConstrainedSystem>(model, build_matrix_free_stiffness(model), std::move(bc), F);
  }
  in.expect("system");
  std::optional<WholeNumbering> built;
  const WholeNumbering* whole = whole_numbering(model, given, built);
  const Index n = whole ? whole->whole_dofs() : model.dofmap.num_dofs();
  la::Matrix K = load_matrix(in, model, n, whole);
  auto system = std::make_unique<ConstrainedSystem>(model, std::move(K), std::move(bc), F);
  system->A_ = load_matrix(in, model, n, whole);
  system->A_.set_spd();
  const std::vector<double> rhs = in.get_vector<double>();
  const std::vector<double> reference = in.get_vector<double>();
  if (rhs.size() != static_cast<std::size_t>(n) || reference.size() != rhs.size())
    in.fail(fmt::format("vectors of {} and {} values where the model has {} dofs", rhs.size(),
                        reference.size(), n));
  system->initial_diagonal_ = whole ? whole->owned_of(reference) : system->owned_.of(reference);
  system->rhs_unit_.assign_replicated(whole ? whole->piece_of(rhs) : rhs);
  system->downdates_ = in.get<std::uint64_t>();
  system->last_downdated_ = in.get_vector<Index>();
  for (Index d : system->last_downdated_)
    if (d < 0 || d >= n) in.fail("a downdated dof out of range");
  if (whole) {
    // A piece keeps those it holds (ConstrainedSystem::without_stiffness reads the owned ones).
    system->last_downdated_ = whole->piece_dofs_of(system->last_downdated_);
    std::erase(system->last_downdated_, Index{-1});
  }
  return system;
}

}  // namespace perimorph::system

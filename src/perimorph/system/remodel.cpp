#include "perimorph/system/remodel.hpp"

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/stiffness.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace perimorph::system {

namespace {

using clock = std::chrono::steady_clock;
double since(clock::time_point t0) {
  return std::chrono::duration<double>(clock::now() - t0).count();
}

bool same_cell_dofs(const dofs::DofMap& a, const dofs::DofMap& b, Index c) {
  return a.continuity(c) == b.continuity(c) && a.cell_nodes(c).size() == b.cell_nodes(c).size();
}

/// The reference diagonal carried over (`reference`, whole-length: from
/// transfer_dof_vector, max), the new system's own where nothing carries over
/// and on prescribed dofs.
void carry_owned_reference(ConstrainedSystem& system, std::vector<double> carried) {
  const la::OwnedDofs& owned = system.owned_dofs();
  const std::vector<double>& fresh = system.reference_diagonal();
  for (std::size_t j = 0; j < carried.size(); ++j)
    if (!(carried[j] > 0.0) || system.prescribed(owned.dof(j))) carried[j] = fresh[j];
  system.set_reference_diagonal(std::move(carried));
}

void carry_reference(ConstrainedSystem& system, const std::vector<double>& reference) {
  carry_owned_reference(system, system.owned_dofs().of(reference));
}

/// The old system's reference diagonal in `after`'s numbering (whole-length;
/// collective where spread: the one O(dofs) gathering of a remodel).
std::vector<double> transferred_reference(const ConstrainedSystem& system,
                                          const setup::Discretization& before,
                                          const setup::Discretization& after) {
  return transfer_dof_vector(before, after, system.owned_dofs().whole(system.reference_diagonal()), true);
}

/// Adds sign × each block to a matrix.
class SignedInserter final : public assembly::MatrixInserter {
 public:
  SignedInserter(assembly::MatrixInserter& target, double sign) : target_(target), sign_(sign) {}
  void add(std::span<const Index> rows, std::span<const Index> cols,
           std::span<const double> values) override {
    block_.resize(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) block_[k] = sign_ * values[k];
    target_.add(rows, cols, block_);
  }

 private:
  assembly::MatrixInserter& target_;  ///< non-owning
  double sign_;
  std::vector<double> block_;
};

/// sign × the stiffness `disc` assembles for the flagged cells (their local
/// blocks, the bonds of every cell pair with a flagged cell), `failed` left out.
void add_cells(assembly::MatrixInserter& K, const setup::Discretization& disc, const std::vector<char>& in,
               const bonds::BrokenBonds* failed, std::span<const double> damage, double sign) {
  SignedInserter inserter(K, sign);
  auto flagged = [&](Index c) { return in[static_cast<std::size_t>(c)] != 0; };
  const bool damaged = disc.damage && !damage.empty();
  const fem::ConstitutiveField C = damaged ? setup::damaged_stiffness(disc.stiffness, *disc.damage, damage)
                                           : fem::ConstitutiveField(0, 0, 0);
  assembly::assemble_elasticity(disc.local_space(), damaged ? C : disc.stiffness, inserter,
                                [&](Index c) { return flagged(c) && disc.has_local_stiffness(c); });
  if (!disc.nonlocal) return;
  assembly::NonlocalOptions options;
  options.include_pair = [&](Index e, Index f) { return flagged(e) || flagged(f); };
  assembly::assemble_nonlocal(disc.nonlocal_space(failed), inserter, options);
}

/// Cell pairs the non-local assembly of `disc` visits (α > 0 at either) with
/// a flagged cell (all pairs when `in` is empty): the cost of assembling them.
std::size_t assembled_pairs(const setup::Discretization& disc, const std::vector<char>& in) {
  if (!disc.nonlocal) return 0;
  const auto& graph = disc.nonlocal->graph;
  const auto& amax = disc.nonlocal->points.cell_alpha_max;
  std::size_t n = 0;
  for (Index e = 0; e < graph.num_cells(); ++e)
    for (Index f : graph.row(e)) {
      if (f < e || amax[static_cast<std::size_t>(e)] + amax[static_cast<std::size_t>(f)] <= 0.0) continue;
      if (in.empty() || in[static_cast<std::size_t>(e)] || in[static_cast<std::size_t>(f)]) ++n;
    }
  return n;
}

}  // namespace

std::vector<Index> changed_cells(const setup::Discretization& before, const setup::Discretization& after) {
  PERIMORPH_ASSERT(before.mesh.num_cells() == after.mesh.num_cells(), "changed_cells: not the same mesh");
  std::vector<Index> out;
  const auto& C0 = before.stiffness;
  const auto& C1 = after.stiffness;
  const std::size_t nv2 = static_cast<std::size_t>(C0.voigt() * C0.voigt());
  for (Index c = 0; c < before.mesh.num_cells(); ++c) {
    bool changed = !same_cell_dofs(before.dofmap, after.dofmap, c) ||
                   before.has_local_stiffness(c) != after.has_local_stiffness(c);
    for (int q = 0; q < C0.points_per_cell() && !changed; ++q)
      changed = std::memcmp(C0.at(c, q), C1.at(c, q), nv2 * sizeof(double)) != 0;
    if (before.nonlocal && after.nonlocal && !changed) {
      const auto& p0 = before.nonlocal->points;
      const auto& p1 = after.nonlocal->points;
      for (int q = 0; q < p0.per_cell && !changed; ++q)
        changed = p0.alpha[p0.index(c, q)] != p1.alpha[p1.index(c, q)];
    }
    if (changed) out.push_back(c);
  }
  return out;
}

std::vector<double> transfer_dof_vector(const setup::Discretization& before,
                                        const setup::Discretization& after, std::span<const double> values,
                                        bool combine_max) {
  const int dim = before.dim();
  const auto& d0 = before.dofmap;
  const auto& d1 = after.dofmap;
  PERIMORPH_ASSERT(values.size() == static_cast<std::size_t>(d0.num_dofs()),
                   "transfer: vector of another size");
  std::vector<double> out(static_cast<std::size_t>(d1.num_dofs()), combine_max ? -HUGE_VAL : 0.0);
  auto put = [&](Index node, int k, double v) {
    double& slot = out[static_cast<std::size_t>(node * dim + k)];
    slot = combine_max ? std::max(slot, v) : v;
  };
  for (Index c = 0; c < after.mesh.num_cells(); ++c) {
    const Index b = setup::local_cell(before, setup::global_cell(after, c));  // c on one mesh
    if (b < 0) continue;
    const auto n0 = d0.cell_nodes(b), n1 = d1.cell_nodes(c);
    for (int k = 0; k < dim; ++k) {
      auto old_value = [&](std::size_t a) { return values[static_cast<std::size_t>(n0[a] * dim + k)]; };
      if (n0.size() == n1.size()) {
        for (std::size_t a = 0; a < n1.size(); ++a) put(n1[a], k, old_value(a));
      } else if (n1.size() == 1) {  // corners → DG degree 0: Q1 value at the centroid
        double mean = 0.0;
        for (std::size_t a = 0; a < n0.size(); ++a) mean += old_value(a);
        put(n1[0], k, mean / static_cast<double>(n0.size()));
      } else {  // DG degree 0 → corners
        for (std::size_t a = 0; a < n1.size(); ++a) put(n1[a], k, old_value(0));
      }
    }
  }
  return out;
}

Remodelled remodel(ConstrainedSystem& system, const setup::Discretization& before,
                   const setup::Discretization& after, const bonds::BrokenBonds* failed,
                   setup::DirichletData bc, std::span<const double> F, std::span<const double> damage) {
  Remodelled out;
  const int dim = before.dim();
  const bool distributed = system.K().distribution() != nullptr;
  if (!distributed) out.cells = changed_cells(before, after);
  std::vector<char> in(static_cast<std::size_t>(before.mesh.num_cells()), 0);
  for (Index c : out.cells) in[static_cast<std::size_t>(c)] = 1;

  // Subtracting and adding the changed cells' bonds costs about their pairs
  // in both models; when that exceeds assembling the new model, assemble it.
  // Spread over processes, the dofs a process owns change with the model
  // (partition/dof_layout.hpp): the old rows it holds are not those it needs,
  // and the new model is assembled (the same as the update to round-off).
  out.partial =
      !distributed && assembled_pairs(before, in) + assembled_pairs(after, in) <= assembled_pairs(after, {});
  if (!out.partial) {
    auto t0 = clock::now();
    la::Matrix K = distributed ? system::assemble_stiffness_over_processes(after, failed, damage).K
                               : system::assemble_stiffness(after, failed, damage).K;
    out.times.add = since(t0);
    t0 = clock::now();
    const std::vector<double> reference = transferred_reference(system, before, after);
    out.system = std::make_unique<ConstrainedSystem>(after, std::move(K), std::move(bc), F);
    carry_reference(*out.system, reference);
    out.times.constrain = since(t0);
    return out;
  }
  // The scale of K before any cell is subtracted: what is dropped below must be round-off of it.
  double largest = 0.0;
  for (double d : system.reference_diagonal()) largest = std::max(largest, std::abs(d));
  auto t0 = clock::now();
  la::Matrix& K_old = system.K();
  add_cells(K_old, before, in, failed, damage, -1.0);
  K_old.finalize();
  out.times.subtract = since(t0);

  // What is left of K_old belongs to unchanged cells and cell pairs: each old
  // dof node carries it to the node the same corner of a cell whose dofs did
  // not change has in `after` (-1: none; only round-off is left there).
  t0 = clock::now();
  std::vector<Index> kept(static_cast<std::size_t>(before.dofmap.num_nodes()), -1);
  for (Index c = 0; c < before.mesh.num_cells(); ++c) {
    if (!same_cell_dofs(before.dofmap, after.dofmap, c)) continue;
    const auto n0 = before.dofmap.cell_nodes(c), n1 = after.dofmap.cell_nodes(c);
    for (std::size_t a = 0; a < n0.size(); ++a) kept[static_cast<std::size_t>(n0[a])] = n1[a];
  }
  const assembly::SparsityPattern pattern =
      assembly::build_sparsity(after.dofmap, after.nonlocal ? &after.nonlocal->graph : nullptr);
  la::Matrix K_new(pattern);
  std::vector<Index> row(1), cols;
  std::vector<double> vals;
  double dropped = 0.0;
  K_old.visit_rows([&](Index r, std::span<const Index> c, std::span<const double> v) {
    const Index node = kept[static_cast<std::size_t>(r / dim)];
    cols.clear();
    vals.clear();
    const auto allowed = node >= 0 ? pattern.row(node) : std::span<const Index>{};
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Index to = kept[static_cast<std::size_t>(c[k] / dim)];
      if (node < 0 || to < 0 || !std::binary_search(allowed.begin(), allowed.end(), to)) {
        dropped = std::max(dropped, std::abs(v[k]));
        continue;
      }
      cols.push_back(to * dim + c[k] % dim);
      vals.push_back(v[k]);
    }
    row[0] = node * dim + r % dim;
    if (!cols.empty()) K_new.add(row, cols, vals);
  });
  PERIMORPH_ASSERT(dropped <= 1e-9 * largest,
                   "remodel: an entry of the old stiffness that no unchanged cell carries is not round-off");
  out.times.copy = since(t0);

  t0 = clock::now();
  add_cells(K_new, after, in, failed, damage, 1.0);
  K_new.finalize();
  out.times.add = since(t0);

  t0 = clock::now();
  const std::vector<double> reference = transferred_reference(system, before, after);
  out.system = std::make_unique<ConstrainedSystem>(after, std::move(K_new), std::move(bc), F);
  carry_reference(*out.system, reference);
  out.times.constrain = since(t0);
  return out;
}

Remodelled remodel_piece(const setup::Discretization& before, std::span<const double> reference,
                         const setup::Discretization& after, const bonds::BrokenBonds* failed,
                         setup::DirichletData bc, std::span<const double> F, std::span<const double> damage) {
  PERIMORPH_ASSERT(before.piece && after.piece, "remodel_piece: pieces of the model");
  Remodelled out;
  out.partial = false;
  auto t0 = clock::now();
  la::Matrix K = system::assemble_stiffness_over_processes(after, failed, damage).K;
  out.times.add = since(t0);
  t0 = clock::now();
  const std::vector<double> carried = transfer_dof_vector(before, after, reference, true);
  out.system = std::make_unique<ConstrainedSystem>(after, std::move(K), std::move(bc), F);
  carry_reference(*out.system, carried);
  out.times.constrain = since(t0);
  return out;
}

}  // namespace perimorph::system

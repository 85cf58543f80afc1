#include "perimorph/setup/piece_model.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/part_mesh.hpp"
#include "perimorph/partition/partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace perimorph::setup {

namespace {

/// v at the listed cells, in their order.
template <class T>
std::vector<T> at_cells(const std::vector<T>& v, std::span<const Index> cells) {
  std::vector<T> out;
  out.reserve(cells.size());
  for (Index c : cells) out.push_back(v[static_cast<std::size_t>(c)]);
  return out;
}

/// The cells of the grid within `r` cells of a marked one along each axis
/// (a cube around each), marked 1: separable, one axis at a time.
std::vector<char> dilated(std::vector<char> marked, const mesh::StructuredLayout& layout, Index r) {
  const std::array<Index, 3> n = layout.cells;
  const std::array<Index, 3> stride{1, n[0], n[0] * n[1]};
  std::vector<char> next(marked.size());
  for (std::size_t d = 0; d < 3; ++d) {
    if (n[d] == 1) continue;
    for (Index c = 0; c < layout.num_box_cells(); ++c) {
      const Index i = (c / stride[d]) % n[d];
      char any = 0;
      for (Index t = std::max<Index>(i - r, 0); t <= std::min(i + r, n[d] - 1) && !any; ++t)
        any = marked[static_cast<std::size_t>(c + (t - i) * stride[d])];
      next[static_cast<std::size_t>(c)] = any;
    }
    marked.swap(next);
  }
  return marked;
}

/// The cells the process of `part` reads: those whose C it computes and
/// those whose non-local points it stores (every cell for the whole model),
/// ascending; with the matrix-free operator (whose cell graph is the diagonal
/// one), every cell within its bond reach: the cube of ⌈δ / h⌉ + 1 cells
/// around each computed cell, the reach of the patch its blocks come from
/// (system::grid_offset_blocks).
std::vector<Index> cells_read(const Discretization& part) {
  const auto cells = static_cast<std::size_t>(part.mesh.num_cells());
  std::vector<char> read(cells, 0);
  for (std::size_t c = 0; c < cells; ++c)
    read[c] = part.computed_cells.empty() || part.computed_cells[c] ||
              (part.nonlocal && part.nonlocal->points.holds(static_cast<Index>(c)));
  if (part.config.solver.op == casefile::SolverOperator::matrix_free && part.mesh.structure) {
    // The grid the part is on: the whole box, or its window (a box of its own).
    mesh::StructuredLayout layout = *part.mesh.structure;
    PERIMORPH_ASSERT(layout.box_cells.empty() || part.window, "a part of the whole mesh or of a window");
    if (part.window) {
      for (std::size_t d = 0; d < 3; ++d) layout.cells[d] = part.window->hi[d] - part.window->lo[d];
      layout.box_cells.clear();
    }
    const double h = layout.spacing.head(part.dim()).minCoeff();
    read =
        dilated(std::move(read), layout, static_cast<Index>(std::ceil(part.config.nonlocal.horizon / h)) + 1);
  }
  std::vector<Index> out;
  for (std::size_t c = 0; c < cells; ++c)
    if (read[c]) out.push_back(static_cast<Index>(c));
  return out;
}

/// Throws Error if a cell of the window `w` that the part reads lies on a side
/// where the window cuts the grid (`n` cells per axis): a cell beyond it might
/// be read too, so the window is too narrow (part_window's widths are wrong).
void check_window_holds(const WindowNumbers& w, const std::array<Index, 3>& n, std::span<const Index> read) {
  std::array<Index, 3> width{};
  for (std::size_t d = 0; d < 3; ++d) width[d] = w.hi[d] - w.lo[d];
  for (Index c : read) {
    const std::array<Index, 3> ijk{c % width[0], (c / width[0]) % width[1], c / (width[0] * width[1])};
    for (std::size_t d = 0; d < 3; ++d)
      if ((ijk[d] == 0 && w.lo[d] > 0) || (ijk[d] == width[d] - 1 && w.hi[d] < n[d]))
        throw Error(
            fmt::format("piece: the part reads cell {}, on the edge of its window [{}, {}) along axis "
                        "{} of {} cells: the window is too narrow",
                        w.global_cell[static_cast<std::size_t>(c)], w.lo[d], w.hi[d], d, n[d]));
  }
}

}  // namespace

Discretization cut_to_piece(const Discretization& part, std::span<const int> owner, int part_number,
                            std::function<bool(bool)> any_over_processes) {
  PERIMORPH_ASSERT(static_cast<Index>(owner.size()) == part.mesh.num_cells(), "a part for every cell");
  const std::vector<Index> cells = cells_read(part);
  mesh::PartMesh pm = mesh::part_mesh(part.mesh, cells);
  Index whole_nodes = part.mesh.num_nodes(), whole_cells = part.mesh.num_cells();
  if (part.window) {
    // Cut from a window: the window's numbers are the whole mesh's.
    const WindowNumbers& w = *part.window;
    check_window_holds(w, part.mesh.structure->cells, cells);
    for (Index& c : pm.global_cell) c = w.global_cell[static_cast<std::size_t>(c)];
    for (Index& v : pm.global_node) v = w.global_node[static_cast<std::size_t>(v)];
    whole_nodes = w.whole_nodes;
    whole_cells = w.whole_cells;
  }

  std::vector<dofs::Continuity> continuity;
  for (Index c : cells) continuity.push_back(part.dofmap.continuity(c));
  dofs::DofMap dofmap(pm.mesh, part.dofmap.block_size(), continuity);
  std::vector<int> piece_owner;
  for (Index c : cells) piece_owner.push_back(owner[static_cast<std::size_t>(c)]);
  partition::PieceDofs piece_dofs =
      partition::piece_dofs(dofmap, pm, piece_owner, part_number, whole_nodes, whole_cells);
  // Dof names (dof_name) are key × dim + component.
  if (static_cast<long long>(piece_dofs.key_space) * part.dim() > std::numeric_limits<Index>::max())
    throw Error(
        fmt::format("piece dofs: keys up to {} name dofs up to {} × {}, beyond PETSc's 32-bit indices; a "
                    "PETSc built with 64-bit indices would be needed",
                    piece_dofs.key_space, piece_dofs.key_space, part.dim()));

  std::optional<NonlocalModel> nl;
  if (part.nonlocal) {
    const NonlocalModel& whole = *part.nonlocal;
    nl = NonlocalModel{whole.material,
                       whole.kernel,
                       whole.calibration,
                       whole.discrete_factor,
                       whole.alpha,
                       bonds::points_of_cells(whole.points, cells),
                       whole.graph.renumbered(cells),
                       {},
                       {at_cells(whole.morph.purely_nonlocal, cells), whole.morph.morphing_cells}};
    nl->cuts = bonds::CutNeighborhood(pm.mesh, nl->points.bond_reach(nl->kernel.horizon));
  }
  std::optional<DamageModel> damage = part.damage;
  if (damage) damage->cell_law = at_cells(damage->cell_law, cells);

  Discretization disc{
      part.config,
      std::move(pm.mesh),
      std::move(dofmap),
      part.rule,
      part.stiffness.cells_of(cells),
      part.scale,
      std::move(nl),
      std::move(damage),
      part.computed_cells.empty() ? std::vector<char>(cells.size(), 1) : at_cells(part.computed_cells, cells),
      {},
      std::move(any_over_processes),
      std::make_shared<const PieceNumbers>(PieceNumbers{std::move(pm.global_cell), std::move(pm.global_node),
                                                        std::move(piece_owner), part_number,
                                                        std::move(piece_dofs)})};
  return disc;
}

std::shared_ptr<const PieceSource> keep_source(Discretization part, std::vector<int> owner) {
  part.stiffness = fem::ConstitutiveField(0, 0, 0);
  if (part.nonlocal) {
    NonlocalModel& nl = *part.nonlocal;
    nl.points = {};
    nl.graph = {};
    nl.cuts = {};
    nl.morph = {};
  }
  return std::make_shared<const PieceSource>(PieceSource{std::move(part), std::move(owner)});
}

Discretization rebuild_piece_for_alpha(const Discretization& piece, alpha::AlphaField alpha) {
  PERIMORPH_ASSERT(piece.piece && piece.source, "rebuild_piece_for_alpha needs a piece with its source part");
  Discretization part = rebuild_for_alpha(piece.source->part, std::move(alpha));
  Discretization next = cut_to_piece(part, piece.source->owner, piece.piece->part, piece.any_over_processes);
  next.source = keep_source(std::move(part), piece.source->owner);
  return next;
}

Index PieceNumbers::local_cell(Index c) const {
  const auto it = std::lower_bound(global_cell.begin(), global_cell.end(), c);
  return it != global_cell.end() && *it == c ? static_cast<Index>(it - global_cell.begin()) : -1;
}

Index global_cell(const Discretization& disc, Index c) {
  return disc.piece ? disc.piece->global_cell[static_cast<std::size_t>(c)] : c;
}

Index local_cell(const Discretization& disc, Index global) {
  return disc.piece ? disc.piece->local_cell(global) : global;
}

Index dof_name(const Discretization& disc, Index dof) {
  if (!disc.piece) return dof;
  const Index dim = disc.dim();
  return disc.piece->dofs.key[static_cast<std::size_t>(dof / dim)] * dim + dof % dim;
}

Index dof_of_name(const Discretization& disc, Index name) {
  if (!disc.piece) return name;
  const Index dim = disc.dim();
  const auto& keys = disc.piece->dofs.key;
  const auto it = std::lower_bound(keys.begin(), keys.end(), name / dim);
  return it != keys.end() && *it == name / dim ? static_cast<Index>(it - keys.begin()) * dim + name % dim
                                               : -1;
}

std::vector<char> cells_of_process(const Discretization& disc, int processes, int process) {
  if (processes == 1 || !disc.piece) return partition::cells_of_part(disc.mesh, processes, process);
  std::vector<char> mine(disc.piece->owner.size());
  for (std::size_t c = 0; c < mine.size(); ++c) mine[c] = disc.piece->of_part(static_cast<Index>(c)) ? 1 : 0;
  return mine;
}

Index PieceNumbers::part_cells() const {
  return static_cast<Index>(std::count(owner.begin(), owner.end(), part));
}

}  // namespace perimorph::setup

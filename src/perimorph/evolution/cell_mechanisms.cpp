#include "perimorph/evolution/cell_mechanisms.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace perimorph::evolution {

namespace {

constexpr double null_tolerance = 1e-10;  ///< of the largest reference diagonal on the cell

}  // namespace

CellsToCheck cells_to_check(const setup::Discretization& model, std::span<const Index> cells) {
  const int dim = model.dim();
  CellsToCheck out;
  out.dofs.reserve(cells.size());
  for (Index c : cells) {
    auto& dofs = out.dofs.emplace_back();
    for (Index node : model.dofmap.cell_nodes(c))
      for (int d = 0; d < dim; ++d) dofs.push_back(node * dim + d);
    out.centroid.push_back(model.mesh.cell_centroid(c));
  }
  return out;
}

CellsToCheck cells_to_check_over_pieces(const setup::Discretization& model, std::span<const Index> mine) {
  // Each cell as [whole-mesh cell, centroid (3), dof count, dof names...].
  const CellsToCheck local = cells_to_check(model, mine);
  std::vector<double> packed;
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const Vec3& x = local.centroid[k];
    packed.insert(packed.end(), {static_cast<double>(setup::global_cell(model, mine[k])), x.x(), x.y(), x.z(),
                                 static_cast<double>(local.dofs[k].size())});
    for (Index d : local.dofs[k]) packed.push_back(static_cast<double>(setup::dof_name(model, d)));
  }
  const std::vector<double> all = la::all_gather(packed);
  std::vector<std::pair<Index, std::size_t>> order;  // (whole-mesh cell, record)
  for (std::size_t at = 0; at < all.size(); at += 5 + static_cast<std::size_t>(all[at + 4]))
    order.emplace_back(static_cast<Index>(all[at]), at);
  std::sort(order.begin(), order.end());
  order.erase(std::unique(order.begin(), order.end(),
                          [](const auto& a, const auto& b) { return a.first == b.first; }),
              order.end());
  CellsToCheck out;
  for (const auto& [cell, at] : order) {
    out.centroid.emplace_back(all[at + 1], all[at + 2], all[at + 3]);
    auto& dofs = out.dofs.emplace_back();
    for (std::size_t j = 0; j < static_cast<std::size_t>(all[at + 4]); ++j)
      dofs.push_back(static_cast<Index>(all[at + 5 + j]));
  }
  return out;
}

CellMechanisms find_cell_mechanisms(const setup::Discretization& model, const la::Matrix& A,
                                    const la::DofValuesAt& reference_diagonal, std::span<const Index> cells,
                                    std::span<const Index> held, const la::DofValuesAt& force) {
  return find_cell_mechanisms(
      cells_to_check(model, cells), [&A](std::span<const std::vector<Index>> sets) { return A.blocks(sets); },
      reference_diagonal, held, force);
}

CellMechanisms find_cell_mechanisms(const CellsToCheck& cells, const BlocksAt& blocks,
                                    const la::DofValuesAt& reference_diagonal, std::span<const Index> held,
                                    const la::DofValuesAt& force) {
  std::vector<Index> excluded(held.begin(), held.end());
  CellMechanisms out;
  // The cells' whole blocks, and the two vectors at their dofs, a chunk at a
  // time (one gathering each per chunk when A is spread over processes); each
  // cell takes the rows and columns not excluded.
  constexpr std::size_t chunk = 1024;
  std::vector<std::vector<Index>> cell_dofs;
  std::vector<Eigen::MatrixXd> cell_blocks;
  std::vector<Index> chunk_dofs;  // the chunk's cells' dofs, sorted, unique
  std::vector<double> chunk_reference, chunk_force;
  auto at = [&](const std::vector<double>& values, Index dof) {
    return values[static_cast<std::size_t>(std::lower_bound(chunk_dofs.begin(), chunk_dofs.end(), dof) -
                                           chunk_dofs.begin())];
  };
  std::vector<Index> dofs;
  std::vector<Eigen::Index> kept;
  const std::size_t count = cells.dofs.size();
  for (std::size_t ci = 0; ci < count; ++ci) {
    if (ci % chunk == 0) {
      cell_dofs.assign(cells.dofs.begin() + static_cast<std::ptrdiff_t>(ci),
                       cells.dofs.begin() + static_cast<std::ptrdiff_t>(std::min(count, ci + chunk)));
      cell_blocks = blocks(cell_dofs);
      chunk_dofs.clear();
      for (const auto& all : cell_dofs) chunk_dofs.insert(chunk_dofs.end(), all.begin(), all.end());
      std::sort(chunk_dofs.begin(), chunk_dofs.end());
      chunk_dofs.erase(std::unique(chunk_dofs.begin(), chunk_dofs.end()), chunk_dofs.end());
      chunk_reference = reference_diagonal(chunk_dofs);
      if (force) chunk_force = force(chunk_dofs);
    }
    dofs.clear();
    kept.clear();
    const std::vector<Index>& all = cell_dofs[ci % chunk];
    for (std::size_t a = 0; a < all.size(); ++a) {
      const Index dof = all[a];
      if (std::binary_search(excluded.begin(), excluded.end(), dof)) continue;
      dofs.push_back(dof);
      kept.push_back(static_cast<Eigen::Index>(a));
    }
    if (dofs.empty()) continue;
    double scale = 0.0;
    for (Index d : dofs) scale = std::max(scale, std::abs(at(chunk_reference, d)));
    const Eigen::MatrixXd block = cell_blocks[ci % chunk](kept, kept);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (block + block.transpose()));
    const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
    Eigen::Index k = 0;
    while (k < lambda.size() && lambda[k] <= null_tolerance * scale) ++k;
    if (k == 0) continue;
    const Eigen::MatrixXd modes = eig.eigenvectors().leftCols(k);  // orthonormal columns
    if (force) {
      Eigen::VectorXd f(static_cast<Eigen::Index>(dofs.size()));
      for (std::size_t a = 0; a < dofs.size(); ++a)
        f[static_cast<Eigen::Index>(a)] = at(chunk_force, dofs[a]);
      const double work = (modes.transpose() * f).norm();
      if (work > 1e-10 * f.norm() && work > 0.0) {
        const Vec3& x = cells.centroid[ci];
        throw Error(fmt::format(
            "bond failures have left a motion of the cell at ({:g}, {:g}, {:g}) that no intact bond resists, "
            "and the applied forces on its nodes do work on it: there is no quasi-static equilibrium",
            x.x(), x.y(), x.z()));
      }
    }
    // The dofs of the k largest pivots of modesᵀ: the modes restricted to them are invertible.
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(modes.transpose());
    std::vector<Index> pins;
    for (Eigen::Index j = 0; j < k; ++j)
      pins.push_back(dofs[static_cast<std::size_t>(qr.colsPermutation().indices()[j])]);
    ++out.cells;
    out.modes += static_cast<std::size_t>(k);
    for (Index p : pins) excluded.insert(std::upper_bound(excluded.begin(), excluded.end(), p), p);
    out.pins.insert(out.pins.end(), pins.begin(), pins.end());
  }
  std::sort(out.pins.begin(), out.pins.end());
  return out;
}

}  // namespace perimorph::evolution

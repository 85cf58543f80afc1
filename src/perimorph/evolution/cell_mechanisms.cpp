#include "perimorph/evolution/cell_mechanisms.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace perimorph::evolution {

namespace {

constexpr double null_tolerance = 1e-10;  ///< of the largest reference diagonal on the cell

}  // namespace

CellMechanisms find_cell_mechanisms(const setup::Discretization& model, const la::Matrix& A,
                                    const la::DofValuesAt& reference_diagonal, std::span<const Index> cells,
                                    std::span<const Index> held, const la::DofValuesAt& force) {
  const int dim = model.dim();
  const auto& dm = model.dofmap;
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
  for (std::size_t ci = 0; ci < cells.size(); ++ci) {
    if (ci % chunk == 0) {
      cell_dofs.clear();
      for (std::size_t k = ci; k < std::min(cells.size(), ci + chunk); ++k) {
        auto& all = cell_dofs.emplace_back();
        for (Index node : dm.cell_nodes(cells[k]))
          for (int d = 0; d < dim; ++d) all.push_back(node * dim + d);
      }
      cell_blocks = A.blocks(cell_dofs);
      chunk_dofs.clear();
      for (const auto& all : cell_dofs) chunk_dofs.insert(chunk_dofs.end(), all.begin(), all.end());
      std::sort(chunk_dofs.begin(), chunk_dofs.end());
      chunk_dofs.erase(std::unique(chunk_dofs.begin(), chunk_dofs.end()), chunk_dofs.end());
      chunk_reference = reference_diagonal(chunk_dofs);
      if (force) chunk_force = force(chunk_dofs);
    }
    const Index c = cells[ci];
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
        const Vec3 x = model.mesh.cell_centroid(c);
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

#pragma once
// Which pre-crack pieces a bond can cross, by cell: a mesh file's pre-crack
// has hundreds of pieces (mesh::split_along_faces), and testing every bond
// against all of them costs more than the bond itself. THEORY §4 (bonds
// through a cut are removed).

#include "perimorph/core/cut.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <span>
#include <vector>

namespace perimorph::bonds {

/// The axis-aligned box of a cut (its parallelogram's corners).
std::pair<Vec3, Vec3> cut_box(const Cut& cut);

/// For each cell, the cuts of the mesh whose box comes within `reach` of the
/// cell's node box. A bond no longer than `reach` from a point of the cell
/// lies in that widened box, so every cut it crosses is in near(cell): the
/// bond's cut test against near(cell) decides as against all of Mesh::cuts.
class CutNeighborhood {
 public:
  CutNeighborhood() = default;
  CutNeighborhood(const mesh::Mesh& mesh, double reach);

  /// The cuts near cell c (empty: no bond of c crosses a cut).
  std::span<const Cut> near(Index c) const {
    if (offsets_.empty()) return {};
    const auto k = static_cast<std::size_t>(c);
    return {cuts_.data() + offsets_[k], offsets_[k + 1] - offsets_[k]};
  }

  /// The cuts a bond between a point of cell e and one of cell f can cross:
  /// those of near(e) whose box meets the box of both cells' nodes (the bond
  /// lies in it), copied into `buffer` (reused; the span views it).
  std::span<const Cut> near_pair(Index e, Index f, std::vector<Cut>& buffer) const;

 private:
  std::vector<std::size_t> offsets_;  ///< per cell, into cuts_ (empty when the mesh has no cut)
  std::vector<Cut> cuts_;
  std::vector<std::pair<Vec3, Vec3>> cut_boxes_;   ///< of cuts_
  std::vector<std::pair<Vec3, Vec3>> cell_boxes_;  ///< of each cell's nodes
};

/// The cuts of `cuts` whose box comes within `reach` of x (those a bond of
/// length ≤ reach from x can cross).
std::vector<Cut> cuts_near_point(std::span<const Cut> cuts, const Vec3& x, double reach);

}  // namespace perimorph::bonds

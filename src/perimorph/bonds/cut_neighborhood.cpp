#include "perimorph/bonds/cut_neighborhood.hpp"

namespace perimorph::bonds {

namespace {
bool overlap(const std::pair<Vec3, Vec3>& a, const Vec3& lo, const Vec3& hi) {
  return (a.first.array() <= hi.array()).all() && (a.second.array() >= lo.array()).all();
}
/// The reach with a margin for the round-off of the bond cutoff (peridynamics/bond_filter.hpp).
double widened(double reach) {
  return reach * (1.0 + 1e-9);
}
}  // namespace

std::pair<Vec3, Vec3> cut_box(const Cut& cut) {
  Vec3 lo = cut.origin, hi = cut.origin;
  for (const Vec3& corner : {Vec3(cut.origin + cut.edge1), Vec3(cut.origin + cut.edge2),
                             Vec3(cut.origin + cut.edge1 + cut.edge2)}) {
    lo = lo.cwiseMin(corner);
    hi = hi.cwiseMax(corner);
  }
  return {lo, hi};
}

CutNeighborhood::CutNeighborhood(const mesh::Mesh& mesh, double reach) {
  if (mesh.cuts.empty()) return;
  std::vector<std::pair<Vec3, Vec3>> boxes;
  for (const Cut& cut : mesh.cuts) boxes.push_back(cut_box(cut));
  offsets_.reserve(static_cast<std::size_t>(mesh.num_cells()) + 1);
  offsets_.push_back(0);
  for (Index c = 0; c < mesh.num_cells(); ++c) {
    Vec3 lo = mesh.node(mesh.cell(c)[0]), hi = lo;
    for (Index n : mesh.cell(c)) {
      lo = lo.cwiseMin(mesh.node(n));
      hi = hi.cwiseMax(mesh.node(n));
    }
    cell_boxes_.emplace_back(lo, hi);
    lo.array() -= widened(reach);
    hi.array() += widened(reach);
    for (std::size_t k = 0; k < boxes.size(); ++k)
      if (overlap(boxes[k], lo, hi)) {
        cuts_.push_back(mesh.cuts[k]);
        cut_boxes_.push_back(boxes[k]);
      }
    offsets_.push_back(cuts_.size());
  }
}

std::span<const Cut> CutNeighborhood::near_pair(Index e, Index f, std::vector<Cut>& buffer) const {
  buffer.clear();
  if (offsets_.empty()) return {};
  const auto ke = static_cast<std::size_t>(e), kf = static_cast<std::size_t>(f);
  Vec3 lo = cell_boxes_[ke].first.cwiseMin(cell_boxes_[kf].first);
  Vec3 hi = cell_boxes_[ke].second.cwiseMax(cell_boxes_[kf].second);
  // A margin for Cut::crosses' tie rule (a bond through a cut's edge within 1e-12 of it crosses it).
  const double margin = 1e-9 * (hi - lo).maxCoeff();
  lo.array() -= margin;
  hi.array() += margin;
  for (std::size_t k = offsets_[ke]; k < offsets_[ke + 1]; ++k)
    if (overlap(cut_boxes_[k], lo, hi)) buffer.push_back(cuts_[k]);
  return buffer;
}

std::vector<Cut> cuts_near_point(std::span<const Cut> cuts, const Vec3& x, double reach) {
  std::vector<Cut> near;
  const Vec3 lo = x.array() - widened(reach), hi = x.array() + widened(reach);
  for (const Cut& cut : cuts)
    if (overlap(cut_box(cut), lo, hi)) near.push_back(cut);
  return near;
}

}  // namespace perimorph::bonds

#include "perimorph/mesh/cell_type.hpp"

namespace perimorph::mesh {

namespace {
constexpr std::array<std::array<int, 1>, 2> bar_faces{{{0}, {1}}};
constexpr std::array<std::array<int, 2>, 4> quad_faces{{{0, 2}, {1, 3}, {0, 1}, {2, 3}}};
constexpr std::array<std::array<int, 4>, 6> hex_faces{
    {{0, 2, 4, 6}, {1, 3, 5, 7}, {0, 1, 4, 5}, {2, 3, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}}};
}  // namespace

std::span<const int> face_nodes(CellType t, int f) {
  switch (t) {
    case CellType::bar2:
      return bar_faces.at(static_cast<std::size_t>(f));
    case CellType::quad4:
      return quad_faces.at(static_cast<std::size_t>(f));
    case CellType::hex8:
      return hex_faces.at(static_cast<std::size_t>(f));
  }
  return {};
}

}  // namespace perimorph::mesh

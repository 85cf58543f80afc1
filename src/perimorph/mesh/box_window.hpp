#pragma once
// A window of a box mesh (issue 17, item 1): the cells of an index range of
// the grid and their nodes, built from the grid alone, as
// part_mesh(make_box(spec), those cells) would cut them from the whole mesh,
// array for array and bit for bit (nodes by box_node), with no array as long
// as the whole mesh. What a process of a distributed run builds its part on.

#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/part_mesh.hpp"

#include <array>

namespace perimorph::mesh {

/// The cells (i, j, k) of the box of `spec` with lo[d] ≤ i_d < hi[d] (only
/// the first spec.dim axes count; the others are [0, 1)), numbered locally in
/// the whole box's order, with their global numbers: part_mesh(make_box(spec),
/// cells). Throws Error for an empty or out-of-box range.
PartMesh make_box_window(const BoxSpec& spec, std::array<Index, 3> lo, std::array<Index, 3> hi);

/// The global numbers of the cells of that window, ascending (its
/// PartMesh::global_cell), without building it.
std::vector<Index> box_window_cells(const BoxSpec& spec, std::array<Index, 3> lo, std::array<Index, 3> hi);

}  // namespace perimorph::mesh

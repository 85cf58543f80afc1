#pragma once
// VTK XML parallel unstructured grid index (.pvtu): the arrays every piece
// holds and the pieces' files, so ParaView reads the pieces written by the
// processes of a distributed run as one grid (issue 17, item 3).

#include "perimorph/io/grid.hpp"

#include <span>
#include <string>

namespace perimorph::io {

/// Writes `path` (under a temporary name renamed into place, as write_vtu):
/// PPoints Float64 ×3, a PPointData/PCellData entry Float64 per field of
/// `layout` (its names and components; its values are not read), and one
/// <Piece Source="..."/> per entry of `pieces`, file names relative to the
/// .pvtu's directory (XML-escaped). Each piece must be a VTU written by
/// write_vtu from a grid with the same fields in the same order.
/// Throws std::logic_error if `pieces` is empty or a name is empty,
/// perimorph::Error if the file cannot be written.
void write_pvtu(const std::string& path, const UnstructuredGrid& layout, std::span<const std::string> pieces);

}  // namespace perimorph::io

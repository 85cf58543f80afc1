#include "perimorph/io/pvtu_writer.hpp"

#include "perimorph/io/atomic_file.hpp"
#include "perimorph/io/xml_escape.hpp"

#include <fmt/format.h>

#include <iterator>
#include <stdexcept>
#include <vector>

namespace perimorph::io {

namespace {

void append_declarations(std::string& out, const char* tag, const std::vector<Field>& fields) {
  fmt::format_to(std::back_inserter(out), "    <{}>\n", tag);
  for (const Field& f : fields)
    fmt::format_to(std::back_inserter(out),
                   "      <PDataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                   xml_escape(f.name), f.components);
  fmt::format_to(std::back_inserter(out), "    </{}>\n", tag);
}

}  // namespace

void write_pvtu(const std::string& path, const UnstructuredGrid& layout,
                std::span<const std::string> pieces) {
  if (pieces.empty()) throw std::logic_error("write_pvtu: no pieces");
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out +=
      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  out += "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  append_declarations(out, "PPointData", layout.point_data);
  append_declarations(out, "PCellData", layout.cell_data);
  out += "    <PPoints>\n";
  out += "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n";
  out += "    </PPoints>\n";
  for (const std::string& piece : pieces) {
    if (piece.empty()) throw std::logic_error("write_pvtu: a piece without a file name");
    fmt::format_to(std::back_inserter(out), "    <Piece Source=\"{}\"/>\n", xml_escape(piece));
  }
  out += "  </PUnstructuredGrid>\n";
  out += "</VTKFile>\n";
  AtomicFile file(path);
  file.write(out);
  file.commit();
}

UnstructuredGrid grid_piece(const UnstructuredGrid& whole, std::span<const char> cells) {
  const auto npc = static_cast<std::size_t>(whole.nodes_per_cell);
  const std::size_t num_cells = npc == 0 ? 0 : whole.connectivity.size() / npc;
  if (cells.size() != num_cells)
    throw std::logic_error(
        fmt::format("grid_piece: {} cell flags for a grid of {} cells", cells.size(), num_cells));
  constexpr Index unused = -1;
  std::vector<Index> new_point(whole.points.size(), unused);
  for (std::size_t c = 0; c < num_cells; ++c)
    if (cells[c])
      for (std::size_t k = 0; k < npc; ++k)
        new_point[static_cast<std::size_t>(whole.connectivity[c * npc + k])] = 0;
  UnstructuredGrid piece;
  piece.nodes_per_cell = whole.nodes_per_cell;
  piece.cell_type = whole.cell_type;
  std::vector<std::size_t> kept_points;
  for (std::size_t p = 0; p < whole.points.size(); ++p)
    if (new_point[p] != unused) {
      new_point[p] = static_cast<Index>(kept_points.size());
      kept_points.push_back(p);
      piece.points.push_back(whole.points[p]);
    }
  std::vector<std::size_t> kept_cells;
  for (std::size_t c = 0; c < num_cells; ++c)
    if (cells[c]) {
      kept_cells.push_back(c);
      for (std::size_t k = 0; k < npc; ++k)
        piece.connectivity.push_back(new_point[static_cast<std::size_t>(whole.connectivity[c * npc + k])]);
    }
  auto restrict = [](const std::vector<Field>& fields, const std::vector<std::size_t>& kept) {
    std::vector<Field> out;
    for (const Field& f : fields) {
      Field g{f.name, f.components, {}};
      const auto nc = static_cast<std::size_t>(f.components);
      g.values.reserve(kept.size() * nc);
      for (std::size_t e : kept)
        g.values.insert(g.values.end(), f.values.begin() + static_cast<std::ptrdiff_t>(e * nc),
                        f.values.begin() + static_cast<std::ptrdiff_t>((e + 1) * nc));
      out.push_back(std::move(g));
    }
    return out;
  };
  piece.point_data = restrict(whole.point_data, kept_points);
  piece.cell_data = restrict(whole.cell_data, kept_cells);
  return piece;
}

}  // namespace perimorph::io

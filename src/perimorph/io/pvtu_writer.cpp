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

}  // namespace perimorph::io

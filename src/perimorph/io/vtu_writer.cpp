#include "perimorph/io/vtu_writer.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/io/atomic_file.hpp"
#include "perimorph/io/xml_escape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <vector>

namespace perimorph::io {

// The binary arrays are memcpy'd from host memory and declared LittleEndian.
static_assert(std::endian::native == std::endian::little, "write_vtu assumes a little-endian host");

namespace {

constexpr std::string_view kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Incremental base64 encoder appending to a string; bytes may arrive in any
/// number of put() calls, finish() pads the last group.
class Base64Encoder {
 public:
  explicit Base64Encoder(std::string& out) : out_(out) {}

  void put(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      group_[pending_++] = p[i];
      if (pending_ == 3) emit(3);
    }
  }

  void finish() {
    if (pending_ == 0) return;
    for (std::size_t i = pending_; i < 3; ++i) group_[i] = 0;
    emit(pending_);
  }

 private:
  void emit(std::size_t n) {
    const unsigned v = (unsigned{group_[0]} << 16) | (unsigned{group_[1]} << 8) | unsigned{group_[2]};
    out_.push_back(kAlphabet[(v >> 18) & 63u]);
    out_.push_back(kAlphabet[(v >> 12) & 63u]);
    out_.push_back(n > 1 ? kAlphabet[(v >> 6) & 63u] : '=');
    out_.push_back(n > 2 ? kAlphabet[v & 63u] : '=');
    pending_ = 0;
  }

  std::string& out_;  ///< non-owning: the caller's output string
  std::array<std::uint8_t, 3> group_{};
  std::size_t pending_ = 0;
};

template <class T>
constexpr std::string_view vtk_type_name() {
  if constexpr (std::is_same_v<T, double>)
    return "Float64";
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return "Int64";
  else {
    static_assert(std::is_same_v<T, std::uint8_t>);
    return "UInt8";
  }
}

/// Appends one complete <DataArray> element (own line, `indent` spaces) to out.
/// components <= 0 omits the NumberOfComponents attribute.
template <class T>
void append_data_array(std::string& out, int indent, std::string_view name, int components,
                       std::span<const T> values, VtuEncoding encoding) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  fmt::format_to(std::back_inserter(out), "{}<DataArray type=\"{}\" Name=\"{}\"", pad, vtk_type_name<T>(),
                 xml_escape(name));
  if (components > 0) fmt::format_to(std::back_inserter(out), " NumberOfComponents=\"{}\"", components);
  if (encoding == VtuEncoding::base64) {
    out += " format=\"binary\">\n";
    out += pad;
    out += "  ";
    Base64Encoder enc(out);
    const std::uint64_t nbytes = values.size_bytes();
    enc.put(&nbytes, sizeof nbytes);
    enc.put(values.data(), values.size_bytes());
    enc.finish();
    out += "\n";
  } else {
    out += " format=\"ascii\">\n";
    // One line per entity for 3+ components, otherwise several per line.
    const auto ncomp = static_cast<std::size_t>(std::max(components, 1));
    const std::size_t per_line = std::is_same_v<T, double> ? ncomp * std::max<std::size_t>(1, 6 / ncomp) : 16;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i % per_line == 0) {
        if (i > 0) out += "\n";
        out += pad;
        out += "  ";
      } else {
        out += " ";
      }
      if constexpr (std::is_same_v<T, std::uint8_t>)
        fmt::format_to(std::back_inserter(out), "{}", unsigned{values[i]});
      else
        fmt::format_to(std::back_inserter(out), "{}", values[i]);
    }
    if (!values.empty()) out += "\n";
  }
  out += pad;
  out += "</DataArray>\n";
}

/// VTK local node k of a cell is perimorph local node order[k].
std::span<const int> vtk_node_order(VtkCell t) {
  static constexpr std::array<int, 1> vertex{0};
  static constexpr std::array<int, 2> line{0, 1};
  static constexpr std::array<int, 4> quad{0, 1, 3, 2};
  static constexpr std::array<int, 8> hex{0, 1, 3, 2, 4, 5, 7, 6};
  switch (t) {
    case VtkCell::vertex:
      return vertex;
    case VtkCell::line:
      return line;
    case VtkCell::quad:
      return quad;
    case VtkCell::hexahedron:
      return hex;
  }
  throw std::logic_error(fmt::format("write_vtu: unknown VtkCell value {}", static_cast<int>(t)));
}

void validate_fields(const std::vector<Field>& fields, std::size_t count, std::string_view kind) {
  std::set<std::string> names;
  for (const Field& f : fields) {
    if (f.name.empty()) throw std::logic_error(fmt::format("write_vtu: {} field with empty name", kind));
    if (!names.insert(f.name).second)
      throw std::logic_error(fmt::format("write_vtu: duplicate {} field '{}'", kind, f.name));
    if (f.components < 1)
      throw std::logic_error(
          fmt::format("write_vtu: {} field '{}' has {} components (need >= 1)", kind, f.name, f.components));
    const std::size_t expected = count * static_cast<std::size_t>(f.components);
    if (f.values.size() != expected)
      throw std::logic_error(fmt::format("write_vtu: {} field '{}' has {} values, expected {} ({} x {})",
                                         kind, f.name, f.values.size(), expected, count, f.components));
  }
}

/// Checks the UnstructuredGrid contract; returns the number of cells.
std::size_t validate(const UnstructuredGrid& g) {
  const int npc = vtk_nodes_per_cell(g.cell_type);
  if (npc == 0 || g.nodes_per_cell != npc)
    throw std::logic_error(fmt::format("write_vtu: nodes_per_cell = {} but VTK cell type {} has {} nodes",
                                       g.nodes_per_cell, static_cast<int>(g.cell_type), npc));
  const auto unpc = static_cast<std::size_t>(npc);
  if (g.connectivity.size() % unpc != 0)
    throw std::logic_error(
        fmt::format("write_vtu: connectivity size {} is not a multiple of {}", g.connectivity.size(), npc));
  const std::size_t num_points = g.points.size();
  for (std::size_t i = 0; i < g.connectivity.size(); ++i) {
    const Index n = g.connectivity[i];
    if (n < 0 || static_cast<std::size_t>(n) >= num_points)
      throw std::logic_error(
          fmt::format("write_vtu: connectivity[{}] = {} outside [0, {})", i, n, num_points));
  }
  const std::size_t num_cells = g.connectivity.size() / unpc;
  validate_fields(g.point_data, num_points, "point");
  validate_fields(g.cell_data, num_cells, "cell");
  return num_cells;
}

/// The arrays of `fields`, each handed to `flush` once encoded: one array's
/// encoding in memory at a time.
template <class Flush>
void append_fields(std::string& out, std::string_view tag, const std::vector<Field>& fields,
                   VtuEncoding encoding, Flush&& flush) {
  fmt::format_to(std::back_inserter(out), "      <{}>\n", tag);
  for (const Field& f : fields) {
    append_data_array<double>(out, 8, f.name, f.components, f.values, encoding);
    flush();
  }
  fmt::format_to(std::back_inserter(out), "      </{}>\n", tag);
}

}  // namespace

std::string base64_encode(std::span<const std::uint8_t> bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  Base64Encoder enc(out);
  enc.put(bytes.data(), bytes.size());
  enc.finish();
  return out;
}

void write_vtu(const std::string& path, const UnstructuredGrid& grid, VtuEncoding encoding) {
  const std::size_t num_cells = validate(grid);
  const std::size_t num_points = grid.points.size();
  const auto npc = static_cast<std::size_t>(grid.nodes_per_cell);

  // The file is assembled in memory array by array and streamed out, so
  // peak extra memory is about one array's encoded size.
  AtomicFile file(path);
  std::string out;
  auto flush = [&] {
    file.write(out);
    out.clear();
  };

  out += "<?xml version=\"1.0\"?>\n";
  out +=
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  fmt::format_to(std::back_inserter(out), "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                 num_points, num_cells);
  append_fields(out, "PointData", grid.point_data, encoding, flush);
  append_fields(out, "CellData", grid.cell_data, encoding, flush);

  {
    std::vector<double> xyz;
    xyz.reserve(3 * num_points);
    for (const Vec3& p : grid.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    out += "      <Points>\n";
    append_data_array<double>(out, 8, "Points", 3, xyz, encoding);
    out += "      </Points>\n";
    flush();
  }

  out += "      <Cells>\n";
  {
    const std::span<const int> order = vtk_node_order(grid.cell_type);
    std::vector<std::int64_t> conn(grid.connectivity.size());
    for (std::size_t c = 0; c < num_cells; ++c)
      for (std::size_t k = 0; k < npc; ++k)
        conn[c * npc + k] = grid.connectivity[c * npc + static_cast<std::size_t>(order[k])];
    append_data_array<std::int64_t>(out, 8, "connectivity", 0, conn, encoding);
    flush();
  }
  {
    std::vector<std::int64_t> offsets(num_cells);
    for (std::size_t c = 0; c < num_cells; ++c) offsets[c] = static_cast<std::int64_t>((c + 1) * npc);
    append_data_array<std::int64_t>(out, 8, "offsets", 0, offsets, encoding);
    const std::vector<std::uint8_t> types(num_cells, static_cast<std::uint8_t>(grid.cell_type));
    append_data_array<std::uint8_t>(out, 8, "types", 0, types, encoding);
  }
  out += "      </Cells>\n";
  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
  flush();
  file.commit();
}

}  // namespace perimorph::io

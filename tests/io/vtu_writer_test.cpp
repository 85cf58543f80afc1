// Output stage: .vtu files are checked by a minimal parse written here (not
// the writer's code) and by the independent Python reader python/read_vtu.py;
// .pvd and .csv files are read back as text.
#include "perimorph/io/vtu_writer.hpp"
#include "perimorph/io/csv_table.hpp"
#include "perimorph/io/pvd_writer.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace perimorph::io {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Independent base64 decoder (ignores whitespace, stops at '=').
std::vector<std::uint8_t> b64decode(const std::string& text) {
  std::vector<std::uint8_t> out;
  unsigned acc = 0;
  int bits = 0;
  for (char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else if (c == '=')
      break;
    if (v < 0) continue;
    acc = (acc << 6) | static_cast<unsigned>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xFFu));
    }
  }
  return out;
}

int attribute(const std::string& xml, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(xml, m, std::regex(name + "=\"(\\d+)\""))) return -1;
  return std::stoi(m[1].str());
}

/// Text content of the DataArray called `name`, and its format attribute.
std::pair<std::string, std::string> data_array(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const std::size_t open_end = xml.find('>', at);
  const std::size_t close = xml.find("</DataArray>", open_end);
  std::smatch m;
  const std::string tag = xml.substr(at, open_end - at);
  std::regex_search(tag, m, std::regex("format=\"(\\w+)\""));
  return {xml.substr(open_end + 1, close - open_end - 1), m[1].str()};
}

/// Decodes a binary DataArray; checks the UInt64 byte-count header.
template <class T>
std::vector<T> binary_values(const std::string& xml, const std::string& name) {
  const auto [text, format] = data_array(xml, name);
  EXPECT_EQ(format, "binary") << name;
  const std::vector<std::uint8_t> raw = b64decode(text);
  std::uint64_t nbytes = 0;
  EXPECT_GE(raw.size(), sizeof nbytes) << name;
  if (raw.size() < sizeof nbytes) return {};
  std::memcpy(&nbytes, raw.data(), sizeof nbytes);
  EXPECT_EQ(nbytes, raw.size() - sizeof nbytes) << name;
  std::vector<T> v((raw.size() - sizeof nbytes) / sizeof(T));
  std::memcpy(v.data(), raw.data() + sizeof nbytes, v.size() * sizeof(T));
  return v;
}

std::vector<double> ascii_values(const std::string& xml, const std::string& name) {
  const auto [text, format] = data_array(xml, name);
  EXPECT_EQ(format, "ascii") << name;
  std::istringstream in(text);
  std::vector<double> v;
  for (std::string tok; in >> tok;) v.push_back(std::strtod(tok.c_str(), nullptr));
  return v;
}

/// Structured grid of n[0] x n[1] x n[2] cells (n[d] = 0: dimension unused),
/// points lexicographic, cells in perimorph's local node order.
UnstructuredGrid box_grid(int nx, int ny, int nz) {
  const int dim = nz > 0 ? 3 : ny > 0 ? 2 : 1;
  const int px = nx + 1, py = dim >= 2 ? ny + 1 : 1, pz = dim == 3 ? nz + 1 : 1;
  UnstructuredGrid g;
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i) g.points.emplace_back(0.5 * i, 0.25 * j, 2.0 * k);
  const int cx = nx, cy = dim >= 2 ? ny : 1, cz = dim == 3 ? nz : 1;
  for (int k = 0; k < cz; ++k)
    for (int j = 0; j < cy; ++j)
      for (int i = 0; i < cx; ++i)
        for (int a = 0; a < (1 << dim); ++a)
          g.connectivity.push_back((i + (a & 1)) + px * ((j + ((a >> 1) & 1)) + py * (k + ((a >> 2) & 1))));
  g.cell_type = dim == 3 ? VtkCell::hexahedron : dim == 2 ? VtkCell::quad : VtkCell::line;
  g.nodes_per_cell = 1 << dim;
  const std::size_t np = g.points.size(), nc = g.connectivity.size() / static_cast<std::size_t>(1 << dim);
  Field u{"displacement", 3, {}}, d{"damage", 1, {}}, s{"stress", 6, {}};
  for (std::size_t p = 0; p < np; ++p) u.values.insert(u.values.end(), {1e-3 * double(p), 0.1, -1.0 / 3.0});
  for (std::size_t c = 0; c < nc; ++c) d.values.push_back(double(c) / double(nc));
  s.values.assign(6 * nc, 2.5e8);
  g.point_data = {u};
  g.cell_data = {d, s};
  return g;
}

class IoFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("perimorph_io_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Runs python/read_vtu.py with `args`; returns its exit status (0 = ok).
  /// Its stderr goes to dir_/reader.err.
  int read_vtu(const std::string& args) {
    const std::string cmd = "/usr/bin/python3 '" PERIMORPH_SOURCE_DIR "/python/read_vtu.py' " + args +
                            " 2> '" + (dir_ / "reader.err").string() + "'";
    return std::system(cmd.c_str());
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  static bool have_python() { return fs::exists("/usr/bin/python3"); }

  fs::path dir_;
};

TEST(IoBase64, MatchesRfc4648Vectors) {
  auto enc = [](const std::string& s) {
    return base64_encode({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
  };
  EXPECT_EQ(enc(""), "");
  EXPECT_EQ(enc("f"), "Zg==");
  EXPECT_EQ(enc("fo"), "Zm8=");
  EXPECT_EQ(enc("foo"), "Zm9v");
  EXPECT_EQ(enc("foob"), "Zm9vYg==");
  EXPECT_EQ(enc("fooba"), "Zm9vYmE=");
  EXPECT_EQ(enc("foobar"), "Zm9vYmFy");
}

TEST_F(IoFiles, QuadGridBase64RoundTripsAndUsesVtkNodeOrder) {
  const UnstructuredGrid g = box_grid(3, 2, 0);
  write_vtu(file("quad.vtu"), g);
  const std::string xml = slurp(file("quad.vtu"));
  EXPECT_NE(xml.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_EQ(attribute(xml, "NumberOfPoints"), 12);
  EXPECT_EQ(attribute(xml, "NumberOfCells"), 6);
  EXPECT_FALSE(fs::exists(file("quad.vtu.tmp")));

  const auto xyz = binary_values<double>(xml, "Points");
  ASSERT_EQ(xyz.size(), 36u);
  for (std::size_t p = 0; p < 12; ++p)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(xyz[3 * p + std::size_t(c)], g.points[p][c]);
  // First cell's perimorph nodes (0, 1, 4, 5) in VTK's counter-clockwise order.
  const auto conn = binary_values<std::int64_t>(xml, "connectivity");
  ASSERT_EQ(conn.size(), 24u);
  EXPECT_EQ(std::vector<std::int64_t>(conn.begin(), conn.begin() + 4),
            (std::vector<std::int64_t>{0, 1, 5, 4}));
  const auto offsets = binary_values<std::int64_t>(xml, "offsets");
  ASSERT_EQ(offsets.size(), 6u);
  EXPECT_EQ(offsets.back(), 24);
  EXPECT_EQ(binary_values<std::uint8_t>(xml, "types"), std::vector<std::uint8_t>(6, 9));
  EXPECT_EQ(binary_values<double>(xml, "displacement"), g.point_data[0].values);
  EXPECT_EQ(binary_values<double>(xml, "damage"), g.cell_data[0].values);
  EXPECT_EQ(binary_values<double>(xml, "stress").size(), 36u);
}

TEST_F(IoFiles, HexGridAsciiRoundTripsExactly) {
  const UnstructuredGrid g = box_grid(2, 1, 2);
  write_vtu(file("hex.vtu"), g, VtuEncoding::ascii);
  const std::string xml = slurp(file("hex.vtu"));
  EXPECT_EQ(attribute(xml, "NumberOfPoints"), 18);
  EXPECT_EQ(attribute(xml, "NumberOfCells"), 4);
  EXPECT_EQ(ascii_values(xml, "displacement"), g.point_data[0].values);  // shortest round-trip
  EXPECT_EQ(ascii_values(xml, "damage"), g.cell_data[0].values);
  const auto conn = ascii_values(xml, "connectivity");
  ASSERT_EQ(conn.size(), 32u);
  // Perimorph hex 0 = points {0,1,3,4, 6,7,9,10}; VTK order 0,1,3,2,4,5,7,6.
  EXPECT_EQ(std::vector<double>(conn.begin(), conn.begin() + 8),
            (std::vector<double>{0, 1, 4, 3, 6, 7, 10, 9}));
  EXPECT_EQ(ascii_values(xml, "types"), std::vector<double>(4, 12.0));
}

TEST_F(IoFiles, PythonReaderAcceptsEveryEncodingAndCellType) {
  if (!have_python()) GTEST_SKIP() << "/usr/bin/python3 not available";
  const std::string arrays =
      " --expect-point-array displacement:3 --expect-cell-array damage:1"
      " --expect-cell-array stress:6";
  for (VtuEncoding enc : {VtuEncoding::base64, VtuEncoding::ascii}) {
    write_vtu(file("q.vtu"), box_grid(3, 2, 0), enc);
    EXPECT_EQ(
        read_vtu(file("q.vtu") + " --expect-points 12 --expect-cells 6 --expect-cell-type quad" + arrays), 0)
        << slurp(file("reader.err"));
    write_vtu(file("h.vtu"), box_grid(2, 1, 2), enc);
    EXPECT_EQ(read_vtu(file("h.vtu") + " --expect-points 18 --expect-cells 4 --expect-cell-type hexahedron" +
                       arrays),
              0)
        << slurp(file("reader.err"));
    write_vtu(file("b.vtu"), box_grid(5, 0, 0), enc);
    EXPECT_EQ(
        read_vtu(file("b.vtu") + " --expect-points 6 --expect-cells 5 --expect-cell-type line" + arrays), 0)
        << slurp(file("reader.err"));
  }
}

TEST_F(IoFiles, PythonReaderRejectsWrongExpectationsAndBadFiles) {
  if (!have_python()) GTEST_SKIP() << "/usr/bin/python3 not available";
  write_vtu(file("q.vtu"), box_grid(3, 2, 0));
  EXPECT_NE(read_vtu(file("q.vtu") + " --expect-points 13"), 0);
  EXPECT_NE(slurp(file("reader.err")).find("12 points, expected 13"), std::string::npos);
  EXPECT_NE(read_vtu(file("q.vtu") + " --expect-cells 5"), 0);
  EXPECT_NE(read_vtu(file("q.vtu") + " --expect-point-array displacement:2"), 0);
  EXPECT_NE(read_vtu(file("q.vtu") + " --expect-cell-array missing:1"), 0);
  EXPECT_NE(read_vtu(file("q.vtu") + " --expect-cell-type hexahedron"), 0);

  // A quad written in lexicographic order is a bowtie: the reader must notice.
  write_vtu(file("a.vtu"), box_grid(1, 1, 0), VtuEncoding::ascii);
  std::string xml = slurp(file("a.vtu"));
  const std::size_t at = xml.find("0 1 3 2");
  ASSERT_NE(at, std::string::npos);
  xml.replace(at, 7, "0 1 2 3");
  std::ofstream(file("bowtie.vtu")) << xml;
  EXPECT_NE(read_vtu(file("bowtie.vtu")), 0);
  EXPECT_NE(slurp(file("reader.err")).find("self-intersecting"), std::string::npos);

  std::ofstream(file("trunc.vtu")) << xml.substr(0, xml.size() / 2);
  EXPECT_NE(read_vtu(file("trunc.vtu")), 0);
}

TEST_F(IoFiles, InvalidGridsThrowLogicErrorAndWriteNothing) {
  auto expect_throw = [&](const UnstructuredGrid& g) {
    EXPECT_THROW(write_vtu(file("bad.vtu"), g), std::logic_error);
    EXPECT_FALSE(fs::exists(file("bad.vtu")));
  };
  UnstructuredGrid g = box_grid(2, 2, 0);
  g.nodes_per_cell = 8;
  expect_throw(g);
  g = box_grid(2, 2, 0);
  g.connectivity.pop_back();
  expect_throw(g);
  g = box_grid(2, 2, 0);
  g.connectivity[3] = static_cast<Index>(g.points.size());
  expect_throw(g);
  g = box_grid(2, 2, 0);
  g.point_data[0].values.pop_back();
  expect_throw(g);
  g = box_grid(2, 2, 0);
  g.cell_data[1].components = 5;
  expect_throw(g);
  g = box_grid(2, 2, 0);
  g.cell_data[1].name = "damage";
  expect_throw(g);
}

TEST_F(IoFiles, PvdCollectionIsValidAfterEveryAdd) {
  PvdCollection pvd(file("run.pvd"));
  if (have_python()) {
    EXPECT_EQ(read_vtu("--pvd " + file("run.pvd") + " --expect-steps 0"), 0) << slurp(file("reader.err"));
  }
  fs::create_directories(dir_ / "vtu");
  for (int step = 0; step < 3; ++step) {
    const std::string rel = "vtu/step_" + std::to_string(step) + ".vtu";
    write_vtu(file(rel), box_grid(2, 2, 0));
    pvd.add(0.1 * step, rel);
  }
  EXPECT_EQ(pvd.size(), 3u);
  const std::string xml = slurp(file("run.pvd"));
  EXPECT_NE(xml.find("type=\"Collection\""), std::string::npos);
  EXPECT_NE(xml.find("timestep=\"0.2\" group=\"\" part=\"0\" file=\"vtu/step_2.vtu\""), std::string::npos);
  EXPECT_FALSE(fs::exists(file("run.pvd.tmp")));
  EXPECT_THROW(pvd.add(std::numeric_limits<double>::quiet_NaN(), "x.vtu"), std::logic_error);
  if (!have_python()) return;
  EXPECT_EQ(read_vtu("--pvd " + file("run.pvd") + " --expect-steps 3"), 0) << slurp(file("reader.err"));
  EXPECT_NE(read_vtu("--pvd " + file("run.pvd") + " --expect-steps 4"), 0);
  pvd.add(0.3, "vtu/missing.vtu");
  EXPECT_NE(read_vtu("--pvd " + file("run.pvd")), 0);
  EXPECT_NE(slurp(file("reader.err")).find("does not exist"), std::string::npos);
}

TEST_F(IoFiles, CsvTableWritesHeaderOnceAndRoundTripsRows) {
  const std::vector<double> row1{0.1, 1.0 / 3.0, -2.5e-300};
  {
    CsvTable csv(file("history.csv"), {"time", "force, N", "u"});
    csv.add_row(row1);
    // Flushed: visible on disk before the table is closed.
    EXPECT_NE(slurp(file("history.csv")).find("\n0.1,"), std::string::npos);
    csv.add_row({1.0, 2.0, 3.0});
    EXPECT_THROW(csv.add_row({1.0, 2.0}), std::logic_error);
    EXPECT_EQ(csv.rows(), 2u);
  }
  std::istringstream in(slurp(file("history.csv")));
  std::string header, line1, line2, extra;
  std::getline(in, header);
  std::getline(in, line1);
  std::getline(in, line2);
  EXPECT_FALSE(std::getline(in, extra));
  EXPECT_EQ(header, "time,\"force, N\",u");
  EXPECT_EQ(line2, "1,2,3");
  std::vector<double> parsed;
  std::istringstream fields(line1);
  for (std::string tok; std::getline(fields, tok, ',');) parsed.push_back(std::strtod(tok.c_str(), nullptr));
  EXPECT_EQ(parsed, row1);
  EXPECT_THROW(CsvTable(file("empty.csv"), {}), std::logic_error);
}

}  // namespace
}  // namespace perimorph::io

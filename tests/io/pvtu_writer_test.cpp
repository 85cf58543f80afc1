// The pieces of a distributed run's VTU (issue 17, item 3): write_pvtu indexes
// the pieces; the independent reader python/read_vtu.py puts them back
// together and checks them.
#include "perimorph/io/pvtu_writer.hpp"
#include "perimorph/io/vtu_writer.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace perimorph::io {
namespace {

namespace fs = std::filesystem;

/// Cells `cells` of a row of three unit quads (cell i: corners (i, 0) to
/// (i + 1, 1)) as one grid: their points, a point field (3 components) and
/// two cell fields, one of them `cell`, each cell's number in the row.
UnstructuredGrid quads_of_a_row(const std::vector<Index>& cells) {
  UnstructuredGrid g;
  g.nodes_per_cell = 4;
  g.cell_type = VtkCell::quad;
  Field u{"displacement", 3, {}}, damage{"damage", 1, {}}, number{"cell", 1, {}};
  for (Index c : cells) {
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        g.connectivity.push_back(static_cast<Index>(g.points.size()));
        g.points.emplace_back(double(c + i), double(j), 0.0);
        u.values.insert(u.values.end(), {double(c + i), double(j), -1.0});
      }
    damage.values.push_back(0.25 * double(c + 1));
    number.values.push_back(double(c));
  }
  g.point_data = {u};
  g.cell_data = {damage, number};
  return g;
}

class IoPieces : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("perimorph_pvtu_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::string slurp(const std::string& name) const {
    std::ifstream in(file(name));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  /// python/read_vtu.py ARGS; its exit status, stderr in reader.err.
  int read_vtu(const std::string& args) const {
    const std::string cmd = "/usr/bin/python3 '" PERIMORPH_SOURCE_DIR "/python/read_vtu.py' " + args +
                            " 2> '" + file("reader.err") + "'";
    return std::system(cmd.c_str());
  }
  /// The row of quads in two pieces (cells 0 and 2 first, then cell 1) and
  /// an index listing `pieces` of them.
  void write(const std::vector<std::string>& pieces, const UnstructuredGrid& layout) const {
    write_vtu(file("run_0001_p0.vtu"), quads_of_a_row({0, 2}));
    write_vtu(file("run_0001_p1.vtu"), quads_of_a_row({1}));
    write_pvtu(file("run_0001.pvtu"), layout, pieces);
  }
  fs::path dir_;
};

TEST_F(IoPieces, TheIndexDeclaresEveryArrayAndListsThePieces) {
  write({"run_0001_p0.vtu", "run_0001_p1.vtu"}, quads_of_a_row({0, 1, 2}));
  const std::string xml = slurp("run_0001.pvtu");
  EXPECT_NE(xml.find("<VTKFile type=\"PUnstructuredGrid\""), std::string::npos);
  EXPECT_NE(xml.find("<PDataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"/>"),
            std::string::npos);
  EXPECT_NE(xml.find("<PDataArray type=\"Float64\" Name=\"damage\" NumberOfComponents=\"1\"/>"),
            std::string::npos);
  EXPECT_NE(xml.find("<Piece Source=\"run_0001_p1.vtu\"/>"), std::string::npos);
  EXPECT_FALSE(fs::exists(file("run_0001.pvtu.tmp")));
  EXPECT_THROW(write_pvtu(file("x.pvtu"), quads_of_a_row({0, 1, 2}), {}), std::logic_error);
}

TEST_F(IoPieces, TheIndependentReaderPutsThePiecesBackInCellOrder) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not available";
  write({"run_0001_p0.vtu", "run_0001_p1.vtu"}, quads_of_a_row({0, 1, 2}));
  // 8 + 4 points (the pieces repeat the points they share), 3 cells.
  EXPECT_EQ(read_vtu(file("run_0001.pvtu") +
                     " --expect-points 12 --expect-cells 3 --expect-point-array displacement:3"
                     " --expect-cell-array damage:1"),
            0)
      << slurp("reader.err");
  // A cell missing (one piece listed) or an array the pieces lack is an error.
  write({"run_0001_p0.vtu"}, quads_of_a_row({0, 1, 2}));
  EXPECT_NE(read_vtu(file("run_0001.pvtu")), 0);
  EXPECT_NE(slurp("reader.err").find("not each cell"), std::string::npos) << slurp("reader.err");
  UnstructuredGrid more = quads_of_a_row({0, 1, 2});
  more.cell_data.push_back({"stress", 9, {}});
  write({"run_0001_p0.vtu", "run_0001_p1.vtu"}, more);
  EXPECT_NE(read_vtu(file("run_0001.pvtu")), 0);
  EXPECT_NE(slurp("reader.err").find("the index declares"), std::string::npos) << slurp("reader.err");
}

}  // namespace
}  // namespace perimorph::io

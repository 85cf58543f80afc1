// The pieces of a distributed run's VTU (issue 17, item 3): grid_piece cuts a
// grid by cells, write_pvtu indexes the pieces; the independent reader
// python/read_vtu.py puts the pieces back together and checks them.
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

/// Three quads in a row (points i, i+1, i+4, i+5 for cell i), a point field
/// (3 components) and two cell fields, one of them the cell's number `cell`.
UnstructuredGrid row_of_quads() {
  UnstructuredGrid g;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) g.points.emplace_back(double(i), double(j), 0.0);
  for (Index c = 0; c < 3; ++c) g.connectivity.insert(g.connectivity.end(), {c, c + 1, c + 4, c + 5});
  g.nodes_per_cell = 4;
  g.cell_type = VtkCell::quad;
  Field u{"displacement", 3, {}};
  for (std::size_t p = 0; p < 8; ++p) u.values.insert(u.values.end(), {double(p), 10.0 * double(p), -1.0});
  g.point_data = {u};
  g.cell_data = {{"damage", 1, {0.25, 0.5, 0.75}}, {"cell", 1, {0.0, 1.0, 2.0}}};
  return g;
}

TEST(IoGridPiece, KeepsTheMarkedCellsTheirPointsInOrderAndTheirValues) {
  const UnstructuredGrid g = row_of_quads();
  const UnstructuredGrid middle = grid_piece(g, std::vector<char>{0, 1, 0});
  ASSERT_EQ(middle.points.size(), 4u);  // points 1, 2, 5, 6 of the whole
  EXPECT_EQ(middle.points[0], g.points[1]);
  EXPECT_EQ(middle.points[3], g.points[6]);
  EXPECT_EQ(middle.connectivity, (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(middle.point_data[0].values, (std::vector<double>{1, 10, -1, 2, 20, -1, 5, 50, -1, 6, 60, -1}));
  EXPECT_EQ(middle.cell_data[0].values, std::vector<double>{0.5});
  EXPECT_EQ(middle.cell_data[1].values, std::vector<double>{1.0});

  const UnstructuredGrid ends = grid_piece(g, std::vector<char>{1, 0, 1});
  EXPECT_EQ(ends.points.size(), 8u);
  EXPECT_EQ(ends.connectivity, (std::vector<Index>{0, 1, 4, 5, 2, 3, 6, 7}));
  EXPECT_EQ(ends.cell_data[0].values, (std::vector<double>{0.25, 0.75}));
  EXPECT_THROW(grid_piece(g, std::vector<char>{1, 0}), std::logic_error);
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
    const UnstructuredGrid g = row_of_quads();
    write_vtu(file("run_0001_p0.vtu"), grid_piece(g, std::vector<char>{1, 0, 1}));
    write_vtu(file("run_0001_p1.vtu"), grid_piece(g, std::vector<char>{0, 1, 0}));
    write_pvtu(file("run_0001.pvtu"), layout, pieces);
  }
  fs::path dir_;
};

TEST_F(IoPieces, TheIndexDeclaresEveryArrayAndListsThePieces) {
  write({"run_0001_p0.vtu", "run_0001_p1.vtu"}, row_of_quads());
  const std::string xml = slurp("run_0001.pvtu");
  EXPECT_NE(xml.find("<VTKFile type=\"PUnstructuredGrid\""), std::string::npos);
  EXPECT_NE(xml.find("<PDataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"/>"),
            std::string::npos);
  EXPECT_NE(xml.find("<PDataArray type=\"Float64\" Name=\"damage\" NumberOfComponents=\"1\"/>"),
            std::string::npos);
  EXPECT_NE(xml.find("<Piece Source=\"run_0001_p1.vtu\"/>"), std::string::npos);
  EXPECT_FALSE(fs::exists(file("run_0001.pvtu.tmp")));
  EXPECT_THROW(write_pvtu(file("x.pvtu"), row_of_quads(), {}), std::logic_error);
}

TEST_F(IoPieces, TheIndependentReaderPutsThePiecesBackInCellOrder) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not available";
  write({"run_0001_p0.vtu", "run_0001_p1.vtu"}, row_of_quads());
  // 8 + 4 points (the pieces repeat the points they share), 3 cells.
  EXPECT_EQ(read_vtu(file("run_0001.pvtu") +
                     " --expect-points 12 --expect-cells 3 --expect-point-array displacement:3"
                     " --expect-cell-array damage:1"),
            0)
      << slurp("reader.err");
  // A cell missing (one piece listed) or an array the pieces lack is an error.
  write({"run_0001_p0.vtu"}, row_of_quads());
  EXPECT_NE(read_vtu(file("run_0001.pvtu")), 0);
  EXPECT_NE(slurp("reader.err").find("not each cell"), std::string::npos) << slurp("reader.err");
  UnstructuredGrid more = row_of_quads();
  more.cell_data.push_back({"stress", 9, {}});
  write({"run_0001_p0.vtu", "run_0001_p1.vtu"}, more);
  EXPECT_NE(read_vtu(file("run_0001.pvtu")), 0);
  EXPECT_NE(slurp("reader.err").find("the index declares"), std::string::npos) << slurp("reader.err");
}

}  // namespace
}  // namespace perimorph::io

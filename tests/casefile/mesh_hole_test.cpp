// [[mesh.hole]]: the parser reads the shape and its keys and rejects a wrong
// shape, a shape of another dimension and keys of another shape; which cells
// a hole removes is checked in tests/mesh/holes_test.cpp and
// tests/setup/mesh_hole_test.cpp.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace perimorph::casefile {
namespace {

constexpr const char* kPlate = R"(
[mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [40, 20]

[[material]]
name = "steel"
E = 200
nu = 0.3
)";

constexpr const char* kBlock = R"(
[mesh]
dim = 3
lower = [0, 0, 0]
upper = [4, 4, 2]
cells = [8, 8, 4]

[[material]]
name = "steel"
E = 200
nu = 0.3
)";

std::string error_of(const std::string& text, const std::string& path = "hole.toml") {
  try {
    parse_case_string(text, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(CaseFileHole, AbsentByDefault) {
  EXPECT_TRUE(parse_case_string(kPlate, "p.toml").mesh.holes.empty());
}

TEST(CaseFileHole, DiskAndBoxIn2D) {
  const CaseConfig c = parse_case_string(std::string(kPlate) + R"(
[[mesh.hole]]
shape = "disk"
center = [2.0, 1]
radius = 0.3

[[mesh.hole]]
shape = "box"
lower = [3, -1]
upper = [5, 0.5]
)",
                                         "p.toml");
  ASSERT_EQ(c.mesh.holes.size(), 2u);
  const HoleSpec& disk = c.mesh.holes[0];
  EXPECT_EQ(disk.shape, HoleShape::disk);
  EXPECT_EQ(disk.center, Vec3(2, 1, 0));
  EXPECT_EQ(disk.radius, 0.3);
  EXPECT_EQ(disk.where.key, "mesh.hole[1]");
  EXPECT_EQ(disk.where.line, 13);
  const HoleSpec& box = c.mesh.holes[1];
  EXPECT_EQ(box.shape, HoleShape::box);
  EXPECT_EQ(box.lower, Vec3(3, -1, 0));
  EXPECT_EQ(box.upper, Vec3(5, 0.5, 0));
  EXPECT_EQ(box.where.key, "mesh.hole[2]");
  EXPECT_EQ(box.where.describe(), "p.toml:18:1: key 'mesh.hole[2]'");
}

TEST(CaseFileHole, BallAndCylinderIn3D) {
  const CaseConfig c = parse_case_string(std::string(kBlock) + R"(
[[mesh.hole]]
shape = "ball"
center = [1, 1, 1]
radius = 0.5

[[mesh.hole]]
shape = "cylinder"
center = [3, 3, 0]
radius = 0.25
)",
                                         "b.toml");
  ASSERT_EQ(c.mesh.holes.size(), 2u);
  EXPECT_EQ(c.mesh.holes[0].shape, HoleShape::ball);
  EXPECT_EQ(c.mesh.holes[0].center, Vec3(1, 1, 1));
  EXPECT_EQ(c.mesh.holes[1].shape, HoleShape::cylinder);
  EXPECT_EQ(c.mesh.holes[1].center, Vec3(3, 3, 0));
  EXPECT_EQ(c.mesh.holes[1].radius, 0.25);
}

TEST(CaseFileHole, ErrorsNameFileLineKeyAndAlternatives) {
  const std::string plate = kPlate;
  // An unknown shape lists the shapes and suggests the closest.
  std::string msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"disc\"\ncenter = [2, 1]\nradius = 0.3\n");
  EXPECT_EQ(msg.rfind("hole.toml:14:9: key 'mesh.hole[1].shape': unknown hole shape \"disc\"; did you mean "
                      "\"disk\"? allowed: \"disk\", \"ball\", \"cylinder\", \"box\"",
                      0),
            0u)
      << msg;
  // A misspelt key gets a suggestion before the shape is read.
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"disk\"\ncentre = [2, 1]\nradius = 0.3\n");
  EXPECT_TRUE(contains(msg, "hole.toml:15:1: unknown key 'mesh.hole[1].centre'")) << msg;
  EXPECT_TRUE(contains(msg, "did you mean 'mesh.hole[1].center'?")) << msg;
  // A key of another shape says what this shape takes.
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"box\"\nlower = [0, 0]\nupper = [1, 1]\nradius = 1\n");
  EXPECT_TRUE(contains(msg,
                       "key 'mesh.hole[1].radius' is not allowed here: a box takes lower = [x, y] and "
                       "upper = [x, y]"))
      << msg;
  // A shape of another dimension names the ones that fit.
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"ball\"\ncenter = [2, 1]\nradius = 0.3\n");
  EXPECT_TRUE(contains(msg,
                       "key 'mesh.hole[1].shape': \"ball\" is a 3D shape, but mesh.dim = 2; for dim = 2 "
                       "use \"disk\" or \"box\""))
      << msg;
  msg = error_of(std::string(kBlock) + "\n[[mesh.hole]]\nshape = \"disk\"\ncenter = [2, 1, 1]\nradius = 1\n");
  EXPECT_TRUE(
      contains(msg, "\"disk\" is a 2D shape, but mesh.dim = 3; for dim = 3 use \"ball\", \"cylinder\""))
      << msg;
  // Missing and invalid values.
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"disk\"\ncenter = [2, 1]\n");
  EXPECT_TRUE(contains(msg,
                       "hole.toml:13:1: key 'mesh.hole[1].radius': missing required key; a disk takes "
                       "center = [x, y] and radius"))
      << msg;
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"disk\"\ncenter = [2, 1]\nradius = -1\n");
  EXPECT_TRUE(contains(msg, "key 'mesh.hole[1].radius': must be positive")) << msg;
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"disk\"\ncenter = [2, 1, 0]\nradius = 1\n");
  EXPECT_TRUE(contains(msg, "key 'mesh.hole[1].center'")) << msg;
  msg = error_of(plate + "\n[[mesh.hole]]\nshape = \"box\"\nlower = [1, 1]\nupper = [2, 1]\n");
  EXPECT_TRUE(contains(msg, "key 'mesh.hole[1].upper[2]': must be greater than mesh.hole[1].lower[2]"))
      << msg;
  // [mesh.hole] (one table) is not an array of tables.
  msg = error_of(plate + "\n[mesh.hole]\nshape = \"disk\"\n");
  EXPECT_TRUE(contains(msg, "mesh.hole")) << msg;
}

}  // namespace
}  // namespace perimorph::casefile

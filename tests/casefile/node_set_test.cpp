// [[node_set]]: named node sets selected by a box. The parser checks names
// and boxes; which nodes a box selects is checked in tests/setup/node_set_test.cpp.

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
upper = [48, 24]
cells = [8, 4]

[[region]]
name = "left"
lower = [0, 0]
upper = [24, 24]

[[material]]
name = "steel"
E = 200
nu = 0.3
)";

std::string error_of(const std::string& text, const std::string& path = "sets.toml") {
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

std::string node_set(const std::string& name, const std::string& lower, const std::string& upper) {
  return "\n[[node_set]]\nname = \"" + name + "\"\nlower = " + lower + "\nupper = " + upper + "\n";
}

TEST(CaseFileNodeSet, AbsentByDefault) {
  EXPECT_TRUE(parse_case_string(kPlate, "p.toml").node_sets.empty());
}

TEST(CaseFileNodeSet, PointAndLineBoxesIn2D) {
  const std::string text = std::string(kPlate) + node_set("pin", "[23.9, -0.1]", "[24.1, 0.1]") +
                           node_set("corner", "[48, 24]", "[48, 24]") +
                           "\n[[dirichlet]]\nset = \"pin\"\nux = 0\n";
  const CaseConfig c = parse_case_string(text, "p.toml");
  ASSERT_EQ(c.node_sets.size(), 2u);
  const NodeSetSpec& pin = c.node_sets[0];
  EXPECT_EQ(pin.name, "pin");
  EXPECT_EQ(pin.lower, Vec3(23.9, -0.1, 0));
  EXPECT_EQ(pin.upper, Vec3(24.1, 0.1, 0));
  EXPECT_EQ(pin.where.key, "node_set[1]");
  EXPECT_EQ(pin.where.file, "p.toml");
  EXPECT_EQ(pin.where.line, 18);
  // Equal bounds (a point box) are allowed; integers are numbers.
  EXPECT_EQ(c.node_sets[1].name, "corner");
  EXPECT_EQ(c.node_sets[1].lower, Vec3(48, 24, 0));
  EXPECT_EQ(c.node_sets[1].upper, c.node_sets[1].lower);
  EXPECT_EQ(c.node_sets[1].where.key, "node_set[2]");
  // A Dirichlet entry may name the set (resolved when the model is built).
  ASSERT_EQ(c.dirichlet.size(), 1u);
  EXPECT_EQ(c.dirichlet[0].set, "pin");
}

TEST(CaseFileNodeSet, OneAndThreeDimensions) {
  const std::string bar = R"(
[mesh]
dim = 1
lower = [0]
upper = [10]
cells = [5]

[[material]]
name = "steel"
E = 200
nu = 0.3

[[node_set]]
name = "middle"
lower = [5]
upper = [5]
)";
  const CaseConfig c1 = parse_case_string(bar, "bar.toml");
  ASSERT_EQ(c1.node_sets.size(), 1u);
  EXPECT_EQ(c1.node_sets[0].lower, Vec3(5, 0, 0));
  EXPECT_EQ(c1.node_sets[0].upper, Vec3(5, 0, 0));

  const std::string block = R"(
[mesh]
dim = 3
lower = [0, 0, 0]
upper = [2, 2, 2]
cells = [2, 2, 2]

[[material]]
name = "steel"
E = 200
nu = 0.3

[[node_set]]
name = "edge"
lower = [-1, 0, 0]
upper = [3, 0, 0.0]
)";
  const CaseConfig c3 = parse_case_string(block, "block.toml");
  ASSERT_EQ(c3.node_sets.size(), 1u);
  EXPECT_EQ(c3.node_sets[0].lower, Vec3(-1, 0, 0));
  EXPECT_EQ(c3.node_sets[0].upper, Vec3(3, 0, 0));
}

TEST(CaseFileNodeSet, NamesMustBeNewAndUnique) {
  const std::string plate = kPlate;
  for (const char* reserved : {"xmin", "ymax", "zmin", "boundary", "all"}) {
    SCOPED_TRACE(reserved);
    const std::string msg = error_of(plate + node_set(reserved, "[0, 0]", "[1, 1]"));
    EXPECT_TRUE(contains(msg, "key 'node_set[1].name': the name \"" + std::string(reserved) +
                                  "\" is already a set of the mesh (every box mesh has"))
        << msg;
  }
  std::string msg = error_of(plate + node_set("left", "[0, 0]", "[1, 1]"));
  EXPECT_TRUE(
      contains(msg, "key 'node_set[1].name': the name \"left\" is already used by a region (region[1]"))
      << msg;
  msg = error_of(plate + node_set("pin", "[0, 0]", "[1, 1]") + node_set("pin", "[2, 2]", "[3, 3]"));
  EXPECT_TRUE(contains(msg,
                       "sets.toml:24:8: key 'node_set[2].name': duplicate node set name \"pin\": already "
                       "used by node_set[1] (line 18)"))
      << msg;
  msg = error_of(plate + "\n[[node_set]]\nname = \"\"\nlower = [0, 0]\nupper = [1, 1]\n");
  EXPECT_TRUE(contains(msg, "key 'node_set[1].name': expected a non-empty name")) << msg;
}

TEST(CaseFileNodeSet, BoxErrorsNameTheKey) {
  const std::string plate = kPlate;
  // upper below lower along y; equal bounds would be fine.
  std::string msg = error_of(plate + node_set("pin", "[1, 2]", "[1, 1.5]"));
  EXPECT_TRUE(contains(msg, "key 'node_set[1].upper[2]': must not be less than node_set[1].lower[2] = 2"))
      << msg;
  EXPECT_TRUE(contains(msg, "got 1.5")) << msg;
  msg = error_of(plate + node_set("pin", "[1, 2, 3]", "[1, 2]"));
  EXPECT_TRUE(contains(msg, "key 'node_set[1].lower': needs 2 numbers for dim = 2, got 3")) << msg;
  msg = error_of(plate + node_set("pin", "[1, 2]", "[1, inf]"));
  EXPECT_TRUE(contains(msg, "key 'node_set[1].upper[2]'")) << msg;
  msg = error_of(plate + "\n[[node_set]]\nname = \"pin\"\nlower = [0, 0]\n");
  EXPECT_TRUE(contains(msg, "sets.toml:18:1: key 'node_set[1].upper': missing required key")) << msg;
  msg = error_of(plate + "\n[[node_set]]\nlower = [0, 0]\nupper = [0, 0]\n");
  EXPECT_TRUE(contains(msg, "key 'node_set[1].name': missing required key")) << msg;
}

TEST(CaseFileNodeSet, UnknownKeysAndTables) {
  const std::string plate = kPlate;
  std::string msg = error_of(plate + "\n[[node_set]]\nname = \"pin\"\nlower = [0, 0]\nuper = [1, 1]\n");
  EXPECT_TRUE(contains(msg, "unknown key 'node_set[1].uper'; did you mean 'node_set[1].upper'?")) << msg;
  msg = error_of(plate + "\n[[node_sets]]\nname = \"pin\"\nlower = [0, 0]\nupper = [1, 1]\n");
  EXPECT_TRUE(contains(msg, "unknown key 'node_sets'; did you mean 'node_set'?")) << msg;
  msg = error_of(plate + "\n[node_set]\nname = \"pin\"\nlower = [0, 0]\nupper = [1, 1]\n");
  EXPECT_TRUE(contains(msg, "key 'node_set'")) << msg;
}

}  // namespace
}  // namespace perimorph::casefile

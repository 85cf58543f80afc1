// One writer per output set (io/output_lock.hpp), and a CSV table that keeps
// only complete rows when a write fails (io/csv_table.hpp; issue 18, item 6).

#include "perimorph/io/output_lock.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/io/csv_table.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

namespace perimorph {
namespace {

std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("perimorph_output_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

TEST(OutputLock, ASecondWriterOfTheSameSetIsRefusedNamingTheFirst) {
  const std::string dir = scratch_dir("lock");
  std::optional<io::OutputLock> first(std::in_place, dir, "plate");
  try {
    io::OutputLock second(dir, "plate");
    FAIL() << "two writers of one output set";
  } catch (const OutputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(fmt::format("another run (process {}) is writing plate.*", getpid())),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("-o DIR"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(io::OutputLock other(dir, "beam")) << "another basename in the same folder";
  first.reset();
  EXPECT_NO_THROW(io::OutputLock again(dir, "plate")) << "the lock outlived its holder";
}

TEST(CsvTable, AFailedWriteSaysWhyAndLeavesNoPartialRow) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  try {
    io::CsvTable table("/dev/full", {"a", "b"});
    FAIL() << "wrote to a full device";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
}

TEST(CsvTable, RemoveLastRowCutsOffExactlyThatRow) {
  const std::string path = scratch_dir("csv") + "/t.csv";
  io::CsvTable table(path, {"a", "b"});
  table.add_row({1.0, 2.0});
  table.add_row({3.0, 4.5});
  table.remove_last_row();
  EXPECT_EQ(table.rows(), 1u);
  EXPECT_THROW(table.remove_last_row(), std::logic_error) << "only the row the last add_row wrote";
  table.add_row({5.0, 6.0});
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "a,b\n1,2\n5,6\n");
}

}  // namespace
}  // namespace perimorph

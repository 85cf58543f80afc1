// AtomicFile: the target appears only on commit, whole; an abandoned write
// leaves neither the target nor the temporary; errors name the file.

#include "perimorph/io/atomic_file.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace perimorph {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(IoAtomicFile, TargetAppearsOnlyOnCommit) {
  const fs::path dir = fs::temp_directory_path() / "perimorph_atomic_file_test";
  fs::create_directories(dir);
  const fs::path target = dir / "out.txt";
  fs::remove(target);
  {
    std::ofstream(target) << "old";
    io::AtomicFile f(target.string());
    f.write("new ");
    f.write("content");
    EXPECT_EQ(slurp(target), "old");  // readers still see the previous version
    f.commit();
  }
  EXPECT_EQ(slurp(target), "new content");
  EXPECT_FALSE(fs::exists(dir / "out.txt.tmp"));
  {
    io::AtomicFile f(target.string());
    f.write("abandoned");
  }
  EXPECT_EQ(slurp(target), "new content");
  EXPECT_FALSE(fs::exists(dir / "out.txt.tmp"));
  fs::remove_all(dir);
}

TEST(IoAtomicFile, UnwritableDirectoryIsAnErrorNamingTheFile) {
  try {
    io::AtomicFile f("/nonexistent-directory/out.vtu");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-directory/out.vtu.tmp"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace perimorph

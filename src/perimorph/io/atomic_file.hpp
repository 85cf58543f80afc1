#pragma once
// A file written in full or not at all: the data go to PATH.tmp, and commit()
// renames it over PATH, so a reader (ParaView polling a PVD, a crash mid-run)
// never sees a half-written file. Without commit() the temporary is removed.

#include <fstream>
#include <string>
#include <string_view>

namespace perimorph::io {

class AtomicFile {
 public:
  /// Opens PATH.tmp; throws Error naming it if that fails.
  explicit AtomicFile(std::string path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(std::string_view data);
  /// Closes, checks that every write succeeded and renames PATH.tmp to PATH;
  /// throws Error naming the file otherwise.
  void commit();

 private:
  std::string path_, tmp_path_;
  std::ofstream file_;
  bool committed_ = false;
  int error_ = 0;  ///< errno of the first failed write
};

}  // namespace perimorph::io

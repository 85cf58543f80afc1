#pragma once
// One writer per output set: a run holds an exclusive lock (flock) on
// DIRECTORY/BASENAME.lock while it writes BASENAME.* there, so that a second
// run into the same folder and basename is refused with a message instead of
// mixing its files with the first's. The lock goes with the process, however
// it ends (SIGKILL included); the file stays, holding the last writer's pid.

#include <string>

namespace perimorph::io {

class OutputLock {
 public:
  /// Takes the lock, or throws OutputError naming the folder, the basename and
  /// the process that holds it.
  OutputLock(const std::string& directory, const std::string& basename);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace perimorph::io

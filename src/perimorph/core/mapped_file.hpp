#pragma once
// A file's bytes mapped read-only into memory (POSIX mmap): pages are read
// from the file when first touched and shared by every process that maps it,
// so a process that reads part of a large file (its piece of a checkpoint,
// run/checkpoint.hpp) holds only that part, and processes on one machine
// share one copy in the page cache.

#include <string>
#include <string_view>

namespace perimorph::core {

class MappedFile {
 public:
  /// Maps `path` whole. Throws Error "cannot read WHAT 'PATH': reason"
  /// (`what`: "checkpoint", …).
  MappedFile(const std::string& path, std::string_view what);
  ~MappedFile();
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  /// The file's bytes, valid while this object lives (empty for an empty file).
  std::string_view bytes() const { return {data_, size_}; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace perimorph::core

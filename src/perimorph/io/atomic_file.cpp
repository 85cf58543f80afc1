#include "perimorph/io/atomic_file.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

namespace perimorph::io {

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)),
      tmp_path_(path_ + ".tmp"),
      file_(tmp_path_, std::ios::binary | std::ios::trunc) {
  if (!file_)
    throw OutputError(fmt::format("cannot open '{}' for writing: {}", tmp_path_, std::strerror(errno)));
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  file_.close();
  std::error_code ec;
  std::filesystem::remove(tmp_path_, ec);  // best effort: nothing to report from a destructor
}

void AtomicFile::write(std::string_view data) {
  file_.write(data.data(), static_cast<std::streamsize>(data.size()));
  if (!file_ && error_ == 0) error_ = errno;
}

void AtomicFile::commit() {
  if (file_) file_.flush();
  if (!file_ && error_ == 0) error_ = errno;
  file_.close();
  if (!file_ && error_ == 0) error_ = errno;
  if (!file_) throw OutputError(fmt::format("cannot write '{}': {}", path_, std::strerror(error_)));
  std::error_code ec;
  std::filesystem::rename(tmp_path_, path_, ec);
  if (ec) throw OutputError(fmt::format("cannot rename '{}' to '{}': {}", tmp_path_, path_, ec.message()));
  committed_ = true;
}

}  // namespace perimorph::io

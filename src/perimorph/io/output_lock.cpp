#include "perimorph/io/output_lock.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string_view>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace perimorph::io {

OutputLock::OutputLock(const std::string& directory, const std::string& basename)
    : path_((std::filesystem::path(directory) / (basename + ".lock")).string()) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw OutputError(fmt::format("cannot open '{}': {}", path_, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char pid[32] = {};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    ::close(fd_);
    fd_ = -1;
    if (error != EWOULDBLOCK)
      throw OutputError(fmt::format("cannot lock '{}': {}", path_, std::strerror(error)));
    const std::string_view holder(pid, n > 0 ? static_cast<std::size_t>(n) : 0);
    throw OutputError(fmt::format(
        "another run{} is writing {}.* in {} (it holds {}): two runs into one folder and basename would mix "
        "their files. Wait for it to end, or give this one another folder (-o DIR, [output] directory) "
        "or basename ([output] basename)",
        holder.empty() ? "" : fmt::format(" (process {})", holder), basename, directory, path_));
  }
  const std::string me = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size())) {
    // The lock holds without the pid: only the message of a second run is poorer.
  }
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace perimorph::io

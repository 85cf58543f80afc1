#include "perimorph/io/progress.hpp"

#include <fmt/format.h>

#include <unistd.h>
#include <algorithm>
#include <cstdio>

namespace perimorph::io {

ProgressLine::ProgressLine(int total, bool enabled)
    : total_(total),
      active_(enabled && ::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

ProgressLine::~ProgressLine() {
  try {
    finish();
  } catch (...) {  // a failing stderr must not terminate the program
  }
}

std::string ProgressLine::format(int done, int total, const std::string& detail, double elapsed_s) {
  std::string eta = "-";
  if (done > 0) {
    const double remaining = elapsed_s / done * std::max(0, total - done);
    eta = fmt::format("{:.1f} s", remaining);
  }
  std::string text = fmt::format("[increment {}/{}]", done, total);
  if (!detail.empty()) text += fmt::format(" {}", detail);
  text += fmt::format(" | elapsed {:.1f} s | ETA {}", elapsed_s, eta);
  return text;
}

void ProgressLine::update(int done, const std::string& detail) {
  if (!active_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string text = format(done, total_, detail, elapsed);
  // Pad with blanks to erase the tail of a longer previous line.
  const std::size_t pad = last_width_ > text.size() ? last_width_ - text.size() : 0;
  fmt::print(stderr, "\r{}{}", text, std::string(pad, ' '));
  std::fflush(stderr);
  last_width_ = text.size();
  drawn_ = true;
}

void ProgressLine::finish() {
  if (!active_ || !drawn_) return;
  fmt::print(stderr, "\n");
  std::fflush(stderr);
  drawn_ = false;
  last_width_ = 0;
}

}  // namespace perimorph::io

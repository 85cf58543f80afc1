#include "perimorph/io/progress.hpp"

#include <fmt/format.h>

#include <unistd.h>
#include <algorithm>
#include <cstdio>

namespace perimorph::io {

ProgressLine::ProgressLine(int total, bool enabled, clock::time_point start)
    : total_(total),
      active_(enabled && ::isatty(STDERR_FILENO) == 1),
      start_(start),
      phase_start_(start),
      increments_start_(start) {}

ProgressLine::~ProgressLine() {
  try {
    finish();
  } catch (...) {  // a failing stderr must not terminate the program
  }
}

double ProgressLine::seconds_since(clock::time_point t) const {
  return std::chrono::duration<double>(clock::now() - t).count();
}

std::string ProgressLine::format(int done, int total, const std::string& detail, double elapsed_s,
                                 double increments_s) {
  std::string eta = "-";
  if (done > 0) {
    const double remaining = increments_s / done * std::max(0, total - done);
    eta = fmt::format("{:.1f} s", remaining);
  }
  std::string text = fmt::format("[increment {}/{}]", done, total);
  if (!detail.empty()) text += fmt::format(" {}", detail);
  text += fmt::format(" | elapsed {:.1f} s | ETA {}", elapsed_s, eta);
  return text;
}

std::string ProgressLine::format_setup(const std::vector<Phase>& done, const std::string& current,
                                       double elapsed_s) {
  std::string list;
  for (const Phase& p : done)
    if (p.seconds >= 0.05) list += fmt::format("{}{} {:.1f} s", list.empty() ? "" : ", ", p.name, p.seconds);
  if (current.empty()) return fmt::format("[set-up {:.1f} s]{}{}", elapsed_s, list.empty() ? "" : " ", list);
  return fmt::format("[set-up] {}...{}{} | elapsed {:.1f} s", current, list.empty() ? "" : " | ", list,
                     elapsed_s);
}

void ProgressLine::phase(const std::string& name) {
  const auto now = clock::now();
  if (!current_phase_.empty())
    phases_.push_back({current_phase_, std::chrono::duration<double>(now - phase_start_).count()});
  current_phase_ = name;
  phase_start_ = now;
  if (active_) draw(format_setup(phases_, current_phase_, seconds_since(start_)));
}

void ProgressLine::start_increments() {
  if (increments_started_) return;
  increments_started_ = true;
  const auto now = clock::now();
  if (!current_phase_.empty())
    phases_.push_back({current_phase_, std::chrono::duration<double>(now - phase_start_).count()});
  current_phase_.clear();
  increments_start_ = now;
  if (!active_) return;
  if (!phases_.empty()) {
    draw(format_setup(phases_, "", seconds_since(start_)));
    finish();
  }
  draw(format(0, total_, "", seconds_since(start_), 0.0));
}

void ProgressLine::update(int done, const std::string& detail) {
  start_increments();
  if (!active_) return;
  draw(format(done, total_, detail, seconds_since(start_), seconds_since(increments_start_)));
}

void ProgressLine::draw(const std::string& text) {
  // Pad with blanks to erase the tail of a longer previous line.
  const std::size_t pad = last_width_ > text.size() ? last_width_ - text.size() : 0;
  fmt::print(stderr, "\r{}{}", text, std::string(pad, ' '));
  std::fflush(stderr);
  last_width_ = text.size();
  last_text_ = text;
  drawn_ = true;
}

void ProgressLine::erase() {
  if (!drawn_) return;
  fmt::print(stderr, "\r{}\r", std::string(last_width_, ' '));
  last_width_ = 0;
}

void ProgressLine::mute() {
  finish();
  active_ = false;
  muted_ = true;
}

void ProgressLine::message(const std::string& text) {
  if (muted_) return;
  const bool redraw = active_ && drawn_;
  if (redraw) erase();
  fmt::print(stderr, "{}\n", text);
  std::fflush(stderr);
  if (redraw) draw(last_text_);
}

void ProgressLine::finish() {
  if (!active_ || !drawn_) return;
  fmt::print(stderr, "\n");
  std::fflush(stderr);
  drawn_ = false;
  last_width_ = 0;
}

}  // namespace perimorph::io

#pragma once
// One self-overwriting status line on stderr for long runs:
//   [increment 3/10] detail | elapsed 12.3 s | ETA 28.7 s
// Active only when the caller enables it (enabled = !quiet) and stderr is a
// terminal, so redirected logs and CI output never receive carriage returns.

#include <chrono>
#include <string>

namespace perimorph::io {

class ProgressLine {
 public:
  /// total: number of increments of the run (>= 0). The clock starts here.
  ProgressLine(int total, bool enabled);
  /// Calls finish().
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Redraws the line after increment `done` (1-based count of completed
  /// increments) with a free-form detail text. The ETA extrapolates the mean
  /// time per completed increment. No-op when not active.
  void update(int done, const std::string& detail);

  /// Ends the line with a newline if anything was drawn, so the next output
  /// starts on a fresh line. Idempotent; no-op when not active.
  void finish();

  /// True if this line prints (enabled flag set and stderr is a terminal).
  bool active() const { return active_; }

  /// The text of one update, without '\r' or padding: pure, for tests.
  /// ETA is "-" while done <= 0.
  static std::string format(int done, int total, const std::string& detail, double elapsed_s);

 private:
  int total_;
  bool active_;
  bool drawn_ = false;
  std::size_t last_width_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace perimorph::io

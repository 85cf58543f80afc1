#pragma once
// One self-overwriting status line on stderr for long runs. During set-up it
// names the phase running and the time of those done:
//   [set-up] bond graph... | mesh 0.1 s, points 0.3 s | elapsed 0.5 s
// and stays on the terminal when the increments begin:
//   [set-up 5.2 s] mesh 0.1 s, points 0.3 s, bond graph 1.2 s, assembly 3.6 s
//   [increment 3/10] detail | elapsed 12.3 s | ETA 28.7 s
// Elapsed times count from the start given (the program's start: set-up
// included); the ETA extrapolates the increments alone. The line is drawn only
// when the caller enables it (enabled = !quiet) and stderr is a terminal, so
// redirected logs and CI output never receive carriage returns; message()
// prints in every case.

#include <chrono>
#include <string>
#include <vector>

namespace perimorph::io {

class ProgressLine {
 public:
  using clock = std::chrono::steady_clock;
  struct Phase {
    std::string name;
    double seconds = 0.0;
  };

  /// total: number of increments of the run (>= 0); times count from `start`.
  ProgressLine(int total, bool enabled, clock::time_point start = clock::now());
  /// Calls finish().
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// A set-up phase begins: the one running (if any) ends and its time is
  /// kept in phases(). Redraws the set-up line. Phases are recorded also when
  /// the line is not active.
  void phase(const std::string& name);

  /// The set-up ends (the phase running ends): its line is left on the
  /// terminal with every phase's time, and the increments' line starts below
  /// it; the ETA counts from here. update() calls it if it was not called.
  void start_increments();

  /// Redraws the line after increment `done` (1-based count of completed
  /// increments) with a free-form detail text. No-op when not active.
  void update(int done, const std::string& detail);

  /// Prints `text` and a newline on stderr whether or not the line is active
  /// (warnings are not progress): a line drawn is erased first and redrawn
  /// below the text.
  void message(const std::string& text);

  /// Ends the line with a newline if anything was drawn, so the next output
  /// starts on a fresh line. Idempotent; no-op when not active.
  void finish();

  /// This process does not report (a distributed run's processes other than
  /// 0, which compute the same figures): nothing is printed from now on,
  /// messages included.
  void mute();

  /// True if this line prints (enabled flag set and stderr is a terminal).
  bool active() const { return active_; }
  /// The set-up phases that have ended, in order.
  const std::vector<Phase>& phases() const { return phases_; }

  /// The text of one increment update, without '\r' or padding: pure, for
  /// tests. `elapsed_s` counts from the start, `increments_s` from the start
  /// of the increments (the ETA is increments_s / done per remaining
  /// increment); ETA is "-" while done <= 0.
  static std::string format(int done, int total, const std::string& detail, double elapsed_s,
                            double increments_s);
  /// The set-up line: `current` running ("" once the set-up is over), the
  /// phases done with their times (those under 0.05 s left out, to keep the
  /// line short).
  static std::string format_setup(const std::vector<Phase>& done, const std::string& current,
                                  double elapsed_s);

 private:
  double seconds_since(clock::time_point t) const;
  void draw(const std::string& text);
  void erase();

  int total_;
  bool active_;
  bool muted_ = false;
  bool drawn_ = false;
  bool increments_started_ = false;
  std::size_t last_width_ = 0;
  std::string last_text_;
  clock::time_point start_, phase_start_, increments_start_;
  std::string current_phase_;
  std::vector<Phase> phases_;
};

}  // namespace perimorph::io

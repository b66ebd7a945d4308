// A progress reporter for long work (studies, turntables): after each finished step it
// prints the count, percent, elapsed time and an ETA to stderr. On a terminal it redraws
// one line in place ('\r') with a bar; otherwise (logs, CI, pipes) it prints one plain line
// per step, so the log stays readable. Apart from the times the text is deterministic.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace sylva {

// Estimated seconds left after `done` of `total` steps took `elapsed` seconds: the mean step
// time so far times the steps left. nullopt before the first step (nothing to go on); 0
// once done >= total. elapsed in seconds, >= 0.
std::optional<double> progress_eta(size_t done, size_t total, double elapsed);

// "0:07", "12:34", "1:02:03" (h:mm:ss from an hour on); "--:--" for nullopt. Negative or
// non-finite seconds print as "--:--" too. Seconds are rounded down.
std::string format_duration(std::optional<double> seconds);

// One status line without a line end. Plain (bar_width = 0):
//   "label 3/10  30%  elapsed 0:12  eta 0:28  what"
// With a bar (bar_width > 0 characters between the brackets):
//   "label [######--------------] 3/10  30%  0:12 < eta 0:28  what"
// `what` is left out when empty. done is clamped to total; total 0 reads as 100%.
std::string format_progress_line(std::string_view label, size_t done, size_t total, double elapsed,
                                 std::string_view what, int bar_width = 0);

struct ProgressOptions {
  bool quiet = false;  // print nothing
  // Redraw in place; nullopt = when stderr is a terminal (isatty).
  std::optional<bool> terminal;
  // Where the text goes; empty = stderr (flushed after each write).
  std::function<void(std::string_view)> sink;
  // Seconds on a monotonic clock; empty = std::chrono::steady_clock.
  std::function<double()> clock;
  // Terminal line width in characters (longer lines are cut so '\r' can redraw them);
  // 0 = ask the terminal (TIOCGWINSZ), 80 when it does not say. [0, 1000].
  int columns = 0;
};

class Progress {
 public:
  // total: the number of steps expected, >= 0 (more steps than that are counted, the total
  // grows with them). On a terminal the empty bar is drawn right away.
  Progress(std::string label, size_t total, ProgressOptions options = {});
  ~Progress();  // finish()
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // One more step is done; `what` names it (one line, no '\n').
  void step(const std::string& what);
  // Ends the in-place line with '\n' (terminal only); idempotent. Call before printing
  // anything else to stderr or stdout on a terminal.
  void finish();

  size_t done() const { return m_done; }
  double elapsed() const;

 private:
  void emit(std::string_view text) const;
  void draw(const std::string& what);

  std::string m_label;
  size_t m_total = 0, m_done = 0;
  ProgressOptions m_options;
  bool m_terminal = false, m_open_line = false;
  int m_columns = 80;
  double m_start = 0;
};

}  // namespace sylva

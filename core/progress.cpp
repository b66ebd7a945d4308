#include "core/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/interrupt.h"

namespace sylva {

std::optional<double> progress_eta(size_t done, size_t total, double elapsed) {
  if (done >= total) return 0.0;
  if (done == 0 || !(elapsed >= 0.0) || !std::isfinite(elapsed)) return std::nullopt;
  return elapsed / double(done) * double(total - done);
}

std::string format_duration(std::optional<double> seconds) {
  if (!seconds || !(*seconds >= 0.0) || !std::isfinite(*seconds) || *seconds > 1e9) return "--:--";
  const long long s = static_cast<long long>(std::floor(*seconds));
  char buf[32];
  if (s < 3600)
    std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  return buf;
}

std::string format_progress_line(std::string_view label, size_t done, size_t total, double elapsed,
                                 std::string_view what, int bar_width) {
  done = std::min(done, total);
  const double share = total == 0 ? 1.0 : double(done) / double(total);
  const int digits = int(std::to_string(total).size());
  std::string line(label);
  if (bar_width > 0) {
    const int filled = std::min(bar_width, int(share * bar_width));
    line += " [" + std::string(size_t(filled), '#') + std::string(size_t(bar_width - filled), '-') +
            "]";
  }
  char buf[160];
  const std::string elapsed_text = format_duration(elapsed);
  const std::string eta_text = format_duration(progress_eta(done, total, elapsed));
  std::snprintf(buf, sizeof buf, " %*zu/%zu %4d%%  %s%s%s %s", digits, done, total,
                int(std::floor(share * 100.0)), bar_width > 0 ? "" : "elapsed ",
                elapsed_text.c_str(), bar_width > 0 ? " < eta" : "  eta", eta_text.c_str());
  line += buf;
  if (!what.empty()) line += "  " + std::string(what);
  return line;
}

Progress::Progress(std::string label, size_t total, ProgressOptions options)
    : m_label(std::move(label)), m_total(total), m_options(std::move(options)) {
  SYLVA_CHECK(m_options.columns >= 0 && m_options.columns <= 1000, "columns in [0, 1000]");
  if (!m_options.clock)
    m_options.clock = [] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
          .count();
    };
  m_start = m_options.clock();
  m_terminal = m_options.terminal.value_or(isatty(STDERR_FILENO) == 1);
  m_columns = m_options.columns;
  if (m_columns == 0) {
    winsize ws{};
    m_columns = m_terminal && ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0
                    ? int(ws.ws_col)
                    : 80;
  }
  if (m_terminal) draw("");
}

Progress::~Progress() {
  finish();
}

double Progress::elapsed() const {
  return std::max(0.0, m_options.clock() - m_start);
}

void Progress::emit(std::string_view text) const {
  if (m_options.quiet) return;
  if (m_options.sink) {
    m_options.sink(text);
    return;
  }
  std::fwrite(text.data(), 1, text.size(), stderr);
  std::fflush(stderr);
}

void Progress::draw(const std::string& what) {
  if (!m_terminal) {
    emit(format_progress_line(m_label, m_done, m_total, elapsed(), what) + "\n");
    return;
  }
  // Cut to the terminal's width: a wrapped line cannot be redrawn with '\r'. Pad with
  // spaces so a shorter line covers the longer one before it.
  const int width = std::max(1, m_columns - 1);
  std::string line = format_progress_line(m_label, m_done, m_total, elapsed(), what,
                                          std::clamp(width / 6, 10, 24));
  line.resize(size_t(width), ' ');
  emit("\r" + line);
  m_open_line = true;
}

void Progress::step(const std::string& what) {
  check_interrupt();  // a long job stops here after SIGINT / SIGTERM (core/interrupt.h)
  ++m_done;
  m_total = std::max(m_total, m_done);
  draw(what);
}

void Progress::finish() {
  if (m_open_line) emit("\n");
  m_open_line = false;
}

}  // namespace sylva

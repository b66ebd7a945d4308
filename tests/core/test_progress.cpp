// The progress reporter: the ETA arithmetic, duration formatting, the plain one-line-per-step
// format for logs, the in-place terminal redraw, quiet mode; times come from a fake clock.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/progress.h"

namespace sylva {
namespace {

TEST(Progress, EtaIsMeanStepTimeTimesStepsLeft) {
  EXPECT_FALSE(progress_eta(0, 10, 5.0).has_value());
  EXPECT_DOUBLE_EQ(*progress_eta(1, 10, 2.0), 18.0);
  EXPECT_DOUBLE_EQ(*progress_eta(4, 10, 8.0), 12.0);
  EXPECT_DOUBLE_EQ(*progress_eta(10, 10, 8.0), 0.0);
  EXPECT_DOUBLE_EQ(*progress_eta(12, 10, 8.0), 0.0);
  EXPECT_DOUBLE_EQ(*progress_eta(0, 0, 0.0), 0.0);
  EXPECT_FALSE(progress_eta(1, 10, std::nan("")).has_value());
  EXPECT_FALSE(progress_eta(1, 10, -1.0).has_value());
}

TEST(Progress, Durations) {
  EXPECT_EQ(format_duration(0.0), "0:00");
  EXPECT_EQ(format_duration(7.9), "0:07");
  EXPECT_EQ(format_duration(754.0), "12:34");
  EXPECT_EQ(format_duration(3599.99), "59:59");
  EXPECT_EQ(format_duration(3723.0), "1:02:03");
  EXPECT_EQ(format_duration(std::nullopt), "--:--");
  EXPECT_EQ(format_duration(-1.0), "--:--");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "--:--");
}

TEST(Progress, PlainLine) {
  EXPECT_EQ(format_progress_line("study", 3, 10, 12.0, "grid 64"),
            "study  3/10   30%  elapsed 0:12  eta 0:28  grid 64");
  EXPECT_EQ(format_progress_line("study", 0, 10, 0.0, ""),
            "study  0/10    0%  elapsed 0:00  eta --:--");
  EXPECT_EQ(format_progress_line("s", 7, 7, 61.0, "x"), "s 7/7  100%  elapsed 1:01  eta 0:00  x");
  EXPECT_EQ(format_progress_line("s", 9, 7, 1.0, ""), "s 7/7  100%  elapsed 0:01  eta 0:00");
  EXPECT_EQ(format_progress_line("s", 0, 0, 0.0, ""), "s 0/0  100%  elapsed 0:00  eta 0:00");
}

TEST(Progress, BarLine) {
  EXPECT_EQ(format_progress_line("s", 1, 4, 2.0, "a", 8),
            "s [##------] 1/4   25%  0:02 < eta 0:06  a");
  EXPECT_EQ(format_progress_line("s", 4, 4, 2.0, "", 4), "s [####] 4/4  100%  0:02 < eta 0:00");
}

// A fake clock advanced by the test, and a sink that records the text.
struct Fixture {
  double now = 100.0;
  std::string text;
  ProgressOptions options(bool terminal) {
    ProgressOptions o;
    o.terminal = terminal;
    o.sink = [this](std::string_view s) { text += s; };
    o.clock = [this] { return now; };
    o.columns = 60;
    return o;
  }
};

TEST(Progress, NotATerminalPrintsOneLinePerStep) {
  Fixture f;
  {
    Progress p("study", 3, f.options(false));
    EXPECT_EQ(f.text, "");  // nothing until the first step
    f.now += 2.0;
    p.step("reference");
    f.now += 4.0;
    p.step("fraction 0.5");
    f.now += 3.0;
    p.step("fraction 0.25");
    EXPECT_DOUBLE_EQ(p.elapsed(), 9.0);
    EXPECT_EQ(p.done(), 3u);
  }
  EXPECT_EQ(f.text,
            "study 1/3   33%  elapsed 0:02  eta 0:04  reference\n"
            "study 2/3   66%  elapsed 0:06  eta 0:03  fraction 0.5\n"
            "study 3/3  100%  elapsed 0:09  eta 0:00  fraction 0.25\n");
}

TEST(Progress, TerminalRedrawsInPlace) {
  Fixture f;
  {
    Progress p("study", 2, f.options(true));
    f.now += 1.0;
    p.step("one");
    p.finish();
    p.finish();
  }
  // Two draws (the empty bar, one step), each '\r' and 59 columns, and one line end.
  ASSERT_EQ(f.text.size(), 2u * 60u + 1u);
  EXPECT_EQ(f.text[0], '\r');
  EXPECT_EQ(f.text[60], '\r');
  EXPECT_EQ(f.text.back(), '\n');
  EXPECT_EQ(f.text.find('\n'), f.text.size() - 1);
  EXPECT_EQ(f.text.substr(61, 36), "study [#####-----] 1/2   50%  0:01 <");
}

TEST(Progress, QuietPrintsNothing) {
  Fixture f;
  ProgressOptions o = f.options(true);
  o.quiet = true;
  {
    Progress p("study", 2, o);
    p.step("one");
    p.step("two");
    p.step("three");  // beyond the total: counted
    EXPECT_EQ(p.done(), 3u);
  }
  EXPECT_EQ(f.text, "");
}

}  // namespace
}  // namespace sylva

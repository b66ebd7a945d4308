// The charts of the trade-off studies (studies/*_study.h): error against time on a log-scale
// x axis, one panel per error measure, drawn with OpenCV's imgproc
// (Debian's OpenCV has no plot module linked here). Each study lays out its own title,
// panels and legend with these pieces, so the charts look alike.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sylva {

inline const cv::Scalar kChartBlack(0, 0, 0), kChartAxisGrey(90, 90, 90),
    kChartGridGrey(228, 228, 228), kChartTextGrey(70, 70, 70);

enum class ChartMarker { Circle, Triangle, Square, Diamond };

// Draws on an 8-bit BGR image; every length is given for a 1200 x 800 chart and scaled by s.
struct ChartPainter {
  cv::Mat& img;
  double s;  // scale relative to 1200x800

  int px(double v) const;
  cv::Size text_size(const std::string& t, double size, int thick = 1) const;
  // Text anchored by `align` (0 left, 0.5 centre, 1 right) at the baseline y.
  void text(const std::string& t, cv::Point p, double size, cv::Scalar c, double align = 0,
            int thick = 1) const;
  // Text turned 90 degrees counter-clockwise, centred on p.
  void vertical_text(const std::string& t, cv::Point p, double size, cv::Scalar c) const;
  // A filled marker of radius r with a white outline.
  void marker(ChartMarker shape, cv::Point p, cv::Scalar c, int r) const;
};

// "%g" of v.
std::string chart_tick_label(double v);
// 1-2-5 ticks on a log axis inside [lo, hi] (0 < lo < hi); every integer multiple when that
// gives fewer than three.
std::vector<double> chart_log_ticks(double lo, double hi);
// A 1-2-5 step giving about `target` intervals over [0, hi] (hi > 0).
double chart_nice_step(double hi, int target);
// The x range of a log axis showing [lo, hi] (both > 0) with a margin: a tenth of its
// decades, at least a factor 1.25 each side.
std::pair<double, double> chart_log_range(double lo, double hi);

struct ChartPoint {
  double x = 1, y = 0;  // x > 0 (log axis), y >= 0
  std::string label;    // drawn next to the point where it overlaps no other label; may be empty
  bool ring = false;    // circled in black (a reference)
};

struct ChartSeries {
  cv::Scalar colour;
  ChartMarker marker = ChartMarker::Circle;
  std::vector<ChartPoint> points;  // joined by lines in this order
};

struct ChartPanel {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  // A reference that is not one of the points: a ring at (x, 0) labelled `lone_label`.
  std::optional<double> lone_x;
  std::string lone_label = "reference";
  // Shown in the middle of the panel when no series has a point (e.g. no such pixels).
  std::string empty_note;
};

// One panel in `area`: axes from 0 to the largest y (1-2-5 steps) and over [x_lo, x_hi] (log),
// grid lines, ticks, labels, the series' lines, markers and point labels. The y label sits
// left of the axis (further out when `first_panel`, where the tick labels are wider).
void draw_chart_panel(const ChartPainter& painter, cv::Rect area, const ChartPanel& panel,
                      double x_lo, double x_hi, bool first_panel);

// The layout the study charts share: title lines above y = 130 (at 1200 x 800), two panels
// side by side, and below them a legend of `legend_rows` rows (at least one) and a line for
// the reference; `legend_y` is the baseline of its first row.
struct ChartLayout {
  cv::Rect left, right;
  int legend_y = 0;
};
ChartLayout chart_two_panel_layout(const ChartPainter& painter, int legend_rows);

// A legend entry at baseline `at`: a short line with the series' marker, then `name`.
void draw_chart_legend_entry(const ChartPainter& painter, cv::Point at, cv::Scalar colour,
                             ChartMarker marker, const std::string& name);

// The reference's black ring and `note` after it, at baseline `at`.
void draw_chart_reference_note(const ChartPainter& painter, cv::Point at, const std::string& note);

}  // namespace sylva

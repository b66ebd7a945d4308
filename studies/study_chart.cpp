#include "studies/study_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace sylva {

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

}  // namespace

int ChartPainter::px(double v) const {
  return int(std::lround(v * s));
}

cv::Size ChartPainter::text_size(const std::string& t, double size, int thick) const {
  int base = 0;
  return cv::getTextSize(t, kFont, size * s, std::max(1, px(thick)), &base);
}

void ChartPainter::text(const std::string& t, cv::Point p, double size, cv::Scalar c, double align,
                        int thick) const {
  const cv::Size sz = text_size(t, size, thick);
  cv::putText(img, t, {p.x - int(align * sz.width), p.y}, kFont, size * s, c,
              std::max(1, px(thick)), cv::LINE_AA);
}

void ChartPainter::vertical_text(const std::string& t, cv::Point p, double size,
                                 cv::Scalar c) const {
  const cv::Size sz = text_size(t, size);
  cv::Mat strip(sz.height * 2, sz.width + 4, img.type(), cv::Scalar(255, 255, 255));
  cv::putText(strip, t, {2, sz.height + sz.height / 2}, kFont, size * s, c, std::max(1, px(1)),
              cv::LINE_AA);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect r(p.x - turned.cols / 2, p.y - turned.rows / 2, turned.cols, turned.rows);
  r &= cv::Rect(0, 0, img.cols, img.rows);
  turned(cv::Rect(0, 0, r.width, r.height)).copyTo(img(r));
}

void ChartPainter::marker(ChartMarker shape, cv::Point p, cv::Scalar c, int r) const {
  const cv::Scalar white(255, 255, 255);
  const int line = std::max(1, px(1));
  if (shape == ChartMarker::Circle) {
    cv::circle(img, p, r, c, cv::FILLED, cv::LINE_AA);
    cv::circle(img, p, r, white, line, cv::LINE_AA);
    return;
  }
  std::vector<cv::Point> poly;
  if (shape == ChartMarker::Triangle) {
    const int h = int(std::lround(r * 1.25));
    poly = {{p.x, p.y - h}, {p.x - h, p.y + h * 3 / 4}, {p.x + h, p.y + h * 3 / 4}};
  } else if (shape == ChartMarker::Square) {
    const int h = int(std::lround(r * 0.9));
    poly = {{p.x - h, p.y - h}, {p.x + h, p.y - h}, {p.x + h, p.y + h}, {p.x - h, p.y + h}};
  } else {
    const int h = int(std::lround(r * 1.3));
    poly = {{p.x, p.y - h}, {p.x + h, p.y}, {p.x, p.y + h}, {p.x - h, p.y}};
  }
  cv::fillConvexPoly(img, poly, c, cv::LINE_AA);
  cv::polylines(img, poly, true, white, line, cv::LINE_AA);
}

std::string chart_tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::vector<double> chart_log_ticks(double lo, double hi) {
  for (const std::vector<int>& mult : {std::vector<int>{1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
    std::vector<double> t;
    for (int e = int(std::floor(std::log10(lo))); e <= int(std::ceil(std::log10(hi))); ++e)
      for (int m : mult) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
      }
    if (t.size() >= 3 || mult.size() > 3) return t;
  }
  return {};
}

double chart_nice_step(double hi, int target) {
  const double raw = hi / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= raw) return m * mag;
  return 10 * mag;
}

std::pair<double, double> chart_log_range(double lo, double hi) {
  const double pad = std::max(1.25, std::pow(hi / lo, 0.08));
  return {lo / pad, hi * pad};
}

void draw_chart_panel(const ChartPainter& P, cv::Rect area, const ChartPanel& panel, double x_lo,
                      double x_hi, bool first_panel) {
  double y_hi = 0;
  for (const ChartSeries& s : panel.series)
    for (const ChartPoint& p : s.points)
      y_hi = std::max(y_hi, p.y);
  if (!(y_hi > 0)) y_hi = 1;
  const double step = chart_nice_step(y_hi * 1.03, 5);
  y_hi = std::ceil(y_hi * 1.03 / step) * step;

  const double lx0 = std::log10(x_lo), lx1 = std::log10(x_hi);
  auto X = [&](double x) {
    return area.x + int(std::lround((std::log10(x) - lx0) / (lx1 - lx0) * area.width));
  };
  auto Y = [&](double v) {
    return area.y + area.height - int(std::lround(v / y_hi * area.height));
  };

  P.text(panel.title, {area.x + area.width / 2, area.y - P.px(14)}, 0.6, kChartBlack, 0.5, 1);
  for (double v = 0; v <= y_hi * (1 + 1e-9); v += step) {
    const int y = Y(v);
    cv::line(P.img, {area.x, y}, {area.x + area.width, y}, kChartGridGrey, 1, cv::LINE_AA);
    cv::line(P.img, {area.x - P.px(5), y}, {area.x, y}, kChartAxisGrey, 1, cv::LINE_AA);
    P.text(chart_tick_label(std::abs(v) < step * 1e-6 ? 0.0 : v), {area.x - P.px(8), y + P.px(5)},
           0.45, kChartTextGrey, 1.0);
  }
  // Tick labels that would touch one already drawn are left out: decades (1, 10, ...) first,
  // then the rest from left to right.
  const std::vector<double> ticks = chart_log_ticks(x_lo, x_hi);
  std::vector<std::pair<int, int>> labelled;  // x extents of the drawn labels
  auto label = [&](double v) {
    const int x = X(v);
    const std::string t = chart_tick_label(v);
    const int half = P.text_size(t, 0.45).width / 2 + P.px(4);
    for (const auto& [a, b] : labelled)
      if (x - half < b && x + half > a) return;
    labelled.emplace_back(x - half, x + half);
    P.text(t, {x, area.y + area.height + P.px(22)}, 0.45, kChartTextGrey, 0.5);
  };
  auto decade = [](double v) {
    const double e = std::log10(v);
    return std::abs(e - std::round(e)) < 1e-9;
  };
  for (double v : ticks) {
    const int x = X(v);
    cv::line(P.img, {x, area.y}, {x, area.y + area.height}, kChartGridGrey, 1, cv::LINE_AA);
    cv::line(P.img, {x, area.y + area.height}, {x, area.y + area.height + P.px(5)}, kChartAxisGrey,
             1, cv::LINE_AA);
    if (decade(v)) label(v);
  }
  for (double v : ticks)
    if (!decade(v)) label(v);
  cv::rectangle(P.img, area, kChartAxisGrey, 1, cv::LINE_AA);
  P.text(panel.x_label, {area.x + area.width / 2, area.y + area.height + P.px(48)}, 0.5,
         kChartBlack, 0.5);
  P.vertical_text(panel.y_label, {area.x - P.px(first_panel ? 58 : 52), area.y + area.height / 2},
                  0.5, kChartBlack);
  const bool any = std::any_of(panel.series.begin(), panel.series.end(),
                               [](const ChartSeries& s) { return !s.points.empty(); });
  if (!any && !panel.empty_note.empty())
    P.text(panel.empty_note, {area.x + area.width / 2, area.y + area.height / 2}, 0.55,
           kChartTextGrey, 0.5);

  // Lines first, markers over them, labels last so nothing hides them.
  for (const ChartSeries& s : panel.series)
    for (size_t i = 1; i < s.points.size(); ++i)
      cv::line(P.img, {X(s.points[i - 1].x), Y(s.points[i - 1].y)},
               {X(s.points[i].x), Y(s.points[i].y)}, s.colour, P.px(2), cv::LINE_AA);
  for (const ChartSeries& s : panel.series)
    for (const ChartPoint& p : s.points) {
      if (p.ring) cv::circle(P.img, {X(p.x), Y(p.y)}, P.px(11), kChartBlack, P.px(2), cv::LINE_AA);
      P.marker(s.marker, {X(p.x), Y(p.y)}, s.colour, P.px(5));
    }
  // Point labels: the first of four spots around the point that overlaps no label drawn so
  // far and stays inside the panel; none when all four do (points on top of each other).
  std::vector<cv::Rect> taken;
  for (const ChartSeries& s : panel.series)
    for (const ChartPoint& p : s.points) {
      if (p.label.empty()) continue;
      const cv::Size sz = P.text_size(p.label, 0.36);
      const cv::Point c(X(p.x), Y(p.y));
      const int d = P.px(7);
      for (const cv::Point& at :
           {cv::Point(c.x + d, c.y - d), cv::Point(c.x + d, c.y + d + sz.height),
            cv::Point(c.x - d - sz.width, c.y - d),
            cv::Point(c.x - d - sz.width, c.y + d + sz.height)}) {
        const cv::Rect box(at.x - 1, at.y - sz.height - 1, sz.width + 2, sz.height + 3);
        if ((box & area) != box || std::any_of(taken.begin(), taken.end(), [&](const cv::Rect& t) {
              return (t & box).area() > 0;
            }))
          continue;
        taken.push_back(box);
        P.text(p.label, at, 0.36, s.colour * 0.8);
        break;
      }
    }
  if (panel.lone_x) {
    const cv::Point p(X(*panel.lone_x), Y(0));
    cv::circle(P.img, p, P.px(11), kChartBlack, P.px(2), cv::LINE_AA);
    cv::circle(P.img, p, P.px(4), kChartBlack, cv::FILLED, cv::LINE_AA);
    P.text(panel.lone_label, {p.x, p.y - P.px(16)}, 0.42, kChartBlack, 0.5);
  }
}

ChartLayout chart_two_panel_layout(const ChartPainter& P, int legend_rows) {
  const int width = P.img.cols, height = P.img.rows;
  const int top = P.px(130), legend_h = P.px(40 + 26 * std::max(1, legend_rows));
  const int bottom = height - legend_h - P.px(62);
  const int left = P.px(90), gap = P.px(100), right = P.px(30);
  const int panel_w = (width - left - gap - right) / 2;
  ChartLayout layout;
  layout.left = cv::Rect(left, top, panel_w, bottom - top);
  layout.right = cv::Rect(left + panel_w + gap, top, panel_w, bottom - top);
  layout.legend_y = height - legend_h + P.px(6);
  return layout;
}

void draw_chart_legend_entry(const ChartPainter& P, cv::Point at, cv::Scalar colour,
                             ChartMarker marker, const std::string& name) {
  cv::line(P.img, {at.x, at.y - P.px(5)}, {at.x + P.px(36), at.y - P.px(5)}, colour, P.px(2),
           cv::LINE_AA);
  P.marker(marker, {at.x + P.px(18), at.y - P.px(5)}, colour, P.px(5));
  P.text(name, {at.x + P.px(44), at.y}, 0.48, kChartTextGrey);
}

void draw_chart_reference_note(const ChartPainter& P, cv::Point at, const std::string& note) {
  cv::circle(P.img, {at.x + P.px(18), at.y - P.px(5)}, P.px(9), kChartBlack, P.px(2), cv::LINE_AA);
  P.text(note, {at.x + P.px(36), at.y}, 0.45, kChartTextGrey);
}

}  // namespace sylva

#include "styles/sheet_layout.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/error.h"

namespace sylva {

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

std::string ascii(const std::string& s) {
  std::string out = s;
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return out;
}

int text_width(const std::string& s, double scale, int thickness) {
  int base = 0;
  return cv::getTextSize(s, kFont, scale, thickness, &base).width;
}

// The longest prefix of `s` (plus "...") that fits in `width`.
std::string cut_to(const std::string& s, int width, double scale, int thickness = 1) {
  if (text_width(s, scale, thickness) <= width) return s;
  std::string t = s;
  while (!t.empty() && text_width(t + "...", scale, thickness) > width)
    t.pop_back();
  return t + "...";
}

}  // namespace

std::vector<std::string> wrap_items(const std::vector<std::string>& items, int width, double scale,
                                    int max_lines, int thickness) {
  std::vector<std::string> lines;
  if (max_lines <= 0 || items.empty()) return lines;
  std::string line;
  size_t i = 0;
  for (; i < items.size(); ++i) {
    const std::string item = ascii(items[i]);
    const std::string joined = line.empty() ? item : line + "  " + item;
    if (text_width(joined, scale, thickness) <= width) {
      line = joined;
      continue;
    }
    if (line.empty()) {  // one item wider than the line
      line = cut_to(item, width, scale, thickness);
      continue;
    }
    lines.push_back(line);
    if (static_cast<int>(lines.size()) == max_lines) break;
    line =
        text_width(item, scale, thickness) <= width ? item : cut_to(item, width, scale, thickness);
  }
  if (static_cast<int>(lines.size()) < max_lines && !line.empty()) {
    lines.push_back(line);
    line.clear();
  }
  if (i < items.size() || !line.empty())  // something was left out
    lines.back() = cut_to(lines.back() + "  ...", width, scale, thickness);
  return lines;
}

cv::Mat layout_sheet(const std::vector<SheetCell>& cells, const SheetLayout& layout) {
  SYLVA_CHECK(!cells.empty(), "layout_sheet: no cells");
  SYLVA_CHECK(layout.columns >= 0 && layout.max_detail_lines >= 0 && layout.max_detail_lines <= 20,
              "layout_sheet: bad layout");
  const cv::Size size = cells[0].image.size();
  for (const SheetCell& c : cells)
    SYLVA_CHECK(c.image.type() == CV_8UC4 && c.image.size() == size,
                "layout_sheet: cells must be CV_8UC4 of one size");
  const int n = static_cast<int>(cells.size());
  const int columns = layout.columns > 0
                          ? std::min(layout.columns, n)
                          : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)) - 1e-9));
  const int rows = (n + columns - 1) / columns;

  // Type sizes follow the cell width: a ~25 px title on a 1024 px cell, never below ~9 px.
  const double title_scale = std::clamp(size.width / 900.0, 0.4, 2.5);
  const double detail_scale = title_scale * 0.8;
  const int title_thickness = std::max(1, static_cast<int>(std::lround(title_scale * 2)));
  int base = 0;
  const int title_h = cv::getTextSize("Hg", kFont, title_scale, title_thickness, &base).height;
  const int detail_h = cv::getTextSize("Hg", kFont, detail_scale, 1, &base).height;
  const int pad = std::max(4, title_h / 2);
  const int text_w = size.width - 2 * pad;

  std::vector<std::vector<std::string>> titles(cells.size()), details(cells.size());
  int title_lines = 0, lines = 0;
  for (size_t i = 0; i < cells.size(); ++i) {
    titles[i] = wrap_items(cells[i].title, text_w, title_scale, 2, title_thickness);
    details[i] = wrap_items(cells[i].details, text_w, detail_scale, layout.max_detail_lines);
    title_lines = std::max(title_lines, static_cast<int>(titles[i].size()));
    lines = std::max(lines, static_cast<int>(details[i].size()));
  }
  const int title_line_h = title_h + title_h / 2;
  const int line_h = detail_h + detail_h / 2 + 2;
  const int label_h = pad + title_lines * title_line_h + lines * line_h + pad;
  const int cell_w = size.width + pad, cell_h = size.height + label_h + pad;

  cv::Mat sheet(rows * cell_h + pad, columns * cell_w + pad, CV_8UC4,
                cv::Scalar(255, 255, 255, 255));
  const cv::Scalar ink(40, 40, 40, 255), grey(90, 90, 90, 255);
  for (int i = 0; i < n; ++i) {
    const int x = pad + (i % columns) * cell_w, y = pad + (i / columns) * cell_h;
    cells[i].image.copyTo(sheet(cv::Rect(x, y, size.width, size.height)));
    int ty = y + size.height + pad;
    for (const std::string& line : titles[i]) {
      ty += title_line_h;
      cv::putText(sheet, line, {x + pad, ty - title_h / 2}, kFont, title_scale, ink,
                  title_thickness, cv::LINE_AA);
    }
    ty = y + size.height + pad + title_lines * title_line_h;
    for (const std::string& line : details[i]) {
      ty += line_h;
      cv::putText(sheet, line, {x + pad, ty - line_h / 4}, kFont, detail_scale, grey, 1,
                  cv::LINE_AA);
    }
  }
  return sheet;
}

}  // namespace sylva

// The contact sheet's picture: cells in a grid, each image with a label below it (title and
// detail items wrapped to the cell width), on an opaque white sheet. Text is OpenCV's Hershey font,
// ASCII only (other bytes print as '?'), scaled with the cell width so a 256 px and a
// 2048 px sheet read alike.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace sylva {

struct SheetCell {
  cv::Mat image;                     // CV_8UC4 BGRA; every cell the same size
  std::vector<std::string> title;    // dark items, e.g. the style and its swept values (<= 2 lines)
  std::vector<std::string> details;  // grey "key=value" items
};

struct SheetLayout {
  int columns = 0;           // cells per row, >= 1; 0 = ceil(sqrt(n))
  int max_detail_lines = 3;  // [0, 20]; items that do not fit end the last line in "..."
};

// Images keep their alpha (a transparent background stays transparent); gaps and labels are
// opaque white with dark text. Throws SYLVA_CHECK on no cells, mixed sizes or a bad layout.
cv::Mat layout_sheet(const std::vector<SheetCell>& cells, const SheetLayout& layout = {});

// Items packed into lines no wider than `width` px at `scale` and stroke `thickness` (Hershey
// simplex), separated by two spaces; at most `max_lines`, the last ending in "..." when items
// are left over. An item wider than a line is cut. Exposed for tests.
std::vector<std::string> wrap_items(const std::vector<std::string>& items, int width, double scale,
                                    int max_lines, int thickness = 1);

}  // namespace sylva

#include "passes/thinning.h"

#include <cstdint>

#include "core/error.h"

namespace sylva {

namespace {

// One sub-iteration: marks every on pixel whose 8 neighbours P2..P9 (north first, clockwise)
// hold 2..6 on pixels with exactly one off-to-on step around the ring, and whose east/south
// (pass 0) or north/west (pass 1) sides are open; then removes the marked ones together.
bool thin_pass(cv::Mat& img, cv::Mat& marker, int pass) {
  marker.setTo(0);
  bool changed = false;
  for (int y = 1; y + 1 < img.rows; ++y) {
    const uint8_t* up = img.ptr<uint8_t>(y - 1);
    const uint8_t* row = img.ptr<uint8_t>(y);
    const uint8_t* down = img.ptr<uint8_t>(y + 1);
    uint8_t* mark = marker.ptr<uint8_t>(y);
    for (int x = 1; x + 1 < img.cols; ++x) {
      if (!row[x]) continue;
      const int p2 = up[x], p3 = up[x + 1], p4 = row[x + 1], p5 = down[x + 1];
      const int p6 = down[x], p7 = down[x - 1], p8 = row[x - 1], p9 = up[x - 1];
      const int b = p2 + p3 + p4 + p5 + p6 + p7 + p8 + p9;
      const int a = (!p2 && p3) + (!p3 && p4) + (!p4 && p5) + (!p5 && p6) + (!p6 && p7) +
                    (!p7 && p8) + (!p8 && p9) + (!p9 && p2);
      const bool open = pass == 0 ? (!(p2 && p4 && p6) && !(p4 && p6 && p8))
                                  : (!(p2 && p4 && p8) && !(p2 && p6 && p8));
      if (a == 1 && b >= 2 && b <= 6 && open) {
        mark[x] = 1;
        changed = true;
      }
    }
  }
  if (changed) img.setTo(0, marker);
  return changed;
}

}  // namespace

cv::Mat thin_zhang_suen(const cv::Mat& binary) {
  SYLVA_CHECK(binary.type() == CV_8UC1, "thin_zhang_suen: CV_8UC1 expected");
  cv::Mat img = binary != 0;
  img /= 255;  // 0/1, so the neighbour sums count
  cv::Mat marker(img.size(), CV_8UC1);
  bool changed = true;
  while (changed) {
    const bool first = thin_pass(img, marker, 0);
    const bool second = thin_pass(img, marker, 1);
    changed = first || second;
  }
  return img * 255;
}

}  // namespace sylva

#include "passes/pass_common.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace sylva {

double reference_scale(const cv::Size& size) {
  return double(std::min(size.width, size.height)) / double(kReferenceResolution);
}

void expect_image(const cv::Mat& m, int type, const cv::Size& size, const char* what) {
  SYLVA_CHECK(!m.empty() && m.type() == type && (size.empty() || m.size() == size),
              std::string("image pass input '") + what + "' has the wrong type or size");
}

}  // namespace sylva

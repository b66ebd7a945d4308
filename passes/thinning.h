// Zhang-Suen thinning (T. Y. Zhang and C. Y. Suen, "A fast parallel algorithm for thinning digital
// patterns", CACM 27(3), 1984): the one-pixel skeleton the ink's chains follow. The same rule and
// border handling as OpenCV's cv::ximgproc::thinning(THINNING_ZHANGSUEN), which
// tests/passes/test_thinning.cpp compares it with; Sylva does not link opencv_ximgproc because it
// pulls opencv_imgcodecs (GDAL, GDCM, poppler ...) into every process, 0.2 s before main().
#pragma once

#include <opencv2/core.hpp>

namespace sylva {

// `binary`: CV_8UC1, non-zero = on. Returns CV_8UC1 0/255. Pixels on the image's outer rows and
// columns are never removed (as OpenCV's).
cv::Mat thin_zhang_suen(const cv::Mat& binary);

}  // namespace sylva

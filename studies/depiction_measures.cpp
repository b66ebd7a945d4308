#include "studies/depiction_measures.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"

namespace sylva {

namespace {

cv::Mat disc(double r) {
  const int k = std::max(1, int(std::lround(r)));
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * k + 1, 2 * k + 1});
}

cv::Mat bgr_of(const cv::Mat& m) {
  cv::Mat bgr;
  if (m.channels() == 4)
    cv::cvtColor(m, bgr, cv::COLOR_BGRA2BGR);
  else
    bgr = m;
  return bgr;
}

// Brown (a wood colour): hue under 25 or over 160 of OpenCV's 180, saturation over 30.
cv::Mat woody(const cv::Mat& bgr) {
  cv::Mat hsv, ch[3];
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  cv::split(hsv, ch);
  return ((ch[0] < 25) | (ch[0] > 160)) & (ch[1] > 30);
}

// The plant (not white, or alpha > 0 when the render's background is transparent) and its
// brown wood at least 3 px wide at 1024 px in pieces of at least 1e-4 of the image.
void plant_and_wood(const cv::Mat& standard, double s, cv::Mat& plant, cv::Mat& wood) {
  const cv::Mat bgr = bgr_of(standard);
  cv::Mat f, sum;
  bgr.convertTo(f, CV_32F);
  cv::transform(f, sum, cv::Matx13f(1, 1, 1));
  plant = sum < 765.0f - 6.0f;
  if (standard.channels() == 4) {
    cv::Mat alpha;
    cv::extractChannel(standard, alpha, 3);
    if (cv::countNonZero(alpha == 0) > 0) plant = alpha > 0;
  }
  wood = plant & woody(bgr);
  cv::morphologyEx(wood, wood, cv::MORPH_OPEN, disc(1.5 * s));
  cv::Mat labels, stats, centres;
  const int n = cv::connectedComponentsWithStats(wood, labels, stats, centres);
  const double least = 1e-4 * double(standard.total());
  for (int y = 0; y < wood.rows; ++y)
    for (int x = 0; x < wood.cols; ++x)
      if (const int l = labels.at<int>(y, x); l > 0 && l < n)
        wood.at<uint8_t>(y, x) = stats.at<int>(l, cv::CC_STAT_AREA) >= least ? 255 : 0;
}

double mean_in(const cv::Mat& values, const cv::Mat& where) {
  const int n = cv::countNonZero(where);
  return n > 0 ? double(cv::countNonZero(values & where)) / n : 0.0;
}

// Share of `a`'s pixels within px of `b`'s (1 when `a` is empty).
double near(const cv::Mat& a, const cv::Mat& b, double px) {
  if (cv::countNonZero(a) == 0) return 1.0;
  cv::Mat d;
  cv::distanceTransform(b == 0, d, cv::DIST_L2, 3);
  return mean_in(d <= float(px), a);
}

// What a drawing encloses: its marks closed over `px`, then every hole the border cannot reach.
cv::Mat enclosed(const cv::Mat& marks, double px) {
  cv::Mat m;
  cv::morphologyEx(marks, m, cv::MORPH_CLOSE, disc(px));
  cv::Mat flood = m.clone();
  cv::Mat pad = cv::Mat::zeros(m.rows + 2, m.cols + 2, CV_8UC1);
  cv::floodFill(flood, pad, {0, 0}, cv::Scalar(128));
  return flood != 128;
}

double spearman(const std::vector<float>& a, const std::vector<float>& b) {
  auto ranks = [](const std::vector<float>& v) {
    std::vector<size_t> order(v.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return v[i] < v[j]; });
    std::vector<double> r(v.size());
    for (size_t k = 0; k < order.size(); ++k)
      r[order[k]] = double(k);
    return r;
  };
  std::vector<double> ra = ranks(a), rb = ranks(b);
  const double mean = (double(a.size()) - 1.0) / 2.0;
  double num = 0, da = 0, db = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    num += (ra[i] - mean) * (rb[i] - mean);
    da += (ra[i] - mean) * (ra[i] - mean);
    db += (rb[i] - mean) * (rb[i] - mean);
  }
  return num / std::sqrt(da * db + 1e-12);
}

cv::Mat gray_of(const cv::Mat& image) {
  cv::Mat g;
  cv::cvtColor(bgr_of(image), g, cv::COLOR_BGR2GRAY);
  return g;
}

// Darkness (1 - grey) averaged over the plant only (the paper left out), a Gaussian of sigma px.
cv::Mat plant_darkness(const cv::Mat& image, const cv::Mat& plant, double sigma) {
  cv::Mat dark, m, norm;
  gray_of(image).convertTo(dark, CV_32F, -1.0 / 255.0, 1.0);
  plant.convertTo(m, CV_32F, 1.0 / 255.0);
  cv::GaussianBlur(dark.mul(m), dark, {0, 0}, sigma);
  cv::GaussianBlur(m, norm, {0, 0}, sigma);
  return dark / (norm + 1e-6f);
}

// Tone: Spearman of the two plant darknesses away from the silhouette, and the expressive
// one's interquartile range there.
void tone_of(const cv::Mat& picture, const cv::Mat& expressive, const cv::Mat& plant, double size,
             DepictionMeasures& out) {
  const double sigma = 0.015 * size;
  const cv::Mat dp = plant_darkness(picture, plant, sigma);
  const cv::Mat de = plant_darkness(expressive, plant, sigma);
  cv::Mat core;
  cv::erode(plant, core, disc(0.01 * size));
  const cv::Mat& where = cv::countNonZero(core) > 1000 ? core : plant;
  std::vector<cv::Point> at;
  cv::findNonZero(where, at);
  if (at.size() < 2) return;
  const size_t step = std::max<size_t>(1, at.size() / 40000);
  std::vector<float> a, b;
  for (size_t i = 0; i < at.size(); i += step) {
    a.push_back(dp.at<float>(at[i]));
    b.push_back(de.at<float>(at[i]));
  }
  out.tone = spearman(a, b);
  std::vector<float> sorted = b;
  std::sort(sorted.begin(), sorted.end());
  auto q = [&](double p) {
    return double(sorted[size_t(std::lround(p * double(sorted.size() - 1)))]);
  };
  out.tone_range = q(0.75) - q(0.25);
}

}  // namespace

DepictionMeasures measure_depiction(const cv::Mat& standard, const cv::Mat& expressive,
                                    const cv::Mat& picture, bool line_style) {
  SYLVA_CHECK(
      standard.size() == picture.size() && expressive.size() == picture.size() && !picture.empty(),
      "measure_depiction: three images of one size");
  const double size = picture.cols, s = size / 1024.0;
  DepictionMeasures m;
  cv::Mat plant, wood;
  plant_and_wood(standard, s, plant, wood);
  cv::Mat eroded;
  cv::erode(wood, eroded, disc(1));
  const cv::Mat wood_edge = wood & ~eroded;
  const cv::Mat g = gray_of(picture);
  // Paper: the picture's median level away from the plant.
  cv::Mat grown;
  cv::dilate(plant, grown, disc(8 * s));
  std::vector<uint8_t> outside;
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.cols; ++x)
      if (!grown.at<uint8_t>(y, x)) outside.push_back(g.at<uint8_t>(y, x));
  double paper = 255.0;
  if (!outside.empty()) {
    std::nth_element(outside.begin(), outside.begin() + long(outside.size() / 2), outside.end());
    paper = outside[outside.size() / 2];
  }
  const cv::Mat ink = g < std::min(128.0, paper - 60.0);
  cv::Mat painted;
  cv::absdiff(g, cv::Scalar(paper), painted);
  painted = painted > 12;
  cv::Mat region;
  if (line_style) {
    m.wood = near(wood_edge, ink, 3 * s);
    region = enclosed(ink, 6 * s);
  } else {
    cv::Mat brown = painted & woody(bgr_of(picture));
    cv::dilate(brown, brown, disc(2 * s));
    m.wood = cv::countNonZero(wood) > 0 ? mean_in(brown, wood) : 1.0;
    cv::morphologyEx(painted, region, cv::MORPH_OPEN, disc(2 * s));
  }
  tone_of(picture, expressive, plant, size, m);
  cv::Mat closed, interior, big;
  cv::morphologyEx(plant, closed, cv::MORPH_CLOSE, disc(0.01 * size));
  cv::erode(closed, interior, disc(0.03 * size));
  cv::dilate(closed, big, disc(0.01 * size));
  const int inner = cv::countNonZero(interior);
  m.inside = mean_in(ink, interior);
  m.overreach = double(cv::countNonZero(region & ~big)) / std::max(1, cv::countNonZero(plant));
  cv::Mat labels;
  const int marks = cv::connectedComponents(ink & interior, labels) - 1;
  m.marks = double(marks) / std::max(1e-9, double(inner) / ((100 * s) * (100 * s)));
  cv::Mat gf, blurred;
  g.convertTo(gf, CV_32F);
  cv::GaussianBlur(gf, blurred, {0, 0}, 4 * s);
  m.rims = mean_in((gf - blurred) < -8.0f, interior);
  return m;
}

}  // namespace sylva

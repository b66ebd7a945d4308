// The AO study's outputs (studies/ao_study.h): its CSV table and its chart
// (studies/study_chart.h).
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "core/csv.h"
#include "core/error.h"
#include "studies/ao_study.h"
#include "studies/study_chart.h"

namespace sylva {

std::string ao_study_csv(const AoStudy& study) {
  std::string csv =
      "model,shells,rays,reference,constant,alpha_rho,setup_seconds,frame_seconds,added_seconds,"
      "foliage_pixels,foliage_mean,foliage_rmse,foliage_mae,foliage_trend_rmse,nonfoliage_pixels,"
      "nonfoliage_mean,nonfoliage_rmse,nonfoliage_mae,nonfoliage_trend_rmse,error\n";
  auto num = [](const std::optional<double>& v, const char* fmt) {
    return v && std::isfinite(*v) ? format_number(fmt, *v) : std::string();
  };
  auto count = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string(); };
  auto errors = [&](const AoPixelError& e) {
    return std::to_string(e.pixels) + "," + num(e.mean, "%.6g") + "," + num(e.rmse, "%.6g") + "," +
           num(e.mae, "%.6g") + "," + num(e.trend_rmse, "%.6g");
  };
  for (const AoStudyRow& r : study.rows) {
    const std::string error = csv_quoted(r.error);
    csv += r.model + "," + count(r.shells) + "," + count(r.rays) + "," + (r.reference ? "1" : "0") +
           "," + num(r.constant, "%.6g") + "," + num(r.alpha_rho, "%.6g") + "," +
           num(r.setup_seconds, "%.4f") + "," + num(r.frame_seconds, "%.5f") + "," +
           num(r.added_seconds, "%.5f") + "," + errors(r.foliage) + "," + errors(r.nonfoliage) +
           "," + error + "\n";
  }
  return csv;
}

// The chart.

namespace {

struct ModelLook {
  const char* model;
  cv::Scalar colour;  // BGR
  ChartMarker marker;
};

// Colour-blind-safe hues (Okabe-Ito), one per model.
const ModelLook kLooks[] = {
    {"none", cv::Scalar(150, 150, 150), ChartMarker::Square},
    {"constant", cv::Scalar(40, 40, 40), ChartMarker::Diamond},
    {"luft-density", cv::Scalar(115, 158, 0), ChartMarker::Circle},
    {"hegeman-sphere", cv::Scalar(178, 114, 0), ChartMarker::Circle},
    {"hegeman-ellipsoid", cv::Scalar(167, 121, 204), ChartMarker::Triangle},
    {"hegeman-shells", cv::Scalar(233, 180, 86), ChartMarker::Diamond},
    {"raytraced", cv::Scalar(0, 94, 213), ChartMarker::Circle},
};

}  // namespace

cv::Mat plot_ao_study(const AoStudy& study, const std::string& scene_name, int width, int height) {
  SYLVA_CHECK(width >= 600 && width <= 4000 && height >= 400 && height <= 4000,
              "plot size in [600, 4000] x [400, 4000]");
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const ChartPainter P{img, std::min(width / 1200.0, height / 800.0)};

  ChartPanel foliage, other;
  foliage.title = "Foliage pixels";
  other.title = "Non-foliage pixels (wood, ground)";
  foliage.x_label = other.x_label = "frame time, seconds (log scale)";
  foliage.y_label = other.y_label = "RMSE of the AO buffer against the reference";
  foliage.empty_note = "no foliage pixels in this view";
  other.empty_note = "no non-foliage pixels in this view";
  double t_lo = 1e30, t_hi = 0;
  size_t failed = 0;
  std::vector<const ModelLook*> shown;
  for (const ModelLook& look : kLooks) {
    ChartSeries sf{look.colour, look.marker, {}};
    ChartSeries so = sf;
    for (const AoStudyRow& r : study.rows) {
      if (r.model != look.model) continue;
      if (!r.frame_seconds) {
        ++failed;
        continue;
      }
      const double x = std::max(*r.frame_seconds, 1e-5);
      t_lo = std::min(t_lo, x);
      t_hi = std::max(t_hi, x);
      std::string label;
      if (r.shells) label = "k=" + std::to_string(*r.shells);
      if (r.rays) label = std::to_string(*r.rays);
      if (r.foliage.rmse) sf.points.push_back({x, *r.foliage.rmse, label, r.reference});
      if (r.nonfoliage.rmse) so.points.push_back({x, *r.nonfoliage.rmse, label, r.reference});
    }
    if (!sf.points.empty()) foliage.series.push_back(sf);
    if (!so.points.empty()) other.series.push_back(so);
    if (!sf.points.empty() || !so.points.empty()) shown.push_back(&look);
  }
  if (t_hi <= 0) t_lo = t_hi = 1;
  const auto [x_lo, x_hi] = chart_log_range(t_lo, t_hi);

  P.text("Ambient occlusion: error against frame time  -  " + scene_name, {width / 2, P.px(34)},
         0.8, kChartBlack, 0.5, 2);
  const AoStudyRow* ref = nullptr;
  for (const AoStudyRow& r : study.rows)
    if (r.reference) ref = &r;
  char sub[320];
  std::snprintf(sub, sizeof sub,
                "%dx%d pixels (%zu foliage, %zu other);  reference: ray-traced, %d rays per "
                "pixel;  constant = the reference's mean, %.3f",
                study.width, study.height, ref ? ref->foliage.pixels : size_t(0),
                ref ? ref->nonfoliage.pixels : size_t(0), study.reference_rays,
                study.reference_mean);
  P.text(sub, {width / 2, P.px(62)}, 0.48, kChartTextGrey, 0.5);
  std::string sub2 = "frame time: median of " + std::to_string(study.repeats) + " timed frame" +
                     (study.repeats == 1 ? "" : "s") + " (colour + AO buffer; none: colour only)";
  if (failed) sub2 += ";  failed models are left out (see the CSV)";
  P.text(sub2, {width / 2, P.px(84)}, 0.48, kChartTextGrey, 0.5);

  const int rows = int(shown.size() + 3) / 4;
  const ChartLayout layout = chart_two_panel_layout(P, rows);
  draw_chart_panel(P, layout.left, foliage, x_lo, x_hi, true);
  draw_chart_panel(P, layout.right, other, x_lo, x_hi, false);

  // Legend: four models per row.
  const int entry_w = P.px(230);
  const int x0 = std::max(P.px(20), (width - 4 * entry_w) / 2);
  const int y = layout.legend_y;
  for (size_t i = 0; i < shown.size(); ++i)
    draw_chart_legend_entry(P, {x0 + int(i % 4) * entry_w, y + int(i / 4) * P.px(26)},
                            shown[i]->colour, shown[i]->marker, shown[i]->model);
  draw_chart_reference_note(
      P, {x0, y + rows * P.px(26) + P.px(4)},
      "the reference (zero error by definition);  small numbers: rays per pixel, k = shells");
  return img;
}

}  // namespace sylva

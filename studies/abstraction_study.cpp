#include "studies/abstraction_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "core/error.h"
#include "studies/study_chart.h"
#include "styles/turntable_frames.h"

namespace sylva {

namespace {

// The first view of `style`, as the coherence study's turntable renders it.
cv::Mat first_view(const SheetScene& scene, const Style& style, const CoherenceStudyOptions& o) {
  TurntablePath path;
  path.frames = o.frames;
  path.degrees = o.step * float(o.frames);
  path.axis = o.axis;
  path.zoom = o.zoom;
  TurntableRenderer renderer(scene, style, path, 1);
  return renderer.render(0, false).image;
}

}  // namespace

AbstractionStudy run_abstraction_study(const SheetScene& scene_in,
                                       const std::vector<AbstractionCell>& cells,
                                       const Style& standard, const Style& expressive,
                                       const CoherenceStudyOptions& options) {
  validate_coherence_study(options);
  SYLVA_CHECK(!cells.empty(), "run_abstraction_study: no cells");
  SheetScene scene = scene_in;
  memoize_preprocessing(scene, true);
  AbstractionStudy study;
  study.width = scene.raster.camera.width;
  study.height = scene.raster.camera.height;
  study.options = options;
  study.options.on_frame = nullptr;
  const cv::Mat std_image = first_view(scene, standard, options);
  const cv::Mat exp_image = first_view(scene, expressive, options);
  for (const AbstractionCell& cell : cells) {
    SYLVA_CHECK(cell.style != nullptr, "run_abstraction_study: a cell without a style");
    AbstractionStudyRow row;
    row.style = cell.name;
    row.detail = cell.detail;
    // Depiction is measured as a line drawing: the study sweeps the line styles' knob.
    row.depiction =
        measure_depiction(std_image, exp_image, first_view(scene, *cell.style, options), true);
    const CoherenceStudy c = run_coherence_study(scene, {cell.style}, options);
    const CoherenceStudyRow& r = c.rows.front();
    row.seconds_per_frame = r.seconds_per_frame;
    row.line_pop_mean = r.line_pop_mean;
    row.line_pop_max = r.line_pop_max;
    study.rows.push_back(row);
  }
  return study;
}

std::string abstraction_study_csv(const AbstractionStudy& study) {
  std::ostringstream s;
  s.precision(9);
  s << "style,detail,width,height,wood,tone,tone_range,inside,marks,overreach,rims,"
       "line_pop_mean,line_pop_max,seconds_per_frame\n";
  auto opt = [&s](const std::optional<double>& v) {
    if (v) s << *v;
  };
  for (const AbstractionStudyRow& r : study.rows) {
    const DepictionMeasures& d = r.depiction;
    s << r.style << ',' << r.detail << ',' << study.width << ',' << study.height << ',' << d.wood
      << ',' << d.tone << ',' << d.tone_range << ',' << d.inside << ',' << d.marks << ','
      << d.overreach << ',' << d.rims << ',';
    opt(r.line_pop_mean);
    s << ',';
    opt(r.line_pop_max);
    s << ',' << r.seconds_per_frame << '\n';
  }
  return s.str();
}

cv::Mat plot_abstraction_study(const AbstractionStudy& study, const std::string& scene_name,
                               int width, int height) {
  SYLVA_CHECK(width >= 600 && width <= 4000 && height >= 400 && height <= 4000,
              "plot size in [600, 4000] x [400, 4000]");
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const ChartPainter P{img, std::min(width / 1200.0, height / 800.0)};
  // One colour per measure, one marker per style.
  const cv::Scalar wood(40, 90, 150), tone(180, 110, 30), inside(60, 60, 60), pop(60, 60, 200);
  const ChartMarker markers[] = {ChartMarker::Circle, ChartMarker::Triangle, ChartMarker::Square,
                                 ChartMarker::Diamond};
  std::map<std::string, size_t> style_index;
  for (const AbstractionStudyRow& r : study.rows)
    style_index.try_emplace(r.style, style_index.size());
  ChartPanel measures, pops;
  measures.title = "Depiction: wood, tone, inside";
  pops.title = "Line pop";
  measures.x_label = pops.x_label = "ink.detail, px at 1024 (log scale)";
  measures.y_label = "share (tone: Spearman, 0 when negative)";
  pops.y_label = "% of line pixels with no line near";
  pops.empty_note = "no lines";
  double lo = 1e30, hi = 0;
  for (const auto& [name, index] : style_index) {
    const ChartMarker m = markers[index % 4];
    ChartSeries w{wood, m, {}}, t{tone, m, {}}, in{inside, m, {}}, p{pop, m, {}};
    for (const AbstractionStudyRow& r : study.rows) {
      if (r.style != name) continue;
      const double x = std::max(0.1, double(r.detail));
      lo = std::min(lo, x);
      hi = std::max(hi, x);
      w.points.push_back({x, r.depiction.wood, "", false});
      t.points.push_back({x, std::max(0.0, r.depiction.tone), "", false});
      in.points.push_back({x, r.depiction.inside, "", false});
      if (r.line_pop_mean) p.points.push_back({x, 100 * *r.line_pop_mean, name, false});
    }
    if (!w.points.empty()) w.points.back().label = name;
    for (ChartSeries* s : {&w, &t, &in})
      measures.series.push_back(*s);
    if (!p.points.empty()) pops.series.push_back(p);
  }
  const auto [x_lo, x_hi] = chart_log_range(std::min(lo, hi), std::max(hi, lo * 1.01));
  P.text("Abstraction against depiction and coherence  -  " + scene_name, {width / 2, P.px(34)},
         0.8, kChartBlack, 0.5, 2);
  char sub[320];
  std::snprintf(sub, sizeof sub, "%dx%d pixels; line pop over %d views %g degrees apart",
                study.width, study.height, study.options.frames, double(study.options.step));
  P.text(sub, {width / 2, P.px(62)}, 0.48, kChartTextGrey, 0.5);
  P.text(
      "floors (issue 32): wood >= 0.7, tone >= 0.5 (ink) / 0.6 (pen), inside 0.04-0.35 / 0.06-0.40",
      {width / 2, P.px(84)}, 0.48, kChartTextGrey, 0.5);
  const ChartLayout layout = chart_two_panel_layout(P, 1);
  draw_chart_panel(P, layout.left, measures, x_lo, x_hi, true);
  draw_chart_panel(P, layout.right, pops, x_lo, x_hi, false);
  const int entry_w = P.px(260);
  const int x0 = std::max(P.px(20), (width - 4 * entry_w) / 2);
  draw_chart_legend_entry(P, {x0, layout.legend_y}, wood, ChartMarker::Circle, "wood");
  draw_chart_legend_entry(P, {x0 + entry_w, layout.legend_y}, tone, ChartMarker::Circle, "tone");
  draw_chart_legend_entry(P, {x0 + 2 * entry_w, layout.legend_y}, inside, ChartMarker::Circle,
                          "inside");
  draw_chart_legend_entry(P, {x0 + 3 * entry_w, layout.legend_y}, pop, ChartMarker::Circle,
                          "line pop (mean)");
  return img;
}

}  // namespace sylva

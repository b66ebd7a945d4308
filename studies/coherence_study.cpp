#include "studies/coherence_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "studies/study_chart.h"
#include "styles/reprojection.h"
#include "styles/turntable_frames.h"

namespace sylva {

void validate_coherence_study(const CoherenceStudyOptions& o) {
  if (o.frames < 2 || o.frames > 100000)
    throw InputError("--frames", "the coherence study needs [2, 100000] frames");
  if (!std::isfinite(o.step) || o.step == 0.0f || std::abs(o.step) > 360.0f)
    throw InputError("--step", "must be in [-360, 360] degrees and not 0");
  TurntablePath path;
  path.frames = o.frames;
  path.degrees = o.step * float(o.frames);
  path.axis = o.axis;
  path.zoom = o.zoom;
  validate_turntable(path);
}

namespace {

TurntablePath path_of(const CoherenceStudyOptions& o) {
  TurntablePath path;
  path.frames = o.frames;
  path.degrees = o.step * float(o.frames);  // frame i at i x step
  path.axis = o.axis;
  path.zoom = o.zoom;
  return path;
}

CoherenceStudyRow measure(const SheetScene& scene, const Style& style,
                          const CoherenceStudyOptions& o) {
  const TurntablePath path = path_of(o);
  TurntableRenderer renderer(scene, style, path, 1);
  renderer.render(0, false);  // warm-up, untimed: preprocessing, shaders, first allocations
  CoherenceStudyRow row;
  row.style = style.info().name;
  TurntableFrame previous;
  double seconds = 0, reprojection = 0, pop = 0, flicker = 0;
  int pops = 0;
  for (int i = 0; i < o.frames; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    TurntableFrame now = renderer.render(i, true);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (i > 0) {
      const FrameCoherence c = frame_coherence(previous.view, now.view);
      reprojection += c.reprojection_error;
      row.reprojection_max = std::max(row.reprojection_max, c.reprojection_error);
      if (c.line_pop) {
        pop += *c.line_pop;
        ++pops;
        row.line_pop_max = std::max(row.line_pop_max.value_or(0.0), *c.line_pop);
      }
      flicker += frame_flicker(previous.image, now.image, previous.mask, now.mask);
    }
    previous = std::move(now);
    if (o.on_frame) o.on_frame(row.style + " frame " + std::to_string(i));
  }
  const int pairs = o.frames - 1;
  row.seconds_per_frame = seconds / o.frames;
  row.reprojection_mean = reprojection / pairs;
  row.flicker_mean = flicker / pairs;
  if (pops > 0) row.line_pop_mean = pop / pops;
  return row;
}

}  // namespace

CoherenceStudy run_coherence_study(const SheetScene& scene_in,
                                   const std::vector<const Style*>& styles,
                                   const CoherenceStudyOptions& options) {
  validate_coherence_study(options);
  SYLVA_CHECK(!styles.empty(), "run_coherence_study: no styles");
  SheetScene scene = scene_in;
  memoize_preprocessing(scene, true);
  CoherenceStudy study;
  study.width = scene.raster.camera.width;
  study.height = scene.raster.camera.height;
  study.options = options;
  study.options.on_frame = nullptr;
  for (const Style* style : styles)
    study.rows.push_back(measure(scene, *style, options));
  return study;
}

std::string coherence_study_csv(const CoherenceStudy& study) {
  std::ostringstream s;
  s.precision(9);
  s << "style,frames,step_deg,width,height,seconds_per_frame,reprojection_error_mean,"
       "reprojection_error_max,line_pop_mean,line_pop_max,flicker_mean\n";
  auto opt = [&s](const std::optional<double>& v) {
    if (v) s << *v;
  };
  for (const CoherenceStudyRow& r : study.rows) {
    s << r.style << ',' << study.options.frames << ',' << study.options.step << ',' << study.width
      << ',' << study.height << ',' << r.seconds_per_frame << ',' << r.reprojection_mean << ','
      << r.reprojection_max << ',';
    opt(r.line_pop_mean);
    s << ',';
    opt(r.line_pop_max);
    s << ',' << r.flicker_mean << '\n';
  }
  return s.str();
}

cv::Mat plot_coherence_study(const CoherenceStudy& study, const std::string& scene_name, int width,
                             int height) {
  SYLVA_CHECK(width >= 600 && width <= 4000 && height >= 400 && height <= 4000,
              "plot size in [600, 4000] x [400, 4000]");
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const ChartPainter P{img, std::min(width / 1200.0, height / 800.0)};
  const cv::Scalar mean_colour(180, 110, 30), worst_colour(60, 60, 200);
  ChartPanel error, pop;
  error.title = "Reprojection error";
  pop.title = "Line pop";
  error.x_label = pop.x_label = "seconds per frame (log scale)";
  error.y_label = "8-bit levels, motion taken out";
  pop.y_label = "% of line pixels with no line near";
  pop.empty_note = "no style with lines";
  ChartSeries e_mean{mean_colour, ChartMarker::Circle, {}},
      e_worst{worst_colour, ChartMarker::Triangle, {}},
      p_mean{mean_colour, ChartMarker::Circle, {}},
      p_worst{worst_colour, ChartMarker::Triangle, {}};
  double lo = 1e30, hi = 0;
  for (const CoherenceStudyRow& r : study.rows) {
    const double x = std::max(r.seconds_per_frame, 1e-6);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    e_mean.points.push_back({x, r.reprojection_mean, r.style, false});
    e_worst.points.push_back({x, r.reprojection_max, "", false});
    if (r.line_pop_mean) p_mean.points.push_back({x, 100 * *r.line_pop_mean, r.style, false});
    if (r.line_pop_max) p_worst.points.push_back({x, 100 * *r.line_pop_max, "", false});
  }
  // One point per style: no lines between them (each series is sorted by time for the eye).
  for (ChartSeries* s : {&e_mean, &e_worst, &p_mean, &p_worst}) {
    std::sort(s->points.begin(), s->points.end(),
              [](const ChartPoint& a, const ChartPoint& b) { return a.x < b.x; });
    if (s->points.empty()) continue;
    (s == &e_mean || s == &e_worst ? error : pop).series.push_back(*s);
  }
  const auto [x_lo, x_hi] = chart_log_range(std::min(lo, hi), std::max(hi, lo * 1.01));
  P.text("Coherence with the motion taken out, against time  -  " + scene_name,
         {width / 2, P.px(34)}, 0.8, kChartBlack, 0.5, 2);
  char sub[320];
  std::snprintf(sub, sizeof sub, "%dx%d pixels, %d views %g degrees apart about %c", study.width,
                study.height, study.options.frames, double(study.options.step), study.options.axis);
  P.text(sub, {width / 2, P.px(62)}, 0.48, kChartTextGrey, 0.5);
  P.text("each pixel compared with where its surface point was in the previous view",
         {width / 2, P.px(84)}, 0.48, kChartTextGrey, 0.5);
  const ChartLayout layout = chart_two_panel_layout(P, 1);
  draw_chart_panel(P, layout.left, error, x_lo, x_hi, true);
  draw_chart_panel(P, layout.right, pop, x_lo, x_hi, false);
  const int entry_w = P.px(420);
  const int x0 = std::max(P.px(20), (width - 2 * entry_w) / 2);
  draw_chart_legend_entry(P, {x0, layout.legend_y}, mean_colour, ChartMarker::Circle,
                          "mean over view pairs");
  draw_chart_legend_entry(P, {x0 + entry_w, layout.legend_y}, worst_colour, ChartMarker::Triangle,
                          "worst view pair");
  return img;
}

}  // namespace sylva

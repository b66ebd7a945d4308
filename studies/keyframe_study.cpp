#include "studies/keyframe_study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>

#include "core/error.h"
#include "studies/study_chart.h"
#include "styles/turntable_frames.h"

namespace sylva {

void validate_keyframe_study(const KeyframeStudyOptions& options, const Style& style) {
  validate_turntable(options.path);
  if (options.every.empty()) throw InputError("--every", "name at least one interval");
  std::set<int> seen;
  for (int n : options.every) {
    if (n < 1 || n > 100000)
      throw InputError("--every", std::to_string(n) + " is outside [1, 100000]");
    if (!seen.insert(n).second) throw InputError("--every", std::to_string(n) + " is listed twice");
  }
  if (!style.traits().blob_outlines)
    throw InputError("--style", "the keyframes study needs a blobs style (style '" +
                                    style.info().name + "' draws every frame afresh)");
}

std::vector<int> keyframe_study_intervals(const KeyframeStudyOptions& options) {
  std::set<int> all(options.every.begin(), options.every.end());
  all.insert(1);
  return {all.begin(), all.end()};
}

size_t keyframe_study_frames(const KeyframeStudyOptions& options) {
  return keyframe_study_intervals(options).size() * static_cast<size_t>(options.path.frames);
}

KeyframeStudy run_keyframe_study(const SheetScene& scene_in, const Style& style,
                                 const KeyframeStudyOptions& options) {
  validate_keyframe_study(options, style);
  SheetScene scene = scene_in;
  memoize_preprocessing(scene, true);
  KeyframeStudy study;
  study.width = scene.raster.camera.width;
  study.height = scene.raster.camera.height;
  study.path = options.path;
  study.style = style.info().name;
  const int frames = options.path.frames;

  // Warm-up (untimed): the Luft preprocessing, shader compilation, first allocations.
  TurntableRenderer(scene, style, options.path, 1).render(0, false);

  std::vector<TurntableFrame> reference;
  for (int every : keyframe_study_intervals(options)) {
    KeyframeStudyRow row;
    row.every = every;
    row.reference = every == 1;
    TurntableRenderer renderer(scene, style, options.path, every);
    TurntableFrame previous;
    double flicker_sum = 0, jitter_sum = 0, error_sum = 0;
    for (int i = 0; i < frames; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      TurntableFrame now = renderer.render(i, true);
      row.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (i > 0) {
        const double flicker = frame_flicker(previous.image, now.image, previous.mask, now.mask);
        flicker_sum += flicker;
        row.flicker_max = std::max(row.flicker_max.value_or(0.0), flicker);
        if (previous.blobs && now.blobs) jitter_sum += blob_jitter(*previous.blobs, *now.blobs);
      }
      if (!row.reference) {
        const TurntableFrame& ref = reference[static_cast<size_t>(i)];
        const double error = frame_flicker(ref.image, now.image, ref.mask, now.mask);
        error_sum += error;
        row.error_max = std::max(row.error_max, error);
      }
      if (row.reference) {
        reference.push_back(now);
      }
      previous = std::move(now);
      if (options.on_frame)
        options.on_frame("n=" + std::to_string(every) + " frame " + std::to_string(i));
    }
    row.seconds_per_frame = row.seconds / frames;
    row.keyframes = renderer.keyframed() ? renderer.keyframes_computed() : frames;
    if (frames > 1) {
      row.flicker_mean = flicker_sum / (frames - 1);
      row.jitter_mean = jitter_sum / (frames - 1);
    }
    row.error_mean = error_sum / frames;
    study.rows.push_back(row);
  }
  return study;
}

std::string keyframe_study_csv(const KeyframeStudy& study) {
  std::ostringstream s;
  s.precision(9);
  s << "every,reference,frames,seconds,seconds_per_frame,keyframes,flicker_mean,flicker_max,"
       "jitter_mean,error_mean,error_max\n";
  auto opt = [&s](const std::optional<double>& v) {
    if (v) s << *v;
  };
  for (const KeyframeStudyRow& r : study.rows) {
    s << r.every << ',' << (r.reference ? 1 : 0) << ',' << study.path.frames << ',' << r.seconds
      << ',' << r.seconds_per_frame << ',' << r.keyframes << ',';
    opt(r.flicker_mean);
    s << ',';
    opt(r.flicker_max);
    s << ',';
    opt(r.jitter_mean);
    s << ',' << r.error_mean << ',' << r.error_max << '\n';
  }
  return s.str();
}

cv::Mat plot_keyframe_study(const KeyframeStudy& study, const std::string& scene_name, int width,
                            int height) {
  SYLVA_CHECK(width >= 600 && width <= 4000 && height >= 400 && height <= 4000,
              "plot size in [600, 4000] x [400, 4000]");
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const ChartPainter P{img, std::min(width / 1200.0, height / 800.0)};

  struct Look {
    const char* name;
    cv::Scalar colour;
    ChartMarker marker;
  };
  const Look looks[] = {
      {"flicker, mean over frame pairs", {180, 110, 30}, ChartMarker::Circle},
      {"flicker, worst frame pair", {60, 60, 200}, ChartMarker::Triangle},
      {"difference from n = 1, mean over frames", {60, 150, 60}, ChartMarker::Square},
      {"seconds per frame", {40, 40, 40}, ChartMarker::Diamond}};
  ChartPanel coherence, time;
  coherence.title = "Coherence";
  time.title = "Time";
  coherence.x_label = time.x_label = "keyframe every n frames (log scale)";
  coherence.y_label = "8-bit levels inside the plant";
  time.y_label = "seconds per frame";
  coherence.empty_note = time.empty_note = "no frames";
  ChartSeries mean{looks[0].colour, looks[0].marker, {}},
      worst{looks[1].colour, looks[1].marker, {}}, error{looks[2].colour, looks[2].marker, {}},
      seconds{looks[3].colour, looks[3].marker, {}};
  double n_hi = 1;
  for (const KeyframeStudyRow& r : study.rows) {
    const double x = r.every;
    n_hi = std::max(n_hi, x);
    const std::string label = "n=" + std::to_string(r.every);
    if (r.flicker_mean) mean.points.push_back({x, *r.flicker_mean, label, r.reference});
    if (r.flicker_max) worst.points.push_back({x, *r.flicker_max, "", r.reference});
    error.points.push_back({x, r.error_mean, "", r.reference});
    seconds.points.push_back({x, r.seconds_per_frame, label, r.reference});
  }
  for (ChartSeries* s : {&mean, &worst, &error})
    if (!s->points.empty()) coherence.series.push_back(*s);
  if (!seconds.points.empty()) time.series.push_back(seconds);
  const auto [x_lo, x_hi] = chart_log_range(1.0, n_hi);

  P.text("Keyframed blobs: flicker and time against the keyframe interval  -  " + scene_name,
         {width / 2, P.px(34)}, 0.8, kChartBlack, 0.5, 2);
  char sub[320];
  std::snprintf(sub, sizeof sub,
                "style %s, %dx%d pixels, %d frames over %g degrees about %c;  reference: n = 1 "
                "(fresh blobs every frame)",
                study.style.c_str(), study.width, study.height, study.path.frames,
                double(study.path.degrees), study.path.axis);
  P.text(sub, {width / 2, P.px(62)}, 0.48, kChartTextGrey, 0.5);
  P.text("flicker: mean |change| between consecutive frames;  time: render only, no file written",
         {width / 2, P.px(84)}, 0.48, kChartTextGrey, 0.5);

  const ChartLayout layout = chart_two_panel_layout(P, 2);
  draw_chart_panel(P, layout.left, coherence, x_lo, x_hi, true);
  draw_chart_panel(P, layout.right, time, x_lo, x_hi, false);

  // Legend: two entries per row.
  const int entry_w = P.px(420);
  const int x0 = std::max(P.px(20), (width - 2 * entry_w) / 2);
  const int y = layout.legend_y;
  for (size_t i = 0; i < std::size(looks); ++i)
    draw_chart_legend_entry(P, {x0 + int(i % 2) * entry_w, y + int(i / 2) * P.px(26)},
                            looks[i].colour, looks[i].marker, looks[i].name);
  draw_chart_reference_note(P, {x0, y + 2 * P.px(26) + P.px(4)},
                            "the reference, n = 1 (zero difference by definition)");
  return img;
}

}  // namespace sylva

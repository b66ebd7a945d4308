#include "studies/foliage_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <set>

#include "core/csv.h"
#include "core/error.h"
#include "npr/generators.h"
#include "studies/study_chart.h"

namespace sylva {

namespace {

using Clock = std::chrono::steady_clock;

// What the comparison needs from the reference, computed once.
struct Reference {
  const FoliageIllumination& result;
  std::vector<std::vector<char>> foliage;  // per mesh, per vertex: used by a foliage triangle
  std::vector<double> interior_ka;         // per triangle of every mesh: interpolated ka
};

Reference make_reference(const Scene& scene, const FoliageIllumination& r) {
  Reference ref{r, {}, {}};
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    std::vector<char>& f = ref.foliage.emplace_back(m.positions.size(), 0);
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      double sum = 0;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = m.indices[3 * t + k];
        sum += r.ka[mi][v];
        if (m.roles[t] == Role::Foliage) f[v] = 1;
      }
      ref.interior_ka.push_back(sum / 3.0);
    }
  }
  return ref;
}

// Angle between two directions in degrees; atan2 keeps identical vectors at exactly 0 and is
// accurate for small angles, where acos of the dot product is not.
double angle_deg(const glm::vec3& a, const glm::vec3& b) {
  const glm::dvec3 da(a), db(b);
  return std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db)) * (180.0 / std::numbers::pi);
}

// The nearest-rank q-quantile of v (not empty); reorders v.
double quantile(std::vector<double>& v, double q) {
  const size_t rank = size_t(std::ceil(q * double(v.size())));
  const size_t k = std::min(v.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

// Fills the error columns of `row` for `run` against the reference.
void compare(const Scene& scene, const Reference& ref, const FoliageIllumination& run,
             KaEncoding encoding, FoliageStudyRow& row) {
  std::vector<double> angles;
  double ka_sq = 0;
  size_t vertices = 0;
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi)
    for (size_t v = 0; v < scene.meshes[mi].positions.size(); ++v) {
      if (ref.foliage[mi][v])
        angles.push_back(angle_deg(run.normals[mi][v], ref.result.normals[mi][v]));
      const double d = double(run.ka[mi][v]) - double(ref.result.ka[mi][v]);
      ka_sq += d * d;
      ++vertices;
    }
  double sum = 0;
  for (double a : angles)
    sum += a;
  row.normal_mean_deg = angles.empty() ? 0.0 : sum / double(angles.size());
  row.normal_p95_deg = angles.empty() ? 0.0 : quantile(angles, 0.95);
  row.ka_rmse = vertices == 0 ? 0.0 : std::sqrt(ka_sq / double(vertices));

  // The renderer's view of ka inside each triangle, at its centroid (Luft §3.2: with the
  // length encoding the interpolated normal's length is what gets decoded).
  double interior_sq = 0;
  size_t t_all = 0;
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    for (size_t t = 0; t < m.triangle_count(); ++t, ++t_all) {
      double seen = 0;
      if (encoding == KaEncoding::Attribute) {
        for (int k = 0; k < 3; ++k)
          seen += run.ka[mi][m.indices[3 * t + k]];
        seen /= 3.0;
      } else {
        glm::dvec3 n(0.0);
        for (int k = 0; k < 3; ++k) {
          const uint32_t v = m.indices[3 * t + k];
          n += glm::dvec3(encode_ka(run.normals[mi][v], run.ka[mi][v]));
        }
        seen = std::clamp(glm::length(n / 3.0), 0.0, 1.0);
      }
      const double d = seen - ref.interior_ka[t_all];
      interior_sq += d * d;
    }
  }
  row.ka_interior_rmse = t_all == 0 ? 0.0 : std::sqrt(interior_sq / double(t_all));
}

std::string describe_run(double fraction, int grid, NormalSource n) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "fraction %g, grid %d, %s", fraction, grid, normal_source_name(n));
  return buf;
}

}  // namespace

const char* normal_source_name(NormalSource s) {
  return s == NormalSource::Surface ? "surface" : "gradient";
}

const char* ka_encoding_name(KaEncoding e) {
  return e == KaEncoding::Length ? "length" : "attribute";
}

void validate_foliage_study(const FoliageStudyOptions& o) {
  if (o.fractions.empty()) throw InputError("fractions", "name at least one fraction in (0, 1]");
  for (double f : o.fractions)
    if (!(f > 0.0 && f <= 1.0))
      throw InputError("fractions", "each must be in (0, 1], got " + format_number("%g", f));
  if (o.grids.empty()) throw InputError("grids", "name at least one grid in [2, 1024] cells");
  for (int g : o.grids)
    if (g < 2 || g > 1024)
      throw InputError("grids", "each must be in [2, 1024] cells, got " + std::to_string(g));
  if (o.normals.empty())
    throw InputError("normal-sources", "name at least one of surface, gradient");
  if (o.encodings.empty()) throw InputError("encodings", "name at least one of length, attribute");
  if (o.reference_grid < 2 || o.reference_grid > 1024)
    throw InputError("reference-grid",
                     "must be in [2, 1024] cells, got " + std::to_string(o.reference_grid));
  FoliageParams p = o.base;
  p.fraction.reset();
  p.grid = o.reference_grid;
  validate_foliage_params(p);
}

size_t foliage_study_runs(const FoliageStudyOptions& o) {
  return 1 + o.fractions.size() * o.grids.size() * o.normals.size();
}

FoliageStudy run_foliage_study(const Scene& scene, const FoliageStudyOptions& o) {
  validate_foliage_study(o);
  FoliageStudy study;
  study.reference_grid =
      std::max(o.reference_grid, *std::max_element(o.grids.begin(), o.grids.end()));
  study.scaled_thresholds = o.scale_thresholds;

  // Reference: all generators, the finest grid, nearest-surface normals (Luft §3.1, §3.3).
  FoliageParams rp = o.base;
  rp.fraction = 1.0;
  rp.grid = study.reference_grid;
  rp.normals = NormalSource::Surface;
  auto t0 = Clock::now();
  const FoliageIllumination reference = compute_foliage_illumination(scene, rp);
  study.reference_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  study.reference = reference.stats;
  if (o.on_run) o.on_run("reference: " + describe_run(1.0, rp.grid, rp.normals));
  const Reference ref = make_reference(scene, reference);

  // Every run uses the reference's resolved rho, tau and d_min.
  FoliageParams base = o.base;
  base.rho = SceneLength{SceneLength::Kind::Absolute, study.reference.rho};
  base.tau = float(study.reference.tau);
  base.ambient.d_min = float(study.reference.d_min);
  base.d_min_auto = false;

  for (double fraction : o.fractions)
    for (int grid : o.grids)
      for (NormalSource normals : o.normals) {
        FoliageStudyRow row;
        row.fraction = fraction;
        row.grid = grid;
        row.normals = normals;
        row.reference =
            fraction == 1.0 && grid == study.reference_grid && normals == NormalSource::Surface;
        FoliageParams p = base;
        if (o.scale_thresholds) {
          // The share actually kept (make_generators rounds and keeps at least one), not
          // the nominal fraction; counting them costs a pass over the foliage, untimed.
          GeneratorOptions go{fraction, p.per_triangle, p.seed};
          const double share = double(make_generators(scene, go).size()) /
                               double(std::max<size_t>(study.reference.generators, 1));
          p.tau = float(study.reference.tau * share);
          p.ambient.d_min = std::max(float(study.reference.d_min * share), 1e-30f);
        }
        row.tau = *p.tau;
        row.d_min = p.ambient.d_min;
        p.fraction = fraction;
        p.grid = grid;
        p.normals = normals;
        std::optional<FoliageIllumination> run;
        try {
          t0 = Clock::now();
          run = compute_foliage_illumination(scene, p);
          row.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
          row.generators = run->stats.generators;
        } catch (const InputError& e) {
          row.error = e.what();
          std::replace(row.error.begin(), row.error.end(), '\n', ' ');
        }
        for (KaEncoding encoding : o.encodings) {
          row.encoding = encoding;
          if (run) compare(scene, ref, *run, encoding, row);
          study.rows.push_back(row);
        }
        if (o.on_run) o.on_run(describe_run(fraction, grid, normals));
      }
  return study;
}

std::string foliage_study_csv(const FoliageStudy& study) {
  std::string csv =
      "fraction,grid,normals,encoding,reference,generators,tau,d_min,seconds,normal_mean_deg,"
      "normal_p95_deg,ka_rmse,ka_interior_rmse,error\n";
  auto num = [](const std::optional<double>& v, const char* fmt) {
    return v && std::isfinite(*v) ? format_number(fmt, *v) : std::string();
  };
  for (const FoliageStudyRow& r : study.rows) {
    const std::string error = csv_quoted(r.error);
    csv += format_number("%g", r.fraction) + "," + std::to_string(r.grid) + "," +
           normal_source_name(r.normals) + "," + ka_encoding_name(r.encoding) + "," +
           (r.reference ? "1" : "0") + "," +
           (r.generators ? std::to_string(*r.generators) : std::string()) + "," +
           format_number("%.6g", r.tau) + "," + format_number("%.6g", r.d_min) + "," +
           num(r.seconds, "%.4f") + "," + num(r.normal_mean_deg, "%.6g") + "," +
           num(r.normal_p95_deg, "%.6g") + "," + num(r.ka_rmse, "%.6g") + "," +
           num(r.ka_interior_rmse, "%.6g") + "," + error + "\n";
  }
  return csv;
}

// ---------------------------------------------------------------------------------------
// The chart (studies/study_chart.h).

namespace {

// Per normal source a light and a dark end (BGR); grids get shades from light (coarse) to
// dark (fine). Blues and oranges stay apart for colour-blind readers.
cv::Scalar shade(NormalSource s, double t) {
  const cv::Scalar light =
      s == NormalSource::Surface ? cv::Scalar(225, 170, 90) : cv::Scalar(80, 165, 250);
  const cv::Scalar dark =
      s == NormalSource::Surface ? cv::Scalar(120, 45, 8) : cv::Scalar(5, 60, 170);
  return light * (1.0 - t) + dark * t;
}

ChartMarker marker_of(NormalSource s) {
  return s == NormalSource::Surface ? ChartMarker::Circle : ChartMarker::Triangle;
}

}  // namespace

cv::Mat plot_foliage_study(const FoliageStudy& study, const std::string& scene_name, int width,
                           int height) {
  SYLVA_CHECK(width >= 600 && width <= 4000 && height >= 400 && height <= 4000,
              "plot size in [600, 4000] x [400, 4000]");
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const ChartPainter P{img, std::min(width / 1200.0, height / 800.0)};

  // One point per preprocessing run: the first encoding's row (time, normal and vertex ka
  // errors do not depend on the encoding).
  std::set<int> grids;
  std::vector<NormalSource> sources;
  size_t failed = 0;
  for (const FoliageStudyRow& r : study.rows) {
    grids.insert(r.grid);
    if (std::find(sources.begin(), sources.end(), r.normals) == sources.end())
      sources.push_back(r.normals);
  }
  ChartPanel normal_panel, ka_panel;
  normal_panel.title = "Foliage normals";
  normal_panel.y_label = "mean angle to the reference normal, degrees";
  ka_panel.title = "Ambient coefficient ka (per vertex)";
  ka_panel.y_label = "RMSE of ka against the reference";
  normal_panel.x_label = ka_panel.x_label = "preprocessing time, seconds (log scale)";
  double t_lo = 1e30, t_hi = 0;
  for (NormalSource src : sources) {
    size_t gi = 0;
    for (int grid : grids) {
      const double t = grids.size() > 1 ? double(gi++) / double(grids.size() - 1) : 1.0;
      ChartSeries sn{shade(src, t), marker_of(src), {}};
      ChartSeries sk = sn;
      std::set<double> seen;
      for (const FoliageStudyRow& r : study.rows) {
        if (r.normals != src || r.grid != grid || !seen.insert(r.fraction).second) continue;
        if (!r.seconds || !r.normal_mean_deg || !r.ka_rmse) {
          ++failed;
          continue;
        }
        const double sec = std::max(*r.seconds, 1e-4);
        t_lo = std::min(t_lo, sec);
        t_hi = std::max(t_hi, sec);
        const std::string label = chart_tick_label(r.fraction);
        sn.points.push_back({sec, *r.normal_mean_deg, label, r.reference});
        sk.points.push_back({sec, *r.ka_rmse, label, r.reference});
      }
      if (!sn.points.empty()) {
        normal_panel.series.push_back(sn);
        ka_panel.series.push_back(sk);
      }
    }
  }
  if (std::none_of(study.rows.begin(), study.rows.end(),
                   [](const FoliageStudyRow& r) { return r.reference && r.seconds; })) {
    // The reference's parameters are not in the sweep: show its time.
    const double lone = std::max(study.reference_seconds, 1e-4);
    normal_panel.lone_x = ka_panel.lone_x = lone;
    t_lo = std::min(t_lo, lone);
    t_hi = std::max(t_hi, lone);
  }
  const auto [x_lo, x_hi] = chart_log_range(t_lo, t_hi);

  // Title and the reference's parameters.
  P.text("Foliage preprocessing: error against time  -  " + scene_name, {width / 2, P.px(34)}, 0.8,
         kChartBlack, 0.5, 2);
  char sub[320];
  std::snprintf(sub, sizeof sub,
                "reference: all %zu generators, grid %d, surface normals: %.2f s;  rho %.4g, "
                "tau %.4g, d_min %.4g",
                study.reference.generators, study.reference_grid, study.reference_seconds,
                study.reference.rho, study.reference.tau, study.reference.d_min);
  P.text(sub, {width / 2, P.px(62)}, 0.48, kChartTextGrey, 0.5);
  std::string sub2 = study.scaled_thresholds
                         ? "every run: the reference's rho; its tau and d_min times the run's "
                           "share of generators"
                         : "every run: the reference's rho, tau and d_min";
  if (failed) sub2 += ";  failed runs are left out (see the CSV)";
  P.text(sub2, {width / 2, P.px(84)}, 0.48, kChartTextGrey, 0.5);

  // Two panels side by side; the legend below them.
  const ChartLayout layout = chart_two_panel_layout(P, int(sources.size()));
  draw_chart_panel(P, layout.left, normal_panel, x_lo, x_hi, true);
  draw_chart_panel(P, layout.right, ka_panel, x_lo, x_hi, false);

  // Legend: one row per normal source, one entry per grid.
  int y = layout.legend_y;
  const int entry_w = P.px(190);
  const int x0 = std::max(P.px(20), (width - int(grids.size() + 1) * entry_w) / 2);
  for (NormalSource src : sources) {
    P.text(std::string(normal_source_name(src)) + " normals:", {x0 + entry_w - P.px(12), y}, 0.5,
           kChartBlack, 1.0);
    size_t gi = 0;
    for (int grid : grids) {
      const double t = grids.size() > 1 ? double(gi) / double(grids.size() - 1) : 1.0;
      const int x = x0 + int(gi + 1) * entry_w;
      draw_chart_legend_entry(P, {x, y}, shade(src, t), marker_of(src),
                              "grid " + std::to_string(grid));
      ++gi;
    }
    y += P.px(26);
  }
  draw_chart_reference_note(P, {x0, y + P.px(4)},
                            "the reference (zero error by definition);  small numbers: the share "
                            "of leaves used as generators (fraction)");
  return img;
}

}  // namespace sylva

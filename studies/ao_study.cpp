#include "studies/ao_study.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "core/csv.h"
#include "core/error.h"
#include "core/gl/gl_context.h"
#include "core/gl/raster_pass.h"
#include "core/graph/render_graph.h"
#include "npr/ao_pass.h"
#include "studies/study_chart.h"

namespace sylva {

namespace {

using Clock = std::chrono::steady_clock;

// The models as ao.model names them.
const std::vector<std::string> kModels = [] {
  std::vector<std::string> names;
  for (const auto& [name, model] : ao_model_choices())
    names.push_back(name);
  return names;
}();

std::string joined_models() {
  std::string s;
  for (const std::string& m : kModels)
    s += (s.empty() ? "" : ", ") + m;
  return s;
}

bool wants(const AoStudyOptions& o, const std::string& model) {
  return std::find(o.models.begin(), o.models.end(), model) != o.models.end();
}

// The ray counts of raytraced rows: the listed ones except the reference's (its own row).
std::vector<int> row_rays(const AoStudyOptions& o) {
  std::vector<int> out;
  for (int r : o.rays)
    if (r != o.reference_rays) out.push_back(r);
  return out;
}

// The pixels the comparison covers and their class.
struct Pixels {
  std::vector<int> index;     // row-major pixel index
  std::vector<char> foliage;  // per entry of index: a foliage triangle's pixel
};

// Pixels covered by the scene (primitive id != 0) with a normal (those the ray-traced pass
// traces), classed by the role of their primitive.
Pixels classify_pixels(const Scene& scene, Rasterizer& rasterizer, const AoStudyOptions& o) {
  std::vector<char> foliage_id;  // per primitive id: one of its triangles is foliage
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count() && t < m.primitive_ids.size(); ++t) {
      const uint32_t id = m.primitive_ids[t];
      if (id >= foliage_id.size()) foliage_id.resize(size_t(id) + 1, 0);
      if (t < m.roles.size() && m.roles[t] == Role::Foliage) foliage_id[id] = 1;
    }
  RasterRequest request = o.request;
  request.targets = Target::Id | Target::Normal;
  request.id_kind = IdKind::Primitive;
  request.ao = AoShading{};
  const GBuffer gb = rasterizer.render(o.camera, o.lighting, request);
  Pixels px;
  for (int y = 0; y < gb.id.rows; ++y)
    for (int x = 0; x < gb.id.cols; ++x) {
      const int id = gb.id.at<int32_t>(y, x);
      if (id <= 0 || gb.normal.at<cv::Vec3f>(y, x) == cv::Vec3f(0, 0, 0)) continue;
      px.index.push_back(y * gb.id.cols + x);
      px.foliage.push_back(size_t(id) < foliage_id.size() && foliage_id[size_t(id)]);
    }
  return px;
}

// `v` averaged over the class's pixels (mask 1) near each pixel: a Gaussian of `sigma` pixels,
// normalised by the mask's own blur so other classes and the background do not leak in.
cv::Mat class_blur(const cv::Mat& v, const cv::Mat& mask, const cv::Mat& mask_blur, double sigma) {
  cv::Mat vm, out;
  cv::multiply(v, mask, vm);
  cv::GaussianBlur(vm, vm, cv::Size(), sigma, sigma, cv::BORDER_CONSTANT);
  cv::divide(vm, mask_blur, out);
  return out;
}

// One class of pixels (foliage or not) and what every row's comparison shares: its mask, the
// mask's blur (floored above 0) and the reference's trend, made once per study.
struct PixelClass {
  const Pixels* px = nullptr;
  bool foliage = false;
  double sigma = 0;  // kAoTrendSigma x the frame's shorter side, pixels
  cv::Mat mask, mask_blur, ref_trend;

  PixelClass(const Pixels& pixels, bool foliage_class, const cv::Mat& ref)
      : px(&pixels), foliage(foliage_class), sigma(kAoTrendSigma * std::min(ref.cols, ref.rows)) {
    mask = cv::Mat::zeros(ref.size(), CV_32FC1);
    auto* m = mask.ptr<float>(0);
    for (size_t i = 0; i < px->index.size(); ++i)
      if (bool(px->foliage[i]) == foliage) m[px->index[i]] = 1.0f;
    cv::GaussianBlur(mask, mask_blur, cv::Size(), sigma, sigma, cv::BORDER_CONSTANT);
    mask_blur = cv::max(mask_blur, 1e-6f);
    ref_trend = class_blur(ref, mask, mask_blur, sigma);
  }
};

// The model's AO buffer against the reference over one class of pixels.
AoPixelError compare(const cv::Mat& ao, const cv::Mat& ref, const PixelClass& c) {
  SYLVA_CHECK(ao.type() == CV_32FC1 && ref.type() == CV_32FC1 && ao.size() == ref.size() &&
                  ao.size() == c.mask.size() && ao.isContinuous() && ref.isContinuous(),
              "AO study: AO buffers are continuous float images of one size");
  const Pixels& px = *c.px;
  AoPixelError e;
  double sum = 0, sq = 0, abs = 0;
  const auto* a = ao.ptr<float>(0);
  const auto* r = ref.ptr<float>(0);
  for (size_t i = 0; i < px.index.size(); ++i) {
    if (bool(px.foliage[i]) != c.foliage) continue;
    const double v = a[px.index[i]], d = v - double(r[px.index[i]]);
    sum += v;
    sq += d * d;
    abs += std::abs(d);
    ++e.pixels;
  }
  if (e.pixels == 0) return e;
  const double n = double(e.pixels);
  e.mean = sum / n;
  e.rmse = std::sqrt(sq / n);
  e.mae = abs / n;
  const cv::Mat ta = class_blur(ao, c.mask, c.mask_blur, c.sigma);
  const auto* pa = ta.ptr<float>(0);
  const auto* pr = c.ref_trend.ptr<float>(0);
  double tsq = 0;
  for (size_t i = 0; i < px.index.size(); ++i) {
    if (bool(px.foliage[i]) != c.foliage) continue;
    const double d = double(pa[px.index[i]]) - double(pr[px.index[i]]);
    tsq += d * d;
  }
  e.trend_rmse = std::sqrt(tsq / n);
  return e;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One frame as a render graph: the raster pass with `ao` (and, for rays > 0, the ray-traced
// AO pass over its position and normal targets), presenting the colour and, when `want_ao`,
// the AO buffer. Only execute() is timed. Returns the AO buffer (empty without want_ao).
cv::Mat run_frame(const Scene& scene, Rasterizer& rasterizer, const AoStudyOptions& o,
                  const AoShading& ao, int rays, bool want_ao, double* seconds) {
  RenderGraph graph;
  RasterSetup setup;
  setup.rasterizer = &rasterizer;
  setup.camera = o.camera;
  setup.lighting = o.lighting;
  setup.request = o.request;
  setup.request.ao = ao;
  const GBufferHandles gb = add_raster_pass(graph, setup);
  const ImageHandle ao_buffer = rays > 0
                                    ? add_raytraced_ao_pass(graph, &scene, gb.position, gb.normal,
                                                            o.camera.view, rays, o.seed)
                                    : gb.ao;
  graph.present(gb.color);
  if (want_ao) graph.present(ao_buffer);
  graph.compile();
  const auto t0 = Clock::now();
  graph.execute();
  if (seconds) *seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return want_ao ? graph.get<cv::Mat>(ao_buffer).clone() : cv::Mat();
}

// The compared AO buffer (an untimed frame, which also warms the shader variant up) and the
// median time of `repeats` frames; none's timed frames present the colour only.
cv::Mat measure(const Scene& scene, Rasterizer& rasterizer, const AoStudyOptions& o,
                const AoShading& ao, int rays, bool none, double& frame_seconds) {
  cv::Mat out = run_frame(scene, rasterizer, o, ao, rays, true, nullptr);
  if (none) run_frame(scene, rasterizer, o, ao, rays, false, nullptr);
  std::vector<double> times;
  for (int i = 0; i < o.repeats; ++i) {
    double t = 0;
    run_frame(scene, rasterizer, o, ao, rays, !none, &t);
    times.push_back(t);
  }
  frame_seconds = median(times);
  return out;
}

std::string describe(const AoStudyRow& r) {
  std::string s = r.reference ? "reference: " + r.model : r.model;
  if (r.shells) s += " k=" + std::to_string(*r.shells);
  if (r.rays) s += " " + std::to_string(*r.rays) + " rays";
  return s;
}

bool parse_alpha_rho(const std::string& text, double& v) {
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, v);
  return !text.empty() && ec == std::errc() && p == end && std::isfinite(v) && v >= 0.0 &&
         v <= 3.4e38;
}

}  // namespace

void validate_ao_study(const AoStudyOptions& o) {
  if (o.models.empty()) throw InputError("models", "name at least one of " + joined_models());
  for (size_t i = 0; i < o.models.size(); ++i) {
    if (std::find(kModels.begin(), kModels.end(), o.models[i]) == kModels.end())
      throw InputError("models",
                       "unknown model '" + o.models[i] + "' (allowed: " + joined_models() + ")");
    if (std::find(o.models.begin(), o.models.begin() + long(i), o.models[i]) !=
        o.models.begin() + long(i))
      throw InputError("models", "'" + o.models[i] + "' is listed twice");
  }
  if (o.shells.empty()) throw InputError("shells", "name at least one k in [1, 64]");
  for (int k : o.shells)
    if (k < 1 || k > kMaxAoShells)
      throw InputError("shells", "each must be in [1, 64], got " + std::to_string(k));
  if (o.rays.empty()) throw InputError("rays", "name at least one ray count in [1, 4096]");
  for (int r : o.rays)
    if (r < 1 || r > 4096)
      throw InputError("rays", "each must be in [1, 4096], got " + std::to_string(r));
  if (o.reference_rays < 1 || o.reference_rays > 4096)
    throw InputError("reference-rays",
                     "must be in [1, 4096], got " + std::to_string(o.reference_rays));
  if (o.repeats < 1 || o.repeats > 100)
    throw InputError("repeats", "must be in [1, 100], got " + std::to_string(o.repeats));
  double v = 0;
  if (o.alpha_rho != "auto" && !parse_alpha_rho(o.alpha_rho, v))
    throw InputError("ao.alpha_rho", "must be 'auto' or a number >= 0, got '" + o.alpha_rho + "'");
  if (wants(o, "luft-density")) validate_foliage_params(o.luft);
}

size_t ao_study_runs(const AoStudyOptions& o) {
  size_t n = 2;  // the reference and none
  for (const std::string& m : o.models) {
    if (m == "none") continue;
    if (m == "hegeman-shells")
      n += o.shells.size();
    else if (m == "raytraced")
      n += row_rays(o).size();
    else
      ++n;
  }
  return n;
}

namespace {

// One run of the study: the GL context and rasteriser with the scene uploaded, the covered
// pixels, the reference and the time baseline, and the measured rows per model.
class AoStudyRun {
 public:
  AoStudyRun(const Scene& scene, const AoStudyOptions& o)
      : m_scene(scene),
        m_o(o),
        m_own_context(o.context ? nullptr : create_gl_context()),
        m_rasterizer(o.context ? *o.context : *m_own_context) {
    m_rasterizer.upload(scene);
    m_px = classify_pixels(scene, m_rasterizer, o);
    if (m_px.index.empty())
      throw InputError("view", "the scene covers no pixel of the " +
                                   std::to_string(o.camera.width) + "x" +
                                   std::to_string(o.camera.height) + " frame");
  }

  // The reference: ray-traced with the most rays, the same frame as the raytraced rows; its
  // mean AO over the covered pixels goes to `mean`.
  AoStudyRow reference(double& mean) {
    AoStudyRow row;
    row.model = "raytraced";
    row.rays = m_o.reference_rays;
    row.reference = true;
    row.setup_seconds = 0.0;
    double t = 0;
    m_ref = measure(m_scene, m_rasterizer, m_o, AoShading{}, m_o.reference_rays, false, t);
    row.frame_seconds = t;
    double total = 0;
    for (int i : m_px.index)
      total += m_ref.ptr<float>(0)[i];
    mean = total / double(m_px.index.size());
    m_foliage.emplace(m_px, true, m_ref);
    m_other.emplace(m_px, false, m_ref);
    finish(row, m_ref);
    return row;
  }

  // none: the time baseline (after reference()).
  AoStudyRow none() {
    AoStudyRow row;
    row.model = "none";
    row.setup_seconds = 0.0;
    double t = 0;
    const cv::Mat ao = measure(m_scene, m_rasterizer, m_o, AoShading{}, 0, true, t);
    row.frame_seconds = t;
    m_baseline = t;
    row.added_seconds = 0.0;
    finish(row, ao);
    return row;
  }
  double baseline() const { return m_baseline; }

  // A model's row: `setup` (timed) makes its shading, then its frames are measured; an
  // InputError fails the row, not the study.
  void run_row(AoStudyRow row, const std::function<AoShading()>& setup, int rays) {
    try {
      const auto t0 = Clock::now();
      const AoShading shading = setup ? setup() : AoShading{};
      row.setup_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      if (shading.model == AoShading::Model::Shells) row.alpha_rho = shading.alpha_rho;
      double frame = 0;
      const cv::Mat ao = measure(m_scene, m_rasterizer, m_o, shading, rays, false, frame);
      row.frame_seconds = frame;
      row.added_seconds = frame - m_baseline;
      finish(row, ao);
    } catch (const InputError& e) {
      row.setup_seconds.reset();
      row.error = e.what();
      std::replace(row.error.begin(), row.error.end(), '\n', ' ');
      if (m_o.on_run) m_o.on_run(describe(row) + " (failed)");
    }
    m_rows[row.model].push_back(row);
  }

  // Hegeman et al.'s shading of `model` with k shells.
  std::function<AoShading()> hegeman(const std::string& model, int k) const {
    return [&scene = m_scene, &o = m_o, model, k] {
      AoSettings s;
      s.model = parse_ao_model(model, "models");
      s.shells = k;
      s.alpha_rho = o.alpha_rho;
      return scene_ao_shading(scene, s, o.seed);
    };
  }

  // The Luft preprocessing's ka as the AO (the realigned normals do not change the AO buffer).
  // It replaces the uploaded normals and ka for good, so it runs last.
  std::function<AoShading()> luft() {
    return [this] {
      const FoliageIllumination luft = compute_foliage_illumination(m_scene, m_o.luft);
      m_rasterizer.set_vertex_shading(vertex_shading(luft, KaEncoding::Attribute));
      AoShading s;
      s.model = AoShading::Model::Ka;
      return s;
    };
  }

  // The measured rows in kModels' order.
  std::vector<AoStudyRow> rows() {
    std::vector<AoStudyRow> out;
    for (const std::string& m : kModels)
      for (AoStudyRow& r : m_rows[m])
        out.push_back(std::move(r));
    return out;
  }

 private:
  void finish(AoStudyRow& row, const cv::Mat& ao) const {
    row.foliage = compare(ao, m_ref, *m_foliage);
    row.nonfoliage = compare(ao, m_ref, *m_other);
    if (m_o.on_run) m_o.on_run(describe(row));
  }

  const Scene& m_scene;
  const AoStudyOptions& m_o;
  std::unique_ptr<GlContext> m_own_context;  // when the options bring none
  Rasterizer m_rasterizer;
  Pixels m_px;
  cv::Mat m_ref;
  std::optional<PixelClass> m_foliage, m_other;  // made once the reference is traced
  double m_baseline = 0;
  std::map<std::string, std::vector<AoStudyRow>> m_rows;  // per model, in measuring order
};

AoStudyRow row_of(const std::string& model) {
  AoStudyRow row;
  row.model = model;
  return row;
}

}  // namespace

AoStudy run_ao_study(const Scene& scene, const AoStudyOptions& o) {
  validate_ao_study(o);
  AoStudy study;
  study.width = o.camera.width;
  study.height = o.camera.height;
  study.repeats = o.repeats;
  study.reference_rays = o.reference_rays;
  AoStudyRun run(scene, o);
  AoStudyRow ref_row = run.reference(study.reference_mean);
  const AoStudyRow none = run.none();
  ref_row.added_seconds = *ref_row.frame_seconds - run.baseline();

  if (wants(o, "constant")) {
    AoStudyRow row = row_of("constant");
    row.constant = study.reference_mean;
    AoShading constant;
    constant.model = AoShading::Model::Constant;
    constant.constant = float(std::clamp(study.reference_mean, 0.0, 1.0));
    run.run_row(
        row, [constant] { return constant; }, 0);
  }
  for (const char* model : {"hegeman-sphere", "hegeman-ellipsoid"})
    if (wants(o, model)) run.run_row(row_of(model), run.hegeman(model, 1), 0);
  if (wants(o, "hegeman-shells"))
    for (int k : o.shells) {
      AoStudyRow row = row_of("hegeman-shells");
      row.shells = k;
      run.run_row(row, run.hegeman("hegeman-shells", k), 0);
    }
  if (wants(o, "raytraced"))
    for (int rays : row_rays(o)) {
      AoStudyRow row = row_of("raytraced");
      row.rays = rays;
      run.run_row(row, {}, rays);
    }
  if (wants(o, "luft-density")) run.run_row(row_of("luft-density"), run.luft(), 0);

  study.rows.push_back(none);
  for (AoStudyRow& r : run.rows())
    study.rows.push_back(std::move(r));
  study.rows.push_back(ref_row);
  return study;
}

}  // namespace sylva

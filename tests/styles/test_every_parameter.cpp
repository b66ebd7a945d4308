// Every parameter of every built-in style, one test each (TEST_P over the specs): the ends of
// its range (each choice, both booleans, black and white, the text forms' extremes) render
// through the library with finite output, and just outside its range `sylva render` exits 2
// with one line naming the key and writes nothing.
//
// "Finite output" is checked on every pass of the style, not only its picture: the graph's
// observer sees each resource as it is written, so every float image, every shadow map and
// every stroke drawing must be finite, the edge passes' lines must lie in [0, 1], the final
// image must be CV_8UC4 of the frame's size (opaque for watercolor), and a second render must
// give the same bytes. Toon keys are also shaded straight from the frame's G-buffers with the
// key light and with all lights (toon_shade_linear, its linear output), edge keys detect edges
// on them (detect_edges), and ink keys composite the frame's raster ink over a flat coverage
// of 0.5 as well (composite_ink), as the pass tests did.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "core/error.h"
#include "npr/leaf_clusters.h"
#include "styles/presets.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "tests/cli/cli_support.h"
#include "tests/styles/style_rig.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

struct Case {
  std::string style, key;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.style << " " << c.key;
}

// The parameter sections each builder reads; keys of other sections cannot change its picture.
const std::map<std::string, std::vector<std::string>>& sections_read() {
  static const std::map<std::string, std::vector<std::string>> s = {
      {"shaded", {"style", "foliage", "ao"}},
      {"ink", {"style", "foliage", "ao", "edges", "ink", "lines", "leaves", "pen"}},
      {"toon", {"style", "foliage", "ao", "toon"}},
      {"watercolor", {"style", "foliage", "ao", "watercolor"}},
      {"blobs", {"style", "foliage", "ao", "edges", "blobs"}},
  };
  return s;
}

// A grey paper image for watercolor.paper (written once).
const std::string& paper_image() {
  static const std::string path = [] {
    const std::string p = temp_dir("paper") + "/paper.png";
    cv::Mat grain(64, 64, CV_8UC1);
    cv::randu(grain, 0, 256);
    cv::imwrite(p, grain);
    return p;
  }();
  return path;
}

// Text keys: the extremes of their forms, and a value just outside them.
struct TextForms {
  std::vector<std::string> ends;
  std::string outside;
};
const std::map<std::string, TextForms>& text_forms() {
  static const std::map<std::string, TextForms> t = {
      {"foliage.rho", {{"auto", "2%", "500%", "0.05"}, "0"}},
      {"foliage.tau", {{"auto", "0"}, "-1"}},
      {"foliage.fraction", {{"auto", "0.001", "1"}, "1.01"}},
      {"foliage.d_min", {{"auto", "1e-6"}, "0"}},
      {"ao.alpha_rho", {{"auto", "0", "1e6"}, "-1"}},
      {"toon.thresholds", {{"even", "-0.999,0.999"}, "0.6,0.2"}},
      {"toon.tones", {{"auto", "0,2,0"}, "0,2.01,0"}},
      {"watercolor.turbulence_size", {{"auto", "0.001", "100%"}, "-3%"}},
      {"watercolor.paper", {{"generated", paper_image()}, "no-such-paper.png"}},
  };
  return t;
}

// The values at both ends of a spec's range.
std::vector<std::string> ends_of(const ParamSpec& spec) {
  auto text = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  switch (spec.type) {
    case ParamType::Float:
      return {text(spec.min_open ? spec.min + 1e-3 : spec.min), text(spec.max)};
    case ParamType::Int:
      return {text(spec.min), text(spec.max)};
    case ParamType::Bool:
      return {"false", "true"};
    case ParamType::Color:
      return {"#000000", "#ffffff"};
    case ParamType::Choice:
      return spec.choices;
    case ParamType::Text:
      return text_forms().at(spec.key).ends;
  }
  return {};
}

// Values just outside the range, each of which `sylva render` must refuse.
std::vector<std::string> outside_of(const ParamSpec& spec) {
  auto text = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  switch (spec.type) {
    case ParamType::Float: {
      const double step = 1e-3 * std::max(1.0, spec.max - spec.min);
      return {text(spec.min_open ? spec.min : spec.min - step), text(spec.max + step)};
    }
    case ParamType::Int:
      return {text(spec.min - 1), text(spec.max + 1)};
    case ParamType::Bool:
      return {"maybe"};
    case ParamType::Color:
      return {"#12345"};
    case ParamType::Choice:
      return {"nonsense"};
    case ParamType::Text:
      return {text_forms().at(spec.key).outside};
  }
  return {};
}

// Settings that switch on the optional paths of a style (shadow maps, a wash, leaf-level
// detail lines, the full tone range), so the key under test meets them; a key under test
// keeps its own value.
std::vector<std::string> with_paths_on(const std::string& builder, const std::string& key) {
  static const std::map<std::string, std::vector<std::string>> on = {
      {"toon", {"toon.cast_shadows=true", "toon.shadow_map_size=256", "toon.specular=true"}},
      {"ink",
       {"ink.fill=0.5", "ink.grain=0.5", "lines.detail=true", "pen.lightest=0", "pen.darkest=1",
        "edges.crease=true", "edges.id=true", "edges.depth_width=2", "edges.fade=0.5"}},
      {"blobs",
       {"edges.crease=true", "edges.depth_width=2", "edges.fade=0.5", "blobs.translucency=0.3"}},
  };
  std::vector<std::string> sets;
  const auto it = on.find(builder);
  if (it == on.end()) return sets;
  for (const std::string& s : it->second)
    if (s.substr(0, s.find('=')) != key) sets.push_back(s);
  return sets;
}

bool all_finite(const cv::Mat& m) {
  if (m.depth() != CV_32F && m.depth() != CV_64F) return true;
  return cv::checkRange(m);
}

bool finite_strokes(const StrokeDrawing& d) {
  for (const Stroke& s : d.strokes) {
    for (const glm::vec2& p : s.points)
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
    for (float w : s.widths)
      if (!std::isfinite(w)) return false;
  }
  return true;
}

// What a render's passes wrote, checked as they are written.
struct Written {
  std::vector<std::string> problems;
  cv::Mat normal, albedo, ka, position, depth, id, color, lines;
  ToonShadowMap shadow;
};

void observe(RenderGraph& graph, Written& w) {
  graph.set_observer([&w](const std::string& name, const std::any& value) {
    const std::string leaf = name.substr(name.rfind('/') + 1);
    if (const cv::Mat* m = std::any_cast<cv::Mat>(&value)) {
      if (!all_finite(*m)) w.problems.push_back(name + " is not finite");
      if (leaf == "edges" && !cv::checkRange(*m, true, nullptr, 0.0, 1.0 + 1e-6))
        w.problems.push_back(name + " leaves [0, 1]");
      for (auto [n, target] : {std::pair{"normal", &w.normal},
                               {"albedo", &w.albedo},
                               {"ka", &w.ka},
                               {"position", &w.position},
                               {"depth", &w.depth},
                               {"id", &w.id},
                               {"color", &w.color},
                               {"lines", &w.lines}})
        if (leaf == n && name.find("key-shadow") == std::string::npos) *target = *m;
    } else if (const StrokeDrawing* d = std::any_cast<StrokeDrawing>(&value)) {
      if (!finite_strokes(*d)) w.problems.push_back(name + " has a stroke that is not finite");
    } else if (const ToonShadowMap* s = std::any_cast<ToonShadowMap>(&value)) {
      if (!all_finite(s->depth)) w.problems.push_back(name + " is not finite");
      w.shadow = *s;
    }
  });
}

class EveryParameter : public ::testing::TestWithParam<Case> {
 protected:
  static void SetUpTestSuite() {
    s_rig = new StyleRig(32);
    assign_clusters(s_rig->scene, {});
    Light point;
    point.type = Light::Type::Point;
    point.vector = glm::vec3(3.0f, 2.0f, 0.0f);
    point.color = glm::vec3(0.2f);
    s_rig->rs.lighting.lights.push_back(point);  // toon's point-light path
  }
  static void TearDownTestSuite() {
    delete s_rig;
    s_rig = nullptr;
  }

  // Renders the style, checking every pass's output into `w`; with `targets`, the raster pass
  // also keeps every G-buffer target for the direct probes. Returns the picture.
  cv::Mat render(const Style& style, Written& w, bool targets) {
    // The foliage preprocessing through a cache shared by every case (each is its own process
    // under ctest): a foliage.* extreme is computed once, not once per preset and render, and
    // the second render of each case (the determinism check) reads it back.
    FoliageRun run;
    run.cache_dir = SYLVA_TEST_FOLIAGE_CACHE;
    SheetScene scene = make_sheet_scene(s_rig->scene, s_rig->rs, run, 1);
    RenderGraph graph;
    observe(graph, w);
    const SheetPlan plan = add_sheet_passes(graph, {&style}, scene);
    if (targets) {
      const GBufferHandles& g = plan.gbuffers[0];
      for (ImageHandle t : {g.normal, g.albedo, g.ka, g.position, g.depth, g.id, g.color})
        graph.present(t);
      graph.compile();
    }
    graph.execute();
    return graph.get<cv::Mat>(plan.outputs[0]).clone();
  }

  static StyleRig* s_rig;
};

StyleRig* EveryParameter::s_rig = nullptr;

// The toon pass straight from the frame's G-buffers, with the key light and with every light.
void check_toon_linear(const Style& style, const std::string& key, const Written& w,
                       const Lighting& lights, const glm::mat4& view) {
  ToonImages in;
  in.normal = w.normal;
  in.albedo = w.albedo;
  in.ka = w.ka;
  in.position = w.position;
  in.shadow = w.shadow;
  ASSERT_FALSE(in.normal.empty() || in.albedo.empty() || in.position.empty() || in.ka.empty());
  for (ToonLight mode : {ToonLight::Key, ToonLight::Sum}) {
    ToonParams p = style.params().toon;
    if (key != "toon.light") p.light = mode;
    const cv::Mat lin = toon_shade_linear(in, lights, view, p);
    ASSERT_EQ(lin.type(), CV_32FC4);
    EXPECT_TRUE(all_finite(lin));
  }
}

// The ink composite of the frame's raster ink over a flat coverage of 0.5 (the wash's edge).
void check_ink_composite(const Style& style, const Written& w) {
  ASSERT_FALSE(w.lines.empty());
  InkParams ink = style.params().ink;
  ink.line_color = style.params().edges.color;
  const cv::Mat half(w.lines.size(), CV_32FC1, cv::Scalar(0.5));
  const cv::Mat out = composite_ink(w.lines, half, make_paper(w.lines.size(), ink.paper), ink);
  EXPECT_EQ(out.type(), CV_8UC4);
  EXPECT_EQ(out.size(), w.lines.size());
}

TEST_P(EveryParameter, BothEndsRenderFiniteOutput) {
  const Case& c = GetParam();
  const ParamSpec spec = Style(c.style).set().spec(c.key, "test");
  for (const std::string& value : ends_of(spec)) {
    SCOPED_TRACE(c.key + " = " + value);
    std::vector<std::string> sets = with_paths_on(Style(c.style).info().builder, c.key);
    sets.push_back(c.key + "=" + value);
    const Style style(c.style, sets);
    Written first, second;
    const bool probes = c.key.starts_with("toon.") || c.key.starts_with("edges.");
    const cv::Mat a = render(style, first, probes);
    EXPECT_EQ(first.problems, std::vector<std::string>{});
    ASSERT_EQ(a.type(), CV_8UC4);
    ASSERT_EQ(a.size(), cv::Size(32, 32));
    const cv::Mat b = render(style, second, probes);
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << "not deterministic";
    if (style.info().builder == "watercolor") {
      cv::Mat alpha;
      cv::extractChannel(a, alpha, 3);
      EXPECT_EQ(cv::countNonZero(alpha != 255), 0) << "watercolor is opaque";
    }
    if (c.key.starts_with("toon."))
      check_toon_linear(style, c.key, first, s_rig->rs.lighting, s_rig->rs.camera.view);
    if (c.key.starts_with("ink.") && style.info().builder == "ink")
      check_ink_composite(style, first);
    if (c.key.starts_with("edges.")) {
      const EdgeImages in{first.normal, first.depth, first.id, first.color};
      ASSERT_FALSE(in.normal.empty() || in.depth.empty() || in.id.empty() || in.color.empty());
      const cv::Mat lines = detect_edges(in, style.params().edges);
      EXPECT_EQ(lines.size(), in.depth.size());
      EXPECT_TRUE(cv::checkRange(lines, true, nullptr, 0.0, 1.0 + 1e-6));
    }
  }
}

TEST_P(EveryParameter, JustOutsideIsOneErrorNamingTheKey) {
  const Case& c = GetParam();
  const ParamSpec spec = Style(c.style).set().spec(c.key, "test");
  const std::string dir = temp_dir("outside");
  for (const std::string& value : outside_of(spec)) {
    SCOPED_TRACE(c.key + " = " + value);
    expect_input_error("render " + small_tree() + " --style " + c.style + " --size 8 --set '" +
                           c.key + "=" + value + "' -o " + dir + "/out.png",
                       c.key);
    EXPECT_FALSE(file_exists(dir + "/out.png"));
  }
}

std::vector<Case> every_case() {
  std::vector<Case> cases;
  for (const std::string& name : builtin_preset_names()) {
    const Style style(name);
    // A stacked preset's layers are built-in presets whose keys are covered on their own.
    if (!style.layers().empty()) continue;
    const std::vector<std::string>& read = sections_read().at(style.info().builder);
    for (const ParamSpec& spec : style.set().specs())
      if (std::find(read.begin(), read.end(), spec.key.substr(0, spec.key.find('.'))) != read.end())
        cases.push_back({name, spec.key});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(BuiltInStyles, EveryParameter, ::testing::ValuesIn(every_case()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string n = info.param.style + "_" + info.param.key;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

// Every spec of every section is some built-in style's: the cases above leave none out.
TEST(EveryParameterCases, CoverEveryKey) {
  std::set<std::string> covered;
  for (const Case& c : every_case())
    covered.insert(c.key);
  const Style standard("standard");
  for (const ParamSpec& spec : standard.set().specs())
    EXPECT_TRUE(covered.contains(spec.key)) << spec.key;
  for (const auto& [key, forms] : text_forms())
    EXPECT_TRUE(covered.contains(key)) << key;
}

}  // namespace
}  // namespace sylva::test

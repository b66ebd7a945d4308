// Contact sheets: sweeps expand to the cartesian product in a fixed order, cells share the
// raster pass and the Luft preprocessing when they ask the same of them, each cell is the
// image the style renders alone, and the layout places images and labels predictably.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "npr/leaf_clusters.h"
#include "samples/plants.h"
#include "styles/sheet.h"
#include "styles/sheet_layout.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using test::where_of;

TEST(Sheet, SweepsExpandToTheProductLastFastest) {
  const auto e = expand_sheet({"ink", "toon"}, {"edges.color=#000000"},
                              {"edges.width=1,2", "edges.normal_threshold=10,20,40"});
  ASSERT_EQ(e.size(), 12u);
  EXPECT_EQ(e[0].style, "ink");
  EXPECT_EQ(e[0].sets, (std::vector<std::string>{"edges.color=#000000", "edges.width=1",
                                                 "edges.normal_threshold=10"}));
  EXPECT_EQ(e[1].swept, (std::vector<std::string>{"edges.width=1", "edges.normal_threshold=20"}));
  EXPECT_EQ(e[3].swept, (std::vector<std::string>{"edges.width=2", "edges.normal_threshold=10"}));
  EXPECT_EQ(e[6].style, "toon");
  EXPECT_EQ(sheet_columns(e.size(), {"edges.width=1,2", "edges.normal_threshold=10,20,40"}), 3);
  EXPECT_EQ(sheet_columns(5, {}), 3);
  EXPECT_EQ(sheet_columns(4, {}), 2);
  EXPECT_EQ(sheet_columns(1, {}), 1);
  EXPECT_EQ(expand_sheet({"ink"}, {}, {}).size(), 1u);
}

TEST(Sheet, BadListsAndSweepsAreInputErrors) {
  EXPECT_EQ(where_of([] { expand_sheet({}, {}, {}); }), "--styles");
  EXPECT_EQ(where_of([] { expand_sheet({"ink", ""}, {}, {}); }), "--styles");
  for (const char* bad : {"edges.width", "=1,2", "edges.width=", "edges.width=1,,2"})
    EXPECT_EQ(where_of([&] { expand_sheet({"ink"}, {}, {bad}); }), "--sweep") << bad;
  EXPECT_EQ(where_of([] {
              expand_sheet({"ink"}, {}, {"edges.width=1", "edges.width=2"});
            }),
            "--sweep");
  // 16 x 17 = 272 cells is over the limit of 256.
  std::string many = "edges.width=1", more = "ink.fill=0";
  for (int i = 1; i < 16; ++i)
    many.append(",").append(std::to_string(1 + i * 0.1));
  for (int i = 1; i < 17; ++i)
    more.append(",").append(std::to_string(i * 0.05));
  EXPECT_EQ(where_of([&] { expand_sheet({"ink"}, {}, {many, more}); }), "--sweep");
  // Values are checked when the styles are built, naming the key.
  const auto entries = expand_sheet({"ink"}, {}, {"edges.width=2,100"});
  EXPECT_EQ(where_of([&] { build_sheet_styles(entries, {}); }), "--set");
}

TEST(Sheet, ChangedParametersAreThoseOffTheDefaults) {
  const Style standard("standard");
  EXPECT_TRUE(changed_parameters(standard).empty());
  const auto styles = build_sheet_styles(expand_sheet({"ink"}, {}, {"edges.width=3"}), {});
  const auto changed = changed_parameters(*styles[0]);
  EXPECT_NE(std::find(changed.begin(), changed.end(), "edges.width=3"), changed.end());
  const auto skipped = changed_parameters(*styles[0], {"edges.width"});
  EXPECT_EQ(skipped.size() + 1, changed.size());
}

struct SheetRig {
  Scene scene;
  std::unique_ptr<GlContext> ctx = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  SheetScene sheet;
  int foliage_calls = 0;
  SheetRig() {
    PlantOptions po;
    po.kind = PlantKind::Bush;
    po.leaves = 300;
    scene = make_plant(po);
    assign_clusters(scene, {});
    raster = std::make_unique<Rasterizer>(*ctx);
    raster->upload(scene);
    sheet.raster.rasterizer = raster.get();
    sheet.raster.camera = make_orbit_camera(scene.bounds(), OrbitParams{}, 64, 64);
    sheet.raster.lighting = Lighting::three_point();
    sheet.foliage_diagonal = scene.bounds(Role::Foliage).diagonal();
    sheet.scene_sphere = scene.framing_sphere();
    sheet.scene = &scene;  // the ink styles' surface samples and leaf pieces
    sheet.branch_cluster = scene.branch_cluster_id();
    sheet.foliage = [this](const FoliageSettings& f) {
      ++foliage_calls;
      IlluminationSetup is;
      is.scene = &scene;
      is.params.grid = f.grid;
      return is;
    };
  }
  // Each style alone, as `sylva render` draws it.
  cv::Mat alone(const Style& style) {
    RenderGraph graph;
    const SheetPlan plan = add_sheet_passes(graph, {&style}, sheet);
    graph.execute();
    return graph.get<cv::Mat>(plan.outputs[0]);
  }
};

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         cv::countNonZero(a.reshape(1) != b.reshape(1)) == 0;
}

TEST(Sheet, CellsShareBuffersAndPreprocessingAndMatchTheirRenders) {
  SheetRig rig;
  // Two ink line widths read the same raster configuration (at 64 px every edges.width is
  // under ink's 1.5 px edges.min_width, so the floor is what differs); expressive reads other
  // normals but the same foliage settings; a second grid is a second preprocessing.
  auto entries = expand_sheet({"ink"}, {}, {"edges.min_width=1.5,3"});
  auto more = expand_sheet({"expressive"}, {}, {"foliage.grid=32,16"});
  entries.insert(entries.end(), more.begin(), more.end());
  auto extra = expand_sheet({"standard"}, {"foliage.grid=64"}, {});
  entries.insert(entries.end(), extra.begin(), extra.end());
  const auto styles = build_sheet_styles(entries, {});
  std::vector<const Style*> list;
  for (const auto& s : styles)
    list.push_back(s.get());
  // Four foliage settings (ink's default grid 128, 32, 16, 64); standard keeps the model's
  // normals, so its preprocessing is declared and culled.
  RenderGraph graph;
  const SheetPlan plan = add_sheet_passes(graph, list, rig.sheet);
  EXPECT_EQ(plan.outputs.size(), 5u);
  EXPECT_EQ(plan.raster_passes, 4);  // ink (shared), expressive x2, standard
  EXPECT_EQ(plan.foliage_passes, 3);
  EXPECT_EQ(rig.foliage_calls, 4);
  EXPECT_TRUE(graph.pass_live("foliage-0/foliage-illumination"));
  EXPECT_FALSE(graph.pass_live("foliage-3/foliage-illumination"));
  EXPECT_TRUE(graph.pass_live("cell-1/leaf-layer"));
  EXPECT_TRUE(graph.pass_live("cell-1/wood-strokes"));
  graph.execute();
  for (size_t i = 0; i < list.size(); ++i) {
    const cv::Mat& cell = graph.get<cv::Mat>(plan.outputs[i]);
    EXPECT_TRUE(same(cell, rig.alone(*list[i]))) << "cell " << i;
  }
  EXPECT_FALSE(same(graph.get<cv::Mat>(plan.outputs[0]), graph.get<cv::Mat>(plan.outputs[1])));
  EXPECT_FALSE(same(graph.get<cv::Mat>(plan.outputs[2]), graph.get<cv::Mat>(plan.outputs[3])));
}

// A cell that keeps the model's normals draws them, even after a cell of the same sheet (or an
// earlier graph on the same rasterizer) replaced them with realigned ones.
TEST(Sheet, ModelNormalsComeBackAfterACellRealignedThem) {
  SheetRig rig;
  const Style standard("standard"), expressive("expressive");
  const cv::Mat first = rig.alone(standard).clone();
  RenderGraph graph;
  const SheetPlan plan = add_sheet_passes(graph, {&expressive, &standard}, rig.sheet);
  graph.execute();
  EXPECT_FALSE(same(graph.get<cv::Mat>(plan.outputs[0]), first));  // realigned: another picture
  EXPECT_TRUE(same(graph.get<cv::Mat>(plan.outputs[1]), first));
  EXPECT_TRUE(same(rig.alone(standard), first));
}

TEST(Sheet, WrapKeepsLinesInsideTheWidth) {
  const std::vector<std::string> items = {"edges.width=2", "edges.normal_threshold=50",
                                          "ink.fill=0.25", "style.normals=realigned-scaled"};
  int base = 0;
  auto width = [&](const std::string& s) {
    return cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &base).width;
  };
  const auto all = wrap_items(items, 2000, 0.5, 3);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0],
            "edges.width=2  edges.normal_threshold=50  ink.fill=0.25  "
            "style.normals=realigned-scaled");
  const auto narrow = wrap_items(items, 200, 0.5, 10);
  EXPECT_GT(narrow.size(), 1u);
  for (const std::string& line : narrow)
    EXPECT_LE(width(line), 200) << line;
  const auto cut = wrap_items(items, 200, 0.5, 1);
  ASSERT_EQ(cut.size(), 1u);
  EXPECT_TRUE(cut[0].ends_with("...")) << cut[0];
  EXPECT_LE(width(cut[0]), 200);
  const auto tiny = wrap_items({"a-very-long-item-that-cannot-fit"}, 40, 0.5, 2);
  ASSERT_EQ(tiny.size(), 1u);
  EXPECT_LE(width(tiny[0]), 40);
  EXPECT_TRUE(wrap_items(items, 200, 0.5, 0).empty());
  EXPECT_TRUE(wrap_items({}, 200, 0.5, 3).empty());
}

TEST(Sheet, LayoutPlacesImagesInRowsWithLabels) {
  std::vector<SheetCell> cells(3);
  for (int i = 0; i < 3; ++i) {
    cells[i].image = cv::Mat(60, 80, CV_8UC4, cv::Scalar(10.0 * i, 100, 200, 255));
    cells[i].title = {"cell" + std::to_string(i)};
    cells[i].details = {"a=1", "b=2"};
  }
  cells[2].image = cv::Scalar(0, 0, 0, 0);  // transparent stays transparent
  SheetLayout layout;
  layout.columns = 2;
  const cv::Mat sheet = layout_sheet(cells, layout);
  ASSERT_EQ(sheet.type(), CV_8UC4);
  // Two columns of 80 px and two rows of 60 px plus labels and gaps.
  EXPECT_GT(sheet.cols, 160);
  EXPECT_LT(sheet.cols, 200);
  EXPECT_GT(sheet.rows, 120 + 2 * 10);
  // Find each image by its colour: cell 1 right of cell 0, cell 2 below it.
  auto locate = [&](const cv::Scalar& c) {
    cv::Mat hit;
    cv::inRange(sheet, c, c, hit);
    return cv::boundingRect(hit);
  };
  const cv::Rect r0 = locate(cv::Scalar(0, 100, 200, 255));
  const cv::Rect r1 = locate(cv::Scalar(10, 100, 200, 255));
  const cv::Rect r2 = locate(cv::Scalar(0, 0, 0, 0));
  EXPECT_EQ(r0.size(), cv::Size(80, 60));
  EXPECT_EQ(r1.size(), cv::Size(80, 60));
  EXPECT_EQ(r2.size(), cv::Size(80, 60));
  EXPECT_EQ(r0.y, r1.y);
  EXPECT_GT(r1.x, r0.x + 80);
  EXPECT_EQ(r2.x, r0.x);
  EXPECT_GT(r2.y, r0.y + 60 + 10);  // a label between the rows
  // The label under cell 0 has dark text; the gaps are opaque white.
  const cv::Mat label = sheet(cv::Rect(r0.x, r0.y + 60, 80, r2.y - r0.y - 60));
  cv::Mat dark;
  cv::inRange(label, cv::Scalar(0, 0, 0, 255), cv::Scalar(120, 120, 120, 255), dark);
  EXPECT_GT(cv::countNonZero(dark), 10);
  EXPECT_EQ(sheet.at<cv::Vec4b>(0, 0), cv::Vec4b(255, 255, 255, 255));
  // Same input, same bytes.
  EXPECT_TRUE(same(sheet, layout_sheet(cells, layout)));
}

}  // namespace
}  // namespace sylva

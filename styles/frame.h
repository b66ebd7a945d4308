// A scene ready to render (DESIGN.md §1): loaded, uploaded into a GL context of its own with
// its plants' levels of detail, and seen through a view (styles/view.h); and the renders a
// program asks of it: one style's image or strokes (what `sylva render` writes) and the
// G-buffers (what `sylva buffers` writes). The CLI renders one frame per process; the Python
// module keeps a frame per scene object and renders it many times, sharing what does not
// depend on the view or the style (FrameMemos).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/gl/gl_context.h"
#include "core/gl/raster_pass.h"
#include "core/io/buffer_files.h"
#include "npr/illumination_pass.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "styles/view.h"

namespace sylva {

// Everything a frame needs: the loaded scene, a GL context and an uploaded rasteriser.
struct Frame {
  Scene scene;
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Rasterizer> rasterizer;
  RasterSetup setup;
};

// Resolves the view options, adds the ground plane (vo.ground), uploads `scene` into a new
// context, with its plants' levels of detail (npr/plant_lod.h) unless vo.lod is "off", read
// from or stored in the result cache folder `cache_dir` ("" = none), and sets the view
// (set_frame_view). Throws InputError for a bad option, std::runtime_error without GL.
std::unique_ptr<Frame> make_frame(Scene scene, ViewOptions& vo, const std::string& cache_dir);
// Points the frame at the view `vo` (resolved here): camera, lighting and raster request. The
// ground and the levels of detail stay as make_frame set them.
void set_frame_view(Frame& frame, ViewOptions& vo);
// The graph's results are plain images: drop the scene, the GL objects and the context
// before encoding files, and hand freed heap back, so peak memory is not their sum.
void release_frame(std::unique_ptr<Frame>& frame);

// InputError(option, ...) naming the styles that can when `style` draws no strokes (vector
// output: .svg, .pdf).
void require_line_style(const Style& style, const std::string& option);

// One style's render: its image (CV_8UC4 BGRA sRGB, straight alpha) or its strokes.
struct StyledRender {
  cv::Mat image;                                 // empty when only the strokes were asked for
  std::shared_ptr<const StrokeDrawing> strokes;  // with `strokes`: the line style's drawing
};
// Renders `style` over `scene` in a graph of its own (add_sheet_passes, one cell), as `sylva
// render` does. With `strokes` (a line style, require_line_style) only the StrokeDrawing is
// made: the raster ink is culled. `on_compiled` sees the compiled graph before it runs.
StyledRender render_styled(const SheetScene& scene, const Style& style, bool strokes = false,
                           const std::function<void(const RenderGraph&)>& on_compiled = {});

// "color,depth,..." as targets; InputError("--buffers", ...) naming an unknown one.
TargetMask parse_buffer_list(const std::string& list);

// What many renders of one frame share, whatever their view and style: the surface samples,
// the leaf pieces, the AO shells and ray tracer, and the Luft preprocessing of the last
// kFoliageMemos foliage settings (keyed exactly, picture-scale rho included). Renders that
// share one FrameMemos run one at a time.
struct FrameMemos {
  static constexpr size_t kFoliageMemos = 16;
  std::shared_ptr<AoMemo> ao;
  std::shared_ptr<SurfaceSampleMemo> samples;
  std::shared_ptr<LeafPieceMemo> pieces;
  std::mutex mutex;
  std::map<std::string, std::shared_ptr<std::shared_ptr<const VertexShading>>> foliage;
  std::vector<std::string> foliage_order;  // keys, oldest first
  FrameMemos();
};
// Makes `scene` read and fill `memos`.
void share_memos(SheetScene& scene, const std::shared_ptr<FrameMemos>& memos);
// The slot of `settings`' Luft preprocessing in `memos` (IlluminationSetup::memo), made empty
// the first time, the oldest dropped beyond kFoliageMemos.
std::shared_ptr<std::shared_ptr<const VertexShading>> foliage_memo(FrameMemos& memos,
                                                                   const FoliageSettings& settings);

// The targets `wanted` of the frame's view as `style` asks the raster pass for them (its
// picture-scale rho and AO; the normals of `mode`), as `sylva buffers` writes them, in
// kAllTargets order. `on_done` sees the graph after it ran. With `memos`, the Luft
// preprocessing is read from and kept in them.
BufferImages render_buffers(Frame& frame, const Style& style, const FoliageRun& run, uint64_t seed,
                            NormalMode mode, TargetMask wanted,
                            const std::function<void(const RenderGraph&)>& on_done = {},
                            FrameMemos* memos = nullptr);

}  // namespace sylva

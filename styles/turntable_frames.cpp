#include "styles/turntable_frames.h"

#include "core/graph/render_graph.h"
#include "npr/ao_pass.h"
#include "npr/leaf_pieces.h"
#include "npr/surface_samples.h"

namespace sylva {

void memoize_preprocessing(SheetScene& scene, bool quiet) {
  scene.ao_memo = std::make_shared<AoMemo>();
  scene.samples_memo = std::make_shared<SurfaceSampleMemo>();
  scene.pieces_memo = std::make_shared<LeafPieceMemo>();
  auto memo = std::make_shared<std::shared_ptr<const VertexShading>>();
  scene.foliage = [f = scene.foliage, memo, quiet](const FoliageSettings& s) {
    IlluminationSetup setup = f(s);
    setup.memo = memo;
    if (quiet) setup.on_done = nullptr;
    return setup;
  };
}

TurntableRenderer::TurntableRenderer(const SheetScene& scene, const Style& style,
                                     const TurntablePath& path, int keyframe_every,
                                     const std::string& keyframe_cache,
                                     const std::string& signature)
    : m_scene(scene),
      m_base(scene.raster.camera),
      m_style(style),
      m_path(path),
      m_every(keyframe_every) {
  (void)last_keyframe(path.frames, keyframe_every);  // validates the interval
  m_blobs = style.traits().blob_outlines;
  if (!m_blobs || (keyframe_every == 1 && keyframe_cache.empty())) return;
  // Keyframed blobs: outlines from their own small raster pass every n-th frame.
  const BlobParams bp = style.params().blobs;
  validate_blob_params(bp);
  m_keyframes = std::make_unique<BlobKeyframes>(
      path.frames, keyframe_every,
      [setup = scene.raster, centre = scene.scene_sphere.centre, path, bp,
       branch = scene.branch_cluster, world = scene.scene, memo = scene.samples_memo](int f) {
        if (bp.outlines == BlobOutlineSource::Scene && world != nullptr)
          return scene_blob_outlines(*coverage_samples(*world, memo.get()),
                                     turntable_camera(setup.camera, centre, path, f), branch, bp);
        return turntable_blob_outlines(setup, centre, path, f, bp, branch);
      },
      keyframe_cache, signature);
}

TurntableRenderer::~TurntableRenderer() = default;

int TurntableRenderer::keyframes_computed() const {
  return m_keyframes ? m_keyframes->computed() : 0;
}

int TurntableRenderer::keyframes_read() const {
  return m_keyframes ? m_keyframes->read() : 0;
}

int TurntableRenderer::prepare_keyframes(int begin, int end) {
  if (!m_keyframes) return 0;
  const std::vector<int> keys = keys_owned(begin, end, m_every, m_path.frames);
  for (int k : keys)
    m_keyframes->prepare(k);
  return static_cast<int>(keys.size());
}

TurntableFrame TurntableRenderer::render(int frame, bool coherence, bool strokes) {
  m_scene.raster.camera = turntable_camera(m_base, m_scene.scene_sphere.centre, m_path, frame);
  if (m_keyframes) m_scene.blobs = std::make_shared<const BlobSet>(m_keyframes->frame(frame));
  RenderGraph graph;
  strokes = strokes && m_style.has_strokes();
  const SheetPlan plan = add_sheet_passes(graph, {&m_style}, m_scene, strokes);
  const bool image = !strokes || coherence;
  if (image) graph.present(plan.outputs[0]);
  if (coherence) {
    graph.present(plan.gbuffers[0].depth);  // the plant's mask
    graph.present(plan.gbuffers[0].position);
  }
  const auto outlines =
      m_blobs && coherence ? graph.find_resource<BlobSet>("blob-outlines") : Handle<BlobSet>{};
  if (outlines.valid()) graph.present(outlines);
  const auto lines =
      coherence && m_style.has_strokes() ? graph.find_resource<cv::Mat>("lines") : ImageHandle{};
  if (lines.valid()) graph.present(lines);
  graph.compile();
  graph.execute();
  TurntableFrame out;
  if (image) out.image = graph.get<cv::Mat>(plan.outputs[0]);  // shares the pixels
  if (strokes) out.strokes = std::make_shared<const StrokeDrawing>(graph.get(plan.strokes[0]));
  if (coherence) {
    out.mask = graph.get<cv::Mat>(plan.gbuffers[0].depth) > 0.0f;
    out.view.image = out.image;
    out.view.position = graph.get<cv::Mat>(plan.gbuffers[0].position);
    out.view.camera = m_scene.raster.camera;
    if (lines.valid()) out.view.lines = graph.get(lines) >= 0.5f;
  }
  if (outlines.valid()) out.blobs = graph.get(outlines);
  return out;
}

}  // namespace sylva

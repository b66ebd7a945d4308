// The frames of one turntable (styles/turntable.h) rendered in one style: what `sylva
// turntable` and `sylva tradeoff --study keyframes` share. Each frame is one render graph
// (styles/sheet.h) from the frame's camera; a blobs style keyframed every n frames takes its
// outlines from npr/blob_keyframes.h (Dudley §5.1) instead of shrink-wrapping every frame.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "npr/blob_keyframes.h"
#include "styles/reprojection.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "styles/turntable.h"

namespace sylva {

// Wraps scene.foliage so the Luft preprocessing runs once for every graph rendered from this
// scene (it does not depend on the view), and sets scene.ao_memo so the AO shells and the ray
// tracer's BVH are made once too; `quiet` drops the preprocessing's progress report.
void memoize_preprocessing(SheetScene& scene, bool quiet);

// One rendered frame.
struct TurntableFrame {
  cv::Mat image;  // CV_8UC4 BGRA sRGB, the style's output (empty when only strokes were asked)
  // With strokes (line styles): the frame's StrokeDrawing, for vector frames.
  std::shared_ptr<const StrokeDrawing> strokes;
  // With coherence only: the plant's coverage (CV_8UC1, 255 where depth > 0), and the blob
  // outlines the frame painted (blobs styles); the frame for reprojection (styles/
  // reprojection.h): the image, view-space positions, line pixels (line styles: the raster
  // ink's coverage >= 0.5) and the camera.
  cv::Mat mask;
  std::optional<BlobSet> blobs;
  CoherenceFrame view;
};

class TurntableRenderer {
 public:
  // `scene` is frame 0's (its raster camera is the path's base; scene_sphere.centre the
  // centre it turns about) and outlives the renderer, as does `style`. `keyframe_every` >= 1
  // (validated by last_keyframe); keyframes are used when the style's builder is "blobs" and
  // keyframe_every > 1 or `keyframe_cache` names a folder (npr/blob_keyframes.h, whose
  // files carry `signature`). Throws InputError for a bad interval or blobs.* parameter.
  TurntableRenderer(const SheetScene& scene, const Style& style, const TurntablePath& path,
                    int keyframe_every, const std::string& keyframe_cache = "",
                    const std::string& signature = "");
  TurntableRenderer(const TurntableRenderer&) = delete;
  TurntableRenderer& operator=(const TurntableRenderer&) = delete;
  ~TurntableRenderer();

  // Frame `frame` (0-based); `coherence` also fills mask and blobs (presenting them from the
  // graph, which keeps the depth target and the outlines alive). `strokes` (a line style)
  // gives the StrokeDrawing, and the image only with coherence.
  TurntableFrame render(int frame, bool coherence, bool strokes = false);

  // Computes (or reads) the keyframes the frames [begin, end) own (keys_owned) without
  // rendering a frame, filling the keyframe cache; returns how many. 0 when not keyframed.
  int prepare_keyframes(int begin, int end);

  bool blobs() const { return m_blobs; }  // the style paints blobs
  bool keyframed() const { return m_keyframes != nullptr; }
  // Keyframes shrink-wrapped so far, and read from the cache; 0 when not keyframed.
  int keyframes_computed() const;
  int keyframes_read() const;

 private:
  SheetScene m_scene;
  Camera m_base;
  const Style& m_style;
  TurntablePath m_path;
  int m_every = 1;
  bool m_blobs = false;
  std::unique_ptr<BlobKeyframes> m_keyframes;
};

}  // namespace sylva

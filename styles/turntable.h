// Turntable animation (DESIGN.md §1): the camera of frame i orbits the scene's framing sphere
// by degrees * i / frames about a world axis through its centre, starting from the view's
// camera; camera-fixed lights turn with it, so the lighting stays put on screen. Frames are
// independent of each other for every style; blobs keyframed every n frames depend only on
// their keyframes, so any slice of frames renders exactly as the same frames of a full run.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "core/gl/camera.h"
#include "core/gl/raster_pass.h"
#include "npr/blob_outlines.h"
#include "passes/blobs.h"

namespace sylva {

struct TurntablePath {
  int frames = 120;        // [1, 100000]
  float degrees = 360.0f;  // total rotation over `frames` (frame `frames` would repeat
                           // frame 0 at 360); [-36000, 36000]
  char axis = 'y';         // world axis: 'x', 'y' (up) or 'z'
  float zoom = 1.0f;       // image magnification; (0, 100], 1 = the view's framing
};

// Throws InputError("--frames" / "--degrees" / "--axis" / "--zoom", ...).
void validate_turntable(const TurntablePath& path);

// The camera of frame `frame` (0-based; frames past the end continue the path, for keyframes
// beyond the last frame): `base` turned about the axis through
// `centre` by degrees * frame / frames, and magnified by zoom.
Camera turntable_camera(const Camera& base, const glm::vec3& centre, const TurntablePath& path,
                        int frame);

// Blob outline jitter between two frames: the mean distance in px that the control points of
// the blobs present in both moved (matched by cluster id and point index); 0 when no blob is
// in both.
double blob_jitter(const BlobSet& previous, const BlobSet& current);

// The blobs of frame `frame` for a keyframed animation (npr/blob_keyframes.h): cluster ids and
// depth rasterised from that frame's camera (`base` = the frame-0 setup; its request's size,
// supersampling and background are kept), shrink-wrapped with `p` as the blobs style does.
std::vector<BlobOutline> turntable_blob_outlines(const RasterSetup& base, const glm::vec3& centre,
                                                 const TurntablePath& path, int frame,
                                                 const BlobParams& p, uint32_t branch_cluster);

// "A:B" = frames A .. B-1 (0-based, half-open like a slice), "A:" = A to the end, ":" or
// empty = all. Throws InputError("--frame-range", ...) unless 0 <= A < B <= frames.
struct FrameRange {
  int begin = 0, end = 0;
};
FrameRange parse_frame_range(const std::string& text, int frames);

// Mean absolute change between two consecutive frames (CV_8UC4, same size), in 8-bit levels
// averaged over B, G, R, over the pixels where either frame's `mask` is set (CV_8UC1, 0 or
// non-zero; the plant's coverage); 0 when no pixel is masked.
double frame_flicker(const cv::Mat& previous, const cv::Mat& current, const cv::Mat& mask_previous,
                     const cv::Mat& mask_current);

}  // namespace sylva

// Keyframed blob animation (Dudley 2005 §5.1): every n-th frame of a camera path is a keyframe
// with freshly shrink-wrapped blobs; the frames between interpolate each blob's control points,
// centre and depth with a Catmull-Rom spline through the keyframes (npr/bspline.h: it passes
// through them, so n = 1 reproduces per-frame blobs exactly; it needs four keys, and the first
// and last intervals reflect their neighbour). The regional centres follow from the
// interpolated points, so they stay fixed relative to the blob. A blob missing from a keyframe
// (hidden or outside the image) keeps the shape of the nearest keyframe that has it and fades
// in or out over the interval. When two keyframes' painter's orders differ, the frames between
// cross-fade from one order to the other.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "npr/blob_outlines.h"

namespace sylva {

// Keyframes are frames 0, n, 2n, ... up to the first at or past the last frame (so the last
// frames interpolate towards a keyframe instead of extrapolating; it may lie past the path's
// end, where the camera path simply continues). Throws InputError("--keyframe-every", ...)
// unless every >= 1; frames >= 1.
int last_keyframe(int frames, int every);

// The blobs of frame `frame` from keyframes[j - 1 .. j + 2] (those that exist), where
// j = frame / every: keys maps a keyframe index (frame / every) to its outlines and must hold
// every index keys_needed() lists.
BlobSet interpolate_blob_keys(const std::map<int, std::vector<BlobOutline>>& keys, int frame,
                              int every, int frames);

// The keyframe indices frame `frame` reads, in increasing order.
std::vector<int> keys_needed(int frame, int every, int frames);

// The keyframe indices that the slice of frames [begin, end) owns, for filling a keyframe
// cache in parallel jobs (turntable --keyframes-only): those whose frame index * every lies in
// the slice, and, for the slice that ends the animation (end == frames), those past the end.
// The slices of a split own every keyframe exactly once. 0 <= begin < end <= frames.
std::vector<int> keys_owned(int begin, int end, int every, int frames);

// The keyframes of one animation, computed on demand (compute(frame) shrink-wraps that
// frame's blobs) and optionally kept in `cache_dir` as text files key-NNNNN.txt whose first
// line is `signature` (a description of everything the outlines depend on): a file with
// another signature is recomputed and replaced. Files are written atomically.
class BlobKeyframes {
 public:
  using Compute = std::function<std::vector<BlobOutline>(int frame)>;
  BlobKeyframes(int frames, int every, Compute compute, std::string cache_dir = "",
                std::string signature = "");
  BlobSet frame(int frame);
  // Makes sure keyframe `index` is computed (or read) and, with a cache folder, on disk.
  void prepare(int index) { (void)key(index); }
  int computed() const { return m_computed; }  // keyframes shrink-wrapped (not read)
  int read() const { return m_read; }          // keyframes read from the cache

 private:
  const std::vector<BlobOutline>& key(int index);
  int m_frames, m_every;
  Compute m_compute;
  std::string m_dir, m_signature;
  std::map<int, std::vector<BlobOutline>> m_keys;
  int m_computed = 0, m_read = 0;
};

// Text form of a keyframe's outlines (exact: floats as %.9g), and back; parse throws
// InputError(where, ...) on a malformed file.
std::string format_blob_outlines(const std::vector<BlobOutline>& blobs);
std::vector<BlobOutline> parse_blob_outlines(const std::string& text, const std::string& where);

}  // namespace sylva

// Animated GIFs (GIF89a, looping forever) for turntables. Frames are kept in memory as 8-bit
// BGR (width x height x 3 bytes each) until finish(), which builds one global palette of at
// most 256 colours over every frame and writes the file atomically. One palette for the whole
// animation, not one per frame, so a flat area keeps its colour from frame to frame (no palette
// flicker). The palette is exact when the frames use at most 256 distinct colours (ink, toon
// on a plain ground); otherwise it is giflib's median cut over pixels sampled evenly from all
// frames, and each pixel takes its nearest palette colour (no dithering, so smooth gradients
// band). Deterministic: same frames, same bytes.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace sylva {

// The frame delay a GIF stores, in hundredths of a second: round(100 / fps), at least 2
// (browsers slow delays of 0 and 1 to 10). So 30 fps plays at 100 / 3 = 33.3 fps.
int gif_delay_centiseconds(double fps);

class GifWriter {
 public:
  // Largest total of frame bytes (width x height x 3 x frames) kept for one GIF: 2 GiB.
  static constexpr size_t kMaxBytes = size_t(2) << 30;

  // `frames` is how many will be written, for the memory check: throws InputError(option,
  // ...) when they would exceed kMaxBytes (use an MP4 or a folder of PNGs instead). `fps` in
  // [1, 240]; the size in [1, 65535] per side.
  GifWriter(std::string path, double fps, cv::Size size, int frames,
            const std::string& option = "--output");

  // An 8-bit BGR (CV_8UC3) or BGRA (alpha dropped) frame of the writer's size.
  void write(const cv::Mat& frame);

  // Writes the file (temporary name, renamed into place). Throws InputError(path, ...) when
  // no frame was written or the file cannot be written; nothing is left behind then.
  void finish();

 private:
  std::string m_path;
  int m_delay;
  cv::Size m_size;
  std::vector<cv::Mat> m_frames;
};

}  // namespace sylva

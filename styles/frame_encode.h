// Encoding a folder of PNG frames (frame-00000.png, ...) into an MP4 or a GIF: what `sylva
// encode` does, and how `sylva turntable -o OUT.mp4` makes its video (its frames go to a
// temporary folder first and are encoded once all are rendered). Fed between renders, the
// encoder gave other bytes from run to run for the same frames; encoded after them, the same
// frames give the same MP4, and a farm's video equals a one-machine one.
#pragma once

#include <string>

namespace sylva {

struct EncodeRequest {
  std::string dir;  // the frame folder
  std::string out;  // .mp4 or .gif, written atomically
  double fps = 30;  // [1, 240]
  int frames = 0;   // [1, 100000]; 0 = every frame up to the highest index in the folder
  bool quiet = false;
};

struct EncodeResult {
  int frames = 0, width = 0, height = 0;
};

// Checks every frame first (missing, partial or of another size: InputError naming it), then
// encodes them in order into r.out (an .mp4 or a .gif, atomically). r.fps and r.frames must be
// in their ranges (the caller checks them).
EncodeResult encode_frames(const EncodeRequest& r);

}  // namespace sylva

// A turntable's frames rendered into their outputs (DESIGN.md §2: styles/ holds the turntable
// frame loops and their outputs): the frames of a range, each from a TurntableRenderer
// (styles/turntable_frames.h), go into a folder of frame files (PNG, EXR, or a line style's
// SVG or PDF strokes; each atomic; with resume the complete frames already there are kept), one
// GIF, or an MP4 encoded from a hidden folder of PNG frames once all are rendered
// (styles/frame_encode.h), so the video is deterministic; optionally with the coherence report,
// a CSV row per frame.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <sstream>
#include <string>

#include "core/io/gif_writer.h"
#include "styles/frame_folder.h"
#include "styles/style_files.h"
#include "styles/turntable.h"
#include "styles/turntable_frames.h"

namespace sylva {

struct TurntableOutput {
  std::string path;                             // .mp4, .gif or a folder
  bool to_dir = false;                          // a folder of frames
  FrameFormat frame_format = FrameFormat::Png;  // folder frames: images or strokes (svg, pdf)
  double fps = 30;                              // MP4 and GIF, [1, 240]
  double dpi = 0;                               // folder frames (style_files.h)
  int frames = 0;                               // frames of the whole animation
  VectorPage page;                              // svg and pdf frames
  bool quiet = false;                           // no progress while an MP4 is encoded
};

// Where the frames go. Made before the first frame, so a bad output fails before any render:
// the folder is created, the GIF opened, or an MP4 writer tried and the hidden folder made.
class FrameSink {
 public:
  // Throws InputError (naming --output for an MP4 writer that does not open).
  FrameSink(const TurntableOutput& out, cv::Size size);
  ~FrameSink();  // removes an MP4's hidden frame folder
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;
  const TurntableOutput& output() const { return m_out; }
  // The file of frame `frame` in the output folder.
  std::string file(int frame) const;
  void write(int frame, const TurntableFrame& f);
  // Finishes the GIF, or encodes the MP4 from its frames.
  void finish();

 private:
  TurntableOutput m_out;
  std::unique_ptr<GifWriter> m_gif;
  std::string m_frames;  // an MP4's frame folder
};

// The coherence report: a row per frame with its time and its coherence against the previous
// one (flicker, reprojection error, line pop; blob jitter for blobs styles).
class CoherenceReport {
 public:
  explicit CoherenceReport(bool blobs);
  void add(int frame, double seconds, TurntableFrame now);
  std::string text() const { return m_csv.str(); }

 private:
  std::ostringstream m_csv;
  TurntableFrame m_previous;
};

// How the frames of one run are rendered.
struct TurntableLoop {
  FrameRange range;      // the frames rendered
  bool resume = false;   // folder output: keep complete frames, remove a killed run's temporaries
  bool report = false;   // fill the coherence report (the frames keep what it needs)
  bool strokes = false;  // vector frames: the strokes of a line style
  bool quiet = false;    // no progress line
};

struct TurntableCount {
  int written = 0, kept = 0;
};

// Renders the frames of loop.range with `renderer` into `sink` (report rows into `report`),
// with a progress line on stderr; a damaged frame found by resume is noted there and rendered
// again. Throws InputError, or Interrupted between frames.
TurntableCount render_turntable_frames(TurntableRenderer& renderer, FrameSink& sink,
                                       const TurntableLoop& loop, CoherenceReport& report);

}  // namespace sylva

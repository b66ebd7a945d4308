#include "styles/turntable_output.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/progress.h"
#include "styles/frame_encode.h"
#include "styles/frame_folder.h"
#include "styles/reprojection.h"
#include "styles/video_out.h"

namespace fs = std::filesystem;

namespace sylva {

FrameSink::FrameSink(const TurntableOutput& out, cv::Size size) : m_out(out) {
  if (out.to_dir) {
    std::error_code ec;
    fs::create_directories(out.path, ec);
    if (ec) throw InputError("--output", "cannot create '" + out.path + "': " + ec.message());
  } else if (fs::path(out.path).extension() == ".gif") {
    m_gif = std::make_unique<GifWriter>(out.path, out.fps, size, out.frames);
  } else {  // an MP4: the frames go to a temporary folder, encoded at the end
    {
      VideoOut probe(out.path, out.fps, size);
    }  // no MP4 writer: an error now, not after the render
    m_frames = make_temporary_folder_beside(out.path);
  }
}

FrameSink::~FrameSink() {
  std::error_code ec;
  if (!m_frames.empty()) fs::remove_all(m_frames, ec);
}

std::string FrameSink::file(int frame) const {
  return (fs::path(m_out.path) / frame_file_name(frame, m_out.frame_format)).string();
}

void FrameSink::write(int frame, const TurntableFrame& f) {
  const bool vector = is_vector_format(m_out.frame_format);
  if (m_out.to_dir && vector) {
    write_vector_drawing(file(frame), *f.strokes, m_out.page);
  } else if (m_out.to_dir) {
    write_styled_image(file(frame), f.image, m_out.dpi);
  } else if (m_gif) {
    m_gif->write(f.image);
  } else {
    try {
      write_styled_image((fs::path(m_frames) / frame_file_name(frame)).string(), f.image, 0.0);
    } catch (const InputError& e) {  // named after the video, not its hidden frame folder
      throw InputError(m_out.path, e.reason());
    }
  }
}

void FrameSink::finish() {
  if (m_gif) m_gif->finish();
  if (!m_frames.empty())
    encode_frames({m_frames, m_out.path, m_out.fps, m_out.frames, m_out.quiet});
}

CoherenceReport::CoherenceReport(bool blobs) {
  m_csv << "frame,seconds,flicker,reprojection_error,line_pop" << (blobs ? ",jitter" : "") << "\n";
}

void CoherenceReport::add(int frame, double seconds, TurntableFrame now) {
  m_csv << frame << ',' << seconds << ',';
  if (!m_previous.image.empty()) {
    const FrameCoherence c = frame_coherence(m_previous.view, now.view);
    m_csv << frame_flicker(m_previous.image, now.image, m_previous.mask, now.mask) << ','
          << c.reprojection_error << ',';
    if (c.line_pop) m_csv << *c.line_pop;
  } else {
    m_csv << ",,";
  }
  if (now.blobs) {
    m_csv << ',';
    if (!m_previous.image.empty() && m_previous.blobs)
      m_csv << blob_jitter(*m_previous.blobs, *now.blobs);
  }
  m_csv << '\n';
  m_previous = std::move(now);
}

namespace {

// With resume: whether frame `frame` is kept; a damaged one is rendered again.
bool keep_frame(const TurntableLoop& loop, const std::string& file, FrameFormat format,
                Progress& progress, int frame) {
  if (!loop.resume) return false;
  std::error_code ec;
  if (!fs::exists(file, ec)) return false;
  const std::string problem = frame_problem(file, format);
  if (problem.empty()) {
    progress.step("frame " + std::to_string(frame) + " kept");
    return true;
  }
  if (!loop.quiet)
    std::fprintf(stderr,
                 "sylva: frame %d in the output folder is damaged (%s); rendering it again\n",
                 frame, problem.c_str());
  return false;
}

}  // namespace

TurntableCount render_turntable_frames(TurntableRenderer& renderer, FrameSink& sink,
                                       const TurntableLoop& loop, CoherenceReport& report) {
  const FrameFormat format = sink.output().frame_format;
  if (loop.resume)
    remove_stale_frame_temporaries(sink.output().path, loop.range.begin, loop.range.end, format);
  TurntableCount n;
  ProgressOptions po;
  po.quiet = loop.quiet;
  Progress progress("turntable", static_cast<size_t>(loop.range.end - loop.range.begin), po);
  for (int i = loop.range.begin; i < loop.range.end; ++i) {
    if (keep_frame(loop, sink.file(i), format, progress, i)) {
      ++n.kept;
      continue;
    }
    const auto t0 = std::chrono::steady_clock::now();
    TurntableFrame now = renderer.render(i, loop.report, loop.strokes);
    sink.write(i, now);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (loop.report) report.add(i, seconds, std::move(now));
    ++n.written;
    progress.step("frame " + std::to_string(i));
  }
  progress.finish();
  return n;
}

}  // namespace sylva

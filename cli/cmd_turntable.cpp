// sylva turntable SCENE --style S --frames N [--degrees 360] [--axis y] [--zoom Z] [--fps F]
//   [--keyframe-every n] [--keyframe-cache DIR [--keyframes-only]] [--frame-range A:B]
//   [--resume] [--report coherence.csv] -o OUT.mp4|OUT.gif|DIR/
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/encode.h"
#include "cli/frame.h"
#include "cli/frame_folder.h"
#include "cli/turntable_options.h"
#include "cli/video_out.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/gif_writer.h"
#include "core/progress.h"
#include "npr/blob_keyframes.h"
#include "styles/turntable.h"
#include "styles/turntable_frames.h"

namespace fs = std::filesystem;

namespace sylva::cli {

namespace {

// Everything a keyframe's blobs depend on, for --keyframe-cache: the scene, the frame-0 camera,
// the image, the path, the interval and the blobs.* settings.
std::string keyframe_signature(const Frame& frame, const Style& style, const TurntablePath& path,
                               int every) {
  std::ostringstream s;
  s.precision(9);
  s << "sylva blob keyframes v1; source " << frame.scene.report.source << "; triangles "
    << frame.scene.triangle_count() << "; clusters " << frame.scene.max_cluster_id() << "; size "
    << frame.setup.camera.width << 'x' << frame.setup.camera.height << "; ssaa "
    << frame.setup.request.ssaa << "; frames " << path.frames << "; degrees " << path.degrees
    << "; axis " << path.axis << "; zoom " << path.zoom << "; every " << every << "; view";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      s << ' ' << frame.setup.camera.view[c][r] << ' ' << frame.setup.camera.proj[c][r];
  for (const ParamSpec& spec : style.set().specs())
    if (spec.key.starts_with("blobs."))
      s << "; " << spec.key << '=' << style.set().value_text(spec.key);
  return s.str();
}

// Where the frames go: files in a folder, one GIF or one MP4.
class FrameSink {
 public:
  FrameSink(const TurntableOptions& o, const TurntableChecks& c, const Style& style, cv::Size size)
      : m_o(o), m_style(style), m_to_dir(c.to_dir), m_vector(c.vector) {
    if (c.to_dir) {
      std::error_code ec;
      fs::create_directories(o.out, ec);
      if (ec) throw InputError("--output", "cannot create '" + o.out + "': " + ec.message());
    } else if (fs::path(o.out).extension() == ".gif") {
      m_gif = std::make_unique<GifWriter>(o.out, o.fps, size, o.path.frames);
    } else {  // an MP4: the frames go to a temporary folder, encoded at the end (cli/encode.h)
      { VideoOut probe(o.out, o.fps, size); }  // no MP4 writer: an error now, not after the render
      m_frames = make_temporary_folder_beside(o.out);
    }
  }
  ~FrameSink() {
    std::error_code ec;
    if (!m_frames.empty()) fs::remove_all(m_frames, ec);
  }
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;
  std::string file(int i) const {
    return (fs::path(m_o.out) / frame_file_name(i, m_o.frame_format)).string();
  }
  void write(int i, const TurntableFrame& f) {
    if (m_vector) {
      write_vector_drawing(file(i), *f.strokes, vector_page(m_style, m_o.view, m_o.dpi));
    } else if (m_to_dir) {
      write_styled_image(file(i), f.image, m_o.dpi);
    } else if (m_gif) {
      m_gif->write(f.image);
    } else {
      try {
        write_styled_image((fs::path(m_frames) / frame_file_name(i)).string(), f.image, 0.0);
      } catch (const InputError& e) {  // named after the video, not its hidden frame folder
        const std::string what = e.what();
        throw InputError(m_o.out, what.substr(std::min(what.size(), e.where().size() + 2)));
      }
    }
  }
  void finish() {
    if (m_gif) m_gif->finish();
    if (!m_frames.empty()) encode_frames({m_frames, m_o.out, m_o.fps, m_o.path.frames, m_o.quiet});
  }

 private:
  const TurntableOptions& m_o;
  const Style& m_style;
  bool m_to_dir, m_vector;
  std::unique_ptr<GifWriter> m_gif;
  std::string m_frames;  // an MP4's frame folder
};

// The --report CSV: a row per frame with its time and its coherence against the previous one.
class CoherenceReport {
 public:
  explicit CoherenceReport(bool blobs) {
    m_csv << "frame,seconds,flicker,reprojection_error,line_pop" << (blobs ? ",jitter" : "")
          << "\n";
  }
  void add(int i, double seconds, TurntableFrame now) {
    m_csv << i << ',' << seconds << ',';
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
  std::string text() const { return m_csv.str(); }

 private:
  std::ostringstream m_csv;
  TurntableFrame m_previous;
};

// With --resume: whether frame `file` is kept; a damaged one is rendered again.
bool keep_frame(const TurntableOptions& o, const std::string& file, Progress& progress, int i) {
  if (!o.resume) return false;
  std::error_code ec;
  if (!fs::exists(file, ec)) return false;
  const std::string problem = frame_problem(file, o.frame_format);
  if (problem.empty()) {
    progress.step("frame " + std::to_string(i) + " kept");
    return true;
  }
  if (!o.quiet)
    std::fprintf(stderr,
                 "sylva: frame %d in the output folder is damaged (%s); rendering it again\n", i,
                 problem.c_str());
  return false;
}

void run_turntable(const CLI::App& cmd, TurntableOptions& o) {
  const TurntableChecks c = check_turntable_options(cmd, o);
  const Style& style = *c.style;
  auto frame = prepare_frame(o.scene, o.view, result_cache_dir(o.illumination));
  SheetScene scene = sheet_scene(*frame, o.illumination, o.scene.seed);
  memoize_preprocessing(scene, o.quiet);
  const Camera base = frame->setup.camera;
  TurntableRenderer renderer(
      scene, style, o.path, o.keyframe_every, o.keyframe_cache,
      c.blobs ? keyframe_signature(*frame, style, o.path, o.keyframe_every) : "");
  if (o.keyframes_only) {
    const int keys = renderer.prepare_keyframes(c.range.begin, c.range.end);
    std::printf("wrote %s (%d keyframe(s): %d shrink-wrapped, %d kept)\n", o.keyframe_cache.c_str(),
                keys, renderer.keyframes_computed(), renderer.keyframes_read());
    return;
  }
  FrameSink sink(o, c, style, cv::Size(base.width, base.height));
  if (o.resume) remove_stale_frame_temporaries(o.out, c.range.begin, c.range.end, o.frame_format);
  CoherenceReport report(c.blobs);
  int written = 0, kept = 0;
  ProgressOptions po;
  po.quiet = o.quiet;
  Progress progress("turntable", static_cast<size_t>(c.range.end - c.range.begin), po);
  for (int i = c.range.begin; i < c.range.end; ++i) {
    if (keep_frame(o, sink.file(i), progress, i)) {
      ++kept;
      continue;
    }
    const auto t0 = std::chrono::steady_clock::now();
    TurntableFrame now = renderer.render(i, !o.report.empty(), c.vector);
    sink.write(i, now);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.report.empty()) report.add(i, seconds, std::move(now));
    ++written;
    progress.step("frame " + std::to_string(i));
  }
  progress.finish();
  release_frame(frame);
  sink.finish();
  if (!o.report.empty()) write_file_atomic(o.report, report.text());
  std::printf("wrote %s (%d frame(s)%s, %dx%d, style %s)\n", o.out.c_str(), written,
              kept > 0 ? (", " + std::to_string(kept) + " kept").c_str() : "", base.width,
              base.height, style.info().name.c_str());
}

}  // namespace

Action add_turntable_command(CLI::App& app) {
  auto o = std::make_shared<TurntableOptions>();
  o->view.size = "512x512";
  CLI::App* cmd = app.add_subcommand(
      "turntable",
      "Render a turntable animation in a style: an MP4, a GIF or a folder of PNG frames");
  add_turntable_options(*cmd, *o);
  return [o, cmd] { run_turntable(*cmd, *o); };
}

}  // namespace sylva::cli

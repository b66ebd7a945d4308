// sylva turntable SCENE --style S --frames N [--degrees 360] [--axis y] [--zoom Z] [--fps F]
//   [--keyframe-every n] [--keyframe-cache DIR [--keyframes-only]] [--frame-range A:B]
//   [--resume] [--report coherence.csv] -o OUT.mp4|OUT.gif|DIR/
// The options are checked (cli/turntable_options.h), the scene loaded, and the frames rendered
// into their outputs by the library (styles/turntable_output.h).
#include <cstdio>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/frame.h"
#include "cli/turntable_options.h"
#include "core/io/atomic_file.h"
#include "styles/turntable_frames.h"
#include "styles/turntable_output.h"

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

TurntableOutput turntable_output(const TurntableOptions& o, const TurntableChecks& c,
                                 const Style& style) {
  TurntableOutput out;
  out.path = o.out;
  out.to_dir = c.to_dir;
  out.frame_format = c.frame_format;
  out.fps = o.fps;
  out.dpi = o.dpi;
  out.frames = o.path.frames;
  if (c.vector) out.page = vector_page(style, o.view.background == "transparent", o.dpi);
  out.quiet = o.quiet;
  return out;
}

TurntableLoop turntable_loop(const TurntableOptions& o, const TurntableChecks& c) {
  TurntableLoop loop;
  loop.range = c.range;
  loop.resume = o.resume;
  loop.report = !o.report.empty();
  loop.strokes = c.vector;
  loop.quiet = o.quiet;
  return loop;
}

// --keyframes-only: the keyframes the range owns into the cache, no frame.
void fill_keyframe_cache(TurntableRenderer& renderer, const TurntableOptions& o,
                         const TurntableChecks& c) {
  const int keys = renderer.prepare_keyframes(c.range.begin, c.range.end);
  std::printf("wrote %s (%d keyframe(s): %d shrink-wrapped, %d kept)\n", o.keyframe_cache.c_str(),
              keys, renderer.keyframes_computed(), renderer.keyframes_read());
}

void run_turntable(const CLI::App& cmd, TurntableOptions& o) {
  const TurntableChecks c = check_turntable_options(cmd, o);
  const Style& style = *c.style;
  auto frame = prepare_frame(o.scene, o.view, result_cache_dir(o.foliage));
  SheetScene scene = sheet_scene(*frame, foliage_run(o.foliage), o.scene.seed);
  memoize_preprocessing(scene, o.quiet);
  const Camera base = frame->setup.camera;
  TurntableRenderer renderer(
      scene, style, o.path, o.keyframe_every, o.keyframe_cache,
      c.blobs ? keyframe_signature(*frame, style, o.path, o.keyframe_every) : "");
  if (o.keyframes_only) {
    fill_keyframe_cache(renderer, o, c);
    return;
  }
  FrameSink sink(turntable_output(o, c, style), cv::Size(base.width, base.height));
  CoherenceReport report(c.blobs);
  const TurntableCount n = render_turntable_frames(renderer, sink, turntable_loop(o, c), report);
  release_frame(frame);
  sink.finish();
  if (!o.report.empty()) write_file_atomic(o.report, report.text());
  std::printf("wrote %s (%d frame(s)%s, %dx%d, style %s)\n", o.out.c_str(), n.written,
              n.kept > 0 ? (", " + std::to_string(n.kept) + " kept").c_str() : "", base.width,
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

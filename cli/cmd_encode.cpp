// sylva encode DIR -o OUT.mp4|OUT.gif [--fps F] [--frames N]: a folder of frames written by
// `sylva turntable -o DIR/` (e.g. by the tasks of a render farm) encoded into the video that
// `sylva turntable -o OUT.mp4|OUT.gif` would have written: the same writers, settings and GIF
// palette rule, from the same pixels (the PNG frames are lossless).
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "styles/frame_encode.h"

namespace sylva::cli {

Action add_encode_command(CLI::App& app) {
  auto o = std::make_shared<EncodeRequest>();
  CLI::App* cmd = app.add_subcommand(
      "encode",
      "Encode a folder of turntable frames (frame-00000.png, ...) into an MP4 or a GIF, as "
      "'turntable -o OUT.mp4' would have");
  cmd->add_option("dir", o->dir, "Folder of frames written by 'sylva turntable -o DIR/'")
      ->required();
  cmd->add_option("--fps", o->fps, "Frames per second, [1, 240]")->capture_default_str();
  cmd->add_option("--frames", o->frames,
                  "Number of frames to encode, [1, 100000]; 0 = up to the highest frame in the "
                  "folder. A missing or partial frame is an error naming it")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "No progress output");
  cmd->add_option("-o,--output", o->out, "Output .mp4 or .gif")->required();
  return [o] {
    check_output_path("--output", o->out, {".mp4", ".gif"});
    if (!(o->fps >= 1 && o->fps <= 240)) throw InputError("--fps", "must be in [1, 240]");
    if (o->frames < 0 || o->frames > 100000)
      throw InputError("--frames", "must be in [1, 100000] (or 0: every frame in the folder)");
    const EncodeResult r = encode_frames(*o);
    std::printf("wrote %s (%d frame(s), %dx%d, %g fps)\n", o->out.c_str(), r.frames, r.width,
                r.height, o->fps);
  };
}

}  // namespace sylva::cli

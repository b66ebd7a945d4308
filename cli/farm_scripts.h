// The job scripts of `sylva farm slurm` (README "Render farms"): a Slurm array job whose task
// $SLURM_ARRAY_TASK_ID renders one contiguous chunk of a turntable's frames with
// `sylva turntable ... --frame-range A:B --resume` into a frame folder, an encode job that runs
// `sylva encode` once every task succeeded, for keyframed blobs a keys job (an array of the
// same chunks) that fills the keyframe cache first, and submit.sh, which submits them chained
// by --dependency=afterok. Every script also runs as plain bash (SLURM_ARRAY_TASK_ID set by
// hand), and holds absolute paths only. Nothing of the scheduler is reimplemented.
#pragma once

#include <string>
#include <vector>

#include "styles/turntable.h"

namespace sylva::cli {

struct FarmJob {
  std::string sylva;                        // absolute path of the sylva binary
  std::vector<std::string> turntable_args;  // after "turntable": scene and options, absolute
                                            // paths, without -o, --frame-range and --resume
  int frames = 1;                           // of the whole turntable
  int tasks = 1;                            // array tasks, [1, frames]
  int max_running = 0;                      // %P on the array; 0 = no limit
  std::string partition, time, mem;         // #SBATCH values; empty = the cluster's default
  int cpus_per_task = 0;                    // 0 = the cluster's default
  std::string job_dir;                      // absolute; scripts and logs/
  std::string frames_dir;                   // absolute; the frames
  std::string video;                        // absolute .mp4 / .gif, or empty: frames only
  double fps = 30;
  std::string keyframe_cache;  // absolute; with keyframes, filled by keys.sbatch first
};

struct FarmScripts {
  std::string render, encode, keys, submit;  // encode / keys empty when not needed
};

// Contiguous chunks of [0, frames) for `tasks` tasks, as even as possible (the first
// frames % tasks chunks one frame longer). 1 <= tasks <= frames.
std::vector<FrameRange> split_frames(int frames, int tasks);

// `text` as one word of a POSIX shell: in single quotes, a ' written as '\''.
std::string shell_quote(const std::string& text);

FarmScripts farm_scripts(const FarmJob& job);

// Throws InputError naming the option unless the #SBATCH values are well formed:
// --partition names ([A-Za-z0-9_.-], comma-separated), --time minutes, MM:SS, HH:MM:SS,
// D-HH, D-HH:MM or D-HH:MM:SS, --mem a whole number with an optional K, M, G or T suffix,
// --cpus-per-task in [1, 4096] (0 = unset), --max-running >= 0.
void check_slurm_values(const FarmJob& job);

}  // namespace sylva::cli

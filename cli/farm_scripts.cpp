#include "cli/farm_scripts.h"

#include <charconv>
#include <regex>
#include <sstream>

#include "core/error.h"

namespace sylva::cli {

namespace {

std::string command_line(const FarmJob& job, const std::vector<std::string>& extra) {
  std::ostringstream line;
  line << shell_quote(job.sylva) << " turntable";
  for (const std::string& a : job.turntable_args)
    line << ' ' << shell_quote(a);
  for (const std::string& a : extra)
    line << ' ' << (a == "$range" ? std::string("\"$range\"") : shell_quote(a));
  return line.str();
}

// The #SBATCH header: name, log file, resources.
std::string header(const FarmJob& job, const std::string& name, const std::string& log,
                   const std::string& array) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "#SBATCH --job-name=" << name << "\n"
    << "#SBATCH --chdir=" << job.job_dir << "\n"
    << "#SBATCH --output=" << job.job_dir << "/logs/" << log << "\n"
    << "#SBATCH --open-mode=append\n";
  if (!array.empty()) s << "#SBATCH --array=" << array << "\n#SBATCH --requeue\n";
  if (!job.partition.empty()) s << "#SBATCH --partition=" << job.partition << "\n";
  if (!job.time.empty()) s << "#SBATCH --time=" << job.time << "\n";
  if (!job.mem.empty()) s << "#SBATCH --mem=" << job.mem << "\n";
  if (job.cpus_per_task > 0) s << "#SBATCH --cpus-per-task=" << job.cpus_per_task << "\n";
  return s.str();
}

// An array script: the task's chunk from $SLURM_ARRAY_TASK_ID, then `sylva turntable`.
std::string array_script(const FarmJob& job, const std::string& name, const std::string& what,
                         const std::vector<std::string>& extra) {
  std::ostringstream range;
  range << "0-" << job.tasks - 1;
  if (job.max_running > 0) range << '%' << job.max_running;
  const std::string array = range.str();
  std::ostringstream s;
  s << header(job, "sylva-" + name, name + "-%a.log", array) << "# " << what
    << ": task $SLURM_ARRAY_TASK_ID"
    << " of " << job.tasks << " (0-based) takes its chunk of the " << job.frames << " frames.\n"
    << "# Without Slurm: SLURM_ARRAY_TASK_ID=0 bash " << name << ".sbatch\n"
    << "set -eu\ncase \"${SLURM_ARRAY_TASK_ID:-}\" in\n";
  const std::vector<FrameRange> chunks = split_frames(job.frames, job.tasks);
  for (size_t t = 0; t < chunks.size(); ++t)
    s << "  " << t << ") range=" << chunks[t].begin << ':' << chunks[t].end << " ;;\n";
  s << "  *) echo \"" << name << ".sbatch: SLURM_ARRAY_TASK_ID must be 0 to " << job.tasks - 1
    << "\" >&2; exit 2 ;;\nesac\n"
    << "echo \"" << name << " task $SLURM_ARRAY_TASK_ID: frames $range\"\n"
    << "exec " << command_line(job, extra) << "\n";
  return s.str();
}

std::string encode_script(const FarmJob& job) {
  char fps[32];
  *std::to_chars(fps, fps + sizeof fps - 1, job.fps).ptr = '\0';  // shortest exact form
  std::ostringstream s;
  s << header(job, "sylva-encode", "encode.log", "")
    << "# Encodes the frames once every render task has succeeded.\nset -eu\nexec "
    << shell_quote(job.sylva) << " encode " << shell_quote(job.frames_dir) << " --frames "
    << job.frames << " --fps " << fps << " -o " << shell_quote(job.video) << "\n";
  return s.str();
}

std::string submit_script(const FarmJob& job, bool keys, bool encode) {
  std::ostringstream s;
  s << "#!/bin/bash\n# Submits this folder's jobs to Slurm, each after the one before it "
       "succeeded; prints their ids.\nset -euo pipefail\ncd "
    << shell_quote(job.job_dir) << "\nafter=()\n"
    << "submit() {  # NAME SCRIPT: sbatch it after the previous job\n"
    << "  local id\n"
    << "  id=$(sbatch --parsable --kill-on-invalid-dep=yes \"${after[@]}\" \"$2\")\n"
    << "  id=${id%%;*}\n"
    << "  echo \"$1 job $id\"\n"
    << "  after=(--dependency=afterok:$id)\n"
    << "}\n";
  if (keys) s << "submit keys keys.sbatch\n";
  s << "submit render render.sbatch\n";
  if (encode) s << "submit encode encode.sbatch\n";
  return s.str();
}

}  // namespace

std::vector<FrameRange> split_frames(int frames, int tasks) {
  SYLVA_CHECK(tasks >= 1 && tasks <= frames, "split_frames: bad task count");
  std::vector<FrameRange> out;
  int begin = 0;
  for (int t = 0; t < tasks; ++t) {
    const int size = frames / tasks + (t < frames % tasks ? 1 : 0);
    out.push_back({begin, begin + size});
    begin += size;
  }
  return out;
}

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text)
    if (c == '\'')
      out += "'\\''";
    else
      out.push_back(c);
  out.push_back('\'');
  return out;
}

FarmScripts farm_scripts(const FarmJob& job) {
  FarmScripts out;
  const bool keys = !job.keyframe_cache.empty();
  const std::vector<std::string> cache = {"--keyframe-cache", job.keyframe_cache};
  std::vector<std::string> render_extra = {"--frame-range", "$range", "--resume", "-o",
                                           job.frames_dir + "/"};
  if (keys) render_extra.insert(render_extra.begin(), cache.begin(), cache.end());
  out.render = array_script(job, "render", "Renders a sylva turntable's frames", render_extra);
  if (keys) {
    std::vector<std::string> keys_extra = cache;
    for (const char* a : {"--keyframes-only", "--frame-range", "$range", "-o"})
      keys_extra.push_back(a);
    keys_extra.push_back(job.frames_dir + "/");
    out.keys = array_script(job, "keys", "Fills the keyframe cache", keys_extra);
  }
  if (!job.video.empty()) out.encode = encode_script(job);
  out.submit = submit_script(job, keys, !job.video.empty());
  return out;
}

void check_slurm_values(const FarmJob& job) {
  static const std::regex partition(R"([A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*)");
  static const std::regex time(R"((\d+-\d+(:\d+){0,2})|(\d+(:\d+){0,2}))");
  static const std::regex mem(R"(\d+[KMGT]?)");
  if (!job.partition.empty() && !std::regex_match(job.partition, partition))
    throw InputError("--partition", "'" + job.partition + "' is not a partition name");
  if (!job.time.empty() && !std::regex_match(job.time, time))
    throw InputError("--time", "'" + job.time +
                                   "' is not a Slurm time (minutes, MM:SS, HH:MM:SS, D-HH, "
                                   "D-HH:MM or D-HH:MM:SS)");
  if (!job.mem.empty() && !std::regex_match(job.mem, mem))
    throw InputError("--mem", "'" + job.mem + "' is not a memory size (e.g. 4000, 4G)");
  if (job.cpus_per_task < 0 || job.cpus_per_task > 4096)
    throw InputError("--cpus-per-task", "must be in [1, 4096] (0 = the cluster's default)");
  if (job.max_running < 0) throw InputError("--max-running", "must be at least 1 (0 = no limit)");
}

}  // namespace sylva::cli

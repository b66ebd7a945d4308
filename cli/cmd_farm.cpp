// sylva farm slurm SCENE [turntable options] --tasks N [--max-running P] [--partition P]
//   [--time T] [--mem M] [--cpus-per-task C] [--job-dir DIR] [--submit] -o OUT.mp4|OUT.gif|DIR/
// Writes a turntable's Slurm jobs into the job folder (cli/farm_scripts.h) and, with --submit,
// submits them. Every turntable option is checked here, before anything reaches a cluster.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "cli/commands.h"
#include "cli/farm_scripts.h"
#include "cli/turntable_options.h"
#include "core/error.h"
#include "core/io/atomic_file.h"

namespace fs = std::filesystem;

namespace sylva::cli {

namespace {

struct FarmOptions {
  TurntableOptions tt;
  FarmJob job;
  std::string job_dir;
  bool submit = false;
};

// Options of the farm itself, and turntable options the farm sets for each task.
const std::set<std::string> kFarmOwn = {
    "--tasks",   "--max-running", "--partition", "--time",  "--mem",  "--cpus-per-task",
    "--job-dir", "--submit",      "--output",    "--quiet", "--help", "--keyframe-cache"};
const std::set<std::string> kFarmSets = {"--frame-range", "--resume", "--report",
                                         "--keyframes-only"};
const std::set<std::string> kPathOptions = {"scene", "--cache-dir", "--surface-out",
                                            "--keyframe-cache"};

std::string option_name(const CLI::Option& opt) {
  if (!opt.nonpositional()) return opt.get_name();
  if (!opt.get_lnames().empty()) return "--" + opt.get_lnames()[0];
  return "-" + opt.get_snames()[0];
}

std::string absolute(const std::string& path) {
  return fs::absolute(path).lexically_normal().string();
}

// The turntable arguments a task repeats: every option given, paths made absolute.
std::vector<std::string> task_arguments(const CLI::App& cmd) {
  std::vector<std::string> args;
  for (const CLI::Option* opt : cmd.get_options()) {
    const std::string name = option_name(*opt);
    if (opt->count() == 0 || kFarmOwn.count(name)) continue;
    if (kFarmSets.count(name))
      throw InputError(name, "the farm sets it for each task (drop it; --tasks splits the frames)");
    if (opt->get_expected_min() == 0) {  // a flag
      if (opt->as<bool>()) args.push_back(name);
      continue;
    }
    for (std::string value : opt->results()) {
      const bool path = kPathOptions.count(name) || (name == "--style" && value.ends_with(".toml"));
      if (opt->nonpositional()) args.push_back(name);
      args.push_back(path ? absolute(value) : value);
    }
  }
  return args;
}

// Where the frames, the video and the job folder go.
void place_outputs(FarmOptions& o, const TurntableChecks& c) {
  std::string out = o.tt.out;
  while (out.size() > 1 && out.ends_with("/"))
    out.pop_back();
  fs::path base = fs::path(absolute(out));
  const std::string job_dir =
      o.job_dir.empty() ? fs::path(base).replace_extension(".farm").string() : absolute(o.job_dir);
  o.job.job_dir = job_dir;
  o.job.frames_dir = c.to_dir ? base.string() : (fs::path(job_dir) / "frames").string();
  o.job.video = c.to_dir ? "" : base.string();
  if (!c.to_dir && access(base.parent_path().c_str(), W_OK) != 0)
    throw InputError("--output", "cannot write into '" + base.parent_path().string() + "'");
}

void write_script(const std::string& dir, const std::string& name, const std::string& text) {
  if (text.empty()) return;
  const fs::path path = fs::path(dir) / name;
  write_file_atomic(path.string(), text);
  std::error_code ec;
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add, ec);
}

void write_job_folder(const FarmJob& job, const FarmScripts& scripts) {
  for (const std::string& dir : {job.job_dir + "/logs", job.frames_dir}) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError("--job-dir", "cannot create '" + dir + "': " + ec.message());
  }
  write_script(job.job_dir, "render.sbatch", scripts.render);
  write_script(job.job_dir, "keys.sbatch", scripts.keys);
  write_script(job.job_dir, "encode.sbatch", scripts.encode);
  write_script(job.job_dir, "submit.sh", scripts.submit);
}

// Runs submit.sh and prints its job ids; its failure (no sbatch, a refused job) is one line.
void submit(const FarmJob& job) {
  const std::string command = "bash " + shell_quote(job.job_dir + "/submit.sh") + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw InputError("--submit", "cannot run submit.sh");
  std::string output, last;
  char line[512];
  while (std::fgets(line, sizeof line, pipe)) {
    output += line;
    last = line;
  }
  const int status = pclose(pipe);
  while (!last.empty() && (last.back() == '\n' || last.back() == '\r'))
    last.pop_back();
  if (status != 0)
    throw InputError("--submit",
                     job.job_dir + "/submit.sh failed: " + (last.empty() ? "no output" : last));
  std::fputs(output.c_str(), stdout);
}

void run_farm_slurm(const CLI::App& cmd, FarmOptions& o) {
  o.job.turntable_args = task_arguments(cmd);
  const TurntableChecks c = check_turntable_options(cmd, o.tt);
  resolve_view_options(o.tt.view);
  (void)load_scene_for_cli(o.tt.scene);  // a bad scene is an error here, not on the cluster
  o.job.frames = o.tt.path.frames;
  if (o.job.tasks < 1 || o.job.tasks > o.job.frames)
    throw InputError("--tasks", "must be in [1, " + std::to_string(o.job.frames) +
                                    "] (at most one task per frame), got " +
                                    std::to_string(o.job.tasks));
  check_slurm_values(o.job);
  place_outputs(o, c);
  o.job.sylva = fs::read_symlink("/proc/self/exe").string();
  o.job.fps = o.tt.fps;
  if (c.blobs && o.tt.keyframe_every > 1)
    o.job.keyframe_cache =
        o.tt.keyframe_cache.empty() ? o.job.job_dir + "/keys" : absolute(o.tt.keyframe_cache);
  else if (!o.tt.keyframe_cache.empty())
    o.job.turntable_args.insert(o.job.turntable_args.end(),
                                {"--keyframe-cache", absolute(o.tt.keyframe_cache)});
  const FarmScripts scripts = farm_scripts(o.job);
  write_job_folder(o.job, scripts);
  std::printf("wrote %s: %s%d render task(s) of %d frame(s)%s\n", o.job.job_dir.c_str(),
              scripts.keys.empty() ? "" : "keyframes, then ", o.job.tasks, o.job.frames,
              o.job.video.empty() ? "" : (", then encode to " + o.job.video).c_str());
  if (o.submit)
    submit(o.job);
  else
    std::printf("submit with: bash %s\n", shell_quote(o.job.job_dir + "/submit.sh").c_str());
}

}  // namespace

Action add_farm_command(CLI::App& app) {
  CLI::App* farm = app.add_subcommand(
      "farm", "Split a turntable into render-farm jobs (Slurm): scripts, and their submission");
  farm->require_subcommand(1);
  auto o = std::make_shared<FarmOptions>();
  o->tt.view.size = "512x512";
  CLI::App* cmd = farm->add_subcommand(
      "slurm",
      "Write a Slurm array job rendering a turntable in chunks of frames, then an encode job "
      "(and for keyframed blobs a keyframe job first); --submit submits them");
  add_turntable_options(*cmd, o->tt);
  cmd->add_option("--tasks", o->job.tasks,
                  "Array tasks, each a contiguous chunk of frames, "
                  "[1, frames]")
      ->required();
  cmd->add_option("--max-running", o->job.max_running,
                  "At most this many tasks at once (the array's %P); 0 = no limit")
      ->capture_default_str();
  cmd->add_option("--partition", o->job.partition, "Slurm partition (default: the cluster's)");
  cmd->add_option("--time", o->job.time, "Time limit per task, e.g. 30, 1:00:00 or 1-0");
  cmd->add_option("--mem", o->job.mem, "Memory per task, e.g. 4G");
  cmd->add_option("--cpus-per-task", o->job.cpus_per_task,
                  "CPUs per task, [1, 4096]; 0 = the cluster's default")
      ->capture_default_str();
  cmd->add_option("--job-dir", o->job_dir,
                  "Folder for the scripts, logs/ and (for a video) frames/; default OUT.farm/");
  cmd->add_flag("--submit", o->submit, "Submit the jobs (sbatch) and print their ids");
  return [o, cmd] { run_farm_slurm(*cmd, *o); };
}

}  // namespace sylva::cli

// Runs the sylva command as a child process for the benchmarks that time what a user runs
// (perf_instances, perf_gl_backends, perf_watercolor): its wall time, its peak resident memory
// (wait4's ru_maxrss, the child alone) and its exit status, with SYLVA_CACHE_DIR set to the
// benchmark's own cache folder.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

extern char** environ;

namespace sylva::perf {

struct ChildRun {
  double seconds = 0.0;
  long peak_kb = 0;
  int status = -1;  // the exit status, -1 when it did not start or did not exit
  bool ok() const { return status == 0; }
};

// `sylva args...`; quiet sends its output to /dev/null.
inline ChildRun run_sylva_child(const std::vector<std::string>& args, const std::string& cache_dir,
                                bool quiet) {
  std::vector<std::string> argv_s = {SYLVA_BINARY};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_s)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  setenv("SYLVA_CACHE_DIR", cache_dir.c_str(), 1);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  ChildRun r;
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, SYLVA_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return r;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.peak_kb = usage.ru_maxrss;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace sylva::perf

// The GL backends against each other (issue 34): `sylva render WILLOW --style ink --size 1024
// --gl BACKEND` as a user runs it, on the shared weeping willow, and `sylva info --gl BACKEND`
// (process start and context creation alone), each iteration a child process with a warm result
// cache; medians over the repetitions `make perf` asks for, both backends in one run. On llvmpipe
// both draw with the same rasteriser: the renders should take the same time, and EGL's context
// costs more to create (eglInitialize loads LLVM, ~0.1 s). A backend this sylva was not built
// with is skipped.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "tests/perf/perf_child.h"

namespace {

namespace fs = std::filesystem;

const fs::path& work_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("sylva-perf-gl-" + std::to_string(getpid()));
    fs::create_directories(d / "cache");
    return d;
  }();
  return dir;
}

// Runs `sylva args...` (output to /dev/null); its wall time in seconds, or -1 when it failed.
double run_sylva(const std::vector<std::string>& args) {
  const sylva::perf::ChildRun r =
      sylva::perf::run_sylva_child(args, (work_dir() / "cache").string(), true);
  return r.ok() ? r.seconds : -1;
}

void time_command(benchmark::State& state, const std::vector<std::string>& args) {
  // A first run per command, untimed: it fills the result cache and finds a backend not built.
  static std::set<std::vector<std::string>> warm;
  if (!warm.count(args)) {
    if (run_sylva(args) < 0) {
      state.SkipWithError("sylva failed (backend not built?)");
      return;
    }
    warm.insert(args);
  }
  for (auto _ : state) {
    const double s = run_sylva(args);
    if (s < 0) {
      state.SkipWithError("sylva failed");
      break;
    }
    state.SetIterationTime(s);
  }
}

void BM_RenderWillowInk1024(benchmark::State& state, const char* backend) {
  const std::string willow =
      std::string(SYLVA_SHARED_DIR) + "/assets/sapling_weeping_willow_s2.glb";
  const std::string out = (work_dir() / (std::string(backend) + ".png")).string();
  time_command(state,
               {"render", willow, "--style", "ink", "--size", "1024", "--gl", backend, "-o", out});
}

void BM_StartContext(benchmark::State& state, const char* backend) {
  time_command(state, {"info", "--gl", backend});
}

BENCHMARK_CAPTURE(BM_RenderWillowInk1024, egl, "egl")
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderWillowInk1024, osmesa, "osmesa")
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StartContext, egl, "egl")
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StartContext, osmesa, "osmesa")
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ec;
  fs::remove_all(work_dir(), ec);
  return 0;
}

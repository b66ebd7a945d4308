// Benchmarks for scenes of many plants (issue 18): `sylva render PARK --style ink --size 2048`
// as a user runs it, on parks (`sylva sample park`) of 1 to 4,000 instances of the shared ash
// (eztree_ash_medium_s5.glb, 20,000 triangles), the area growing with the count (about 70 units
// per tree, the ash's height) so the trees keep their spacing and the camera frames the whole
// park. Each iteration runs the command as a child process with a warm result cache (the Luft
// preprocessing of the one plant read back): its wall time is the iteration's time, and its
// peak resident memory (wait4's ru_maxrss) is kept. After the runs a summary prints, per count,
// the median time and the peak memory, the ratios of 400 instances to one (the issue asks at
// most 3x the time and 1.6x the memory), the peak at 4,000 (at most 2.5 GB), and the slope of
// log(time) over log(count) from 1 to 4,000 (least squares over every count, and the two ends
// alone): 0 would be a cost independent of the count, 1 a cost in proportion to it. The same
// for 1 and 400 instances drawn whole (--lod off) shows what the levels of detail buy.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tests/perf/perf_child.h"

namespace {

namespace fs = std::filesystem;

constexpr int kCounts[] = {1, 10, 100, 400, 1000, 4000};
constexpr double kSpacing = 70.0;  // scene units per tree (the ash is 71 tall, 65 wide)

struct Files {
  fs::path dir = fs::temp_directory_path() / ("sylva-perf-instances-" + std::to_string(getpid()));
  Files() { fs::create_directories(dir / "cache"); }
  ~Files() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string park(int count) const {
    return (dir / ("park-" + std::to_string(count) + ".glb")).string();
  }
};

Files& files() {
  static Files f;
  return f;
}

using Run = sylva::perf::ChildRun;

// Runs `sylva args...` as a child with the benchmark's cache folder.
Run run_sylva(const std::vector<std::string>& args) {
  return sylva::perf::run_sylva_child(args, (files().dir / "cache").string(), false);
}

std::vector<std::string> render_args(int count, bool lod = true) {
  return {"render",  files().park(count),
          "--style", "ink",
          "--size",  "2048",
          "--lod",   lod ? "on" : "off",
          "-o",      (files().dir / "out.png").string()};
}

// The park of `count` ashes, written once, and one render to fill the cache.
bool prepare(int count) {
  static std::map<int, bool> ready;
  if (ready.count(count)) return ready[count];
  const std::string side = std::to_string(kSpacing * std::sqrt(double(count)));
  const Run made =
      run_sylva({"sample", "park", "--plants",
                 std::string(SYLVA_SHARED_DIR) + "/assets/eztree_ash_medium_s5.glb", "--count",
                 std::to_string(count), "--area", side, "--seed", "1", "-o", files().park(count)});
  return ready[count] = made.status == 0 && run_sylva(render_args(count)).status == 0;
}

// Per level-of-detail setting (on, off) and count: the iterations' seconds and the peak.
std::map<bool, std::map<int, std::vector<double>>> g_seconds;
std::map<bool, std::map<int, long>> g_peak_kb;

void run_park(benchmark::State& state, bool lod) {
  const int count = int(state.range(0));
  if (!prepare(count)) {
    state.SkipWithError("sylva sample park or render failed");
    return;
  }
  long peak = 0;
  for (auto _ : state) {
    const Run r = run_sylva(render_args(count, lod));
    if (r.status != 0) {
      state.SkipWithError("sylva render failed");
      return;
    }
    state.SetIterationTime(r.seconds);
    g_seconds[lod][count].push_back(r.seconds);
    peak = std::max(peak, r.peak_kb);
  }
  g_peak_kb[lod][count] = std::max(g_peak_kb[lod][count], peak);
  state.counters["instances"] = count;
  state.counters["peak_rss_mb"] = double(peak) / 1024.0;
}

// The default (--lod on).
void BM_ParkInk2048(benchmark::State& state) {
  run_park(state, true);
}
// The instances drawn whole (--lod off), for what the levels of detail buy.
void BM_ParkInk2048NoLod(benchmark::State& state) {
  run_park(state, false);
}

BENCHMARK(BM_ParkInk2048)
    ->ArgsProduct({std::vector<int64_t>(std::begin(kCounts), std::end(kCounts))})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ParkInk2048NoLod)
    ->Arg(1)
    ->Arg(400)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void print_summary(bool lod) {
  std::map<int, double> med;
  for (const auto& [count, v] : g_seconds[lod])
    if (!v.empty()) med[count] = median(v);
  if (med.empty()) return;
  std::map<int, long>& peak = g_peak_kb[lod];
  std::printf("\nparks of the shared ash, ink at 2048x2048, --lod %s (median of %zu runs each)\n",
              lod ? "on" : "off", g_seconds[lod].begin()->second.size());
  std::printf("%10s %12s %14s\n", "instances", "median s", "peak RSS MB");
  for (const auto& [count, s] : med)
    std::printf("%10d %12.3f %14.1f\n", count, s, double(peak[count]) / 1024.0);
  if (med.count(1) && med.count(400))
    std::printf("400 vs 1 instance: time x%.2f (at most 3), peak memory x%.2f (at most 1.6)\n",
                med[400] / med[1], double(peak[400]) / double(peak[1]));
  if (peak.count(4000))
    std::printf("4000 instances: peak memory %.2f GB (at most 2.5)\n",
                double(peak[4000]) / (1024.0 * 1024.0));
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(med.size());
  for (const auto& [count, s] : med) {
    const double x = std::log(double(count)), y = std::log(s);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  if (med.size() >= 2)
    std::printf("log-log slope of time over instances: %.3f (least squares, %zu counts)",
                (n * sxy - sx * sy) / (n * sxx - sx * sx), med.size());
  if (med.count(1) && med.count(4000))
    std::printf(", %.3f (1 to 4000)", std::log(med[4000] / med[1]) / std::log(4000.0));
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary(true);
  print_summary(false);
  return 0;
}

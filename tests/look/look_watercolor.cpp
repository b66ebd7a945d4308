// Watercolor looks: discs and a synthetic tree (tests/passes/watercolor_scenes.h), with the
// pass's time on one thread and on all printed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <glm/glm.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "passes/watercolor.h"
#include "tests/look/look.h"
#include "tests/passes/watercolor_scenes.h"

namespace sylva::test {

namespace {

// CPU time of this process in ms: what a loaded machine still measures reliably.
double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// The median wall and CPU time of five watercolor() runs on 1 thread and on all, printed.
cv::Mat timed_watercolor(const WatercolorScene& s, const WatercolorParams& p) {
  const glm::mat4 identity(1.0f);
  (void)watercolor(s.img, identity, p);  // warm-up
  cv::Mat out;
  for (int threads : {1, cv::getNumberOfCPUs()}) {
    const int before = cv::getNumThreads();
    cv::setNumThreads(threads);
    std::vector<double> wall, cpu;
    for (int i = 0; i < 5; ++i) {
      const double c0 = cpu_ms();
      const auto t0 = std::chrono::steady_clock::now();
      out = watercolor(s.img, identity, p);
      wall.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      cpu.push_back(cpu_ms() - c0);
    }
    cv::setNumThreads(before);
    std::sort(wall.begin(), wall.end());
    std::sort(cpu.begin(), cpu.end());
    std::printf("watercolor %dx%d, %d thread(s): median wall %.1f ms, CPU %.1f ms\n", out.cols,
                out.rows, threads, wall[2], cpu[2]);
  }
  return out;
}

}  // namespace

// Three overlapping discs at three edge softnesses, and a synthetic 64-cluster tree plain, wet
// and with leaf detail, with 2x crops to judge grain, rims, wobble and detail.
void watercolor_look(const Save& save) {
  const glm::mat4 identity(1.0f);
  {
    WatercolorScene s = empty_scene({600, 450});
    add_disc(s, {230, 210}, 130, 1, {0.55f, 0.25f, 0.05f}, 6.0f);
    add_disc(s, {370, 230}, 120, 2, {0.05f, 0.35f, 0.75f}, 4.0f);
    add_disc(s, {300, 320}, 90, 3, {0.15f, 0.55f, 0.25f}, 3.0f);
    WatercolorParams p;
    save("discs.png", watercolor(s.img, identity, p));
    p.edge_softness = 1.0f;
    save("discs_soft.png", watercolor(s.img, identity, p));
    p.edge_softness = 0.0f;
    save("discs_hard.png", watercolor(s.img, identity, p));
    cv::Mat color;
    cv::cvtColor(s.img.color, color, cv::COLOR_BGRA2BGR);
    save("discs_input.png", color);
  }
  const WatercolorScene s = synthetic_tree({1024, 1024}, 64, 700, 11);
  cv::Mat color;
  cv::cvtColor(s.img.color, color, cv::COLOR_BGRA2BGR);
  save("tree_input.png", color);
  const cv::Rect crop(470, 280, 300, 300);
  auto zoom = [&](const cv::Mat& m) {
    cv::Mat z;
    cv::resize(m(crop), z, cv::Size(), 2, 2, cv::INTER_NEAREST);
    return z;
  };
  WatercolorParams p;
  p.reference_length = 3.0f;
  const cv::Mat out = timed_watercolor(s, p);
  save("tree.png", out);
  save("crop_tree.png", zoom(out));
  save("crop_input.png", zoom(color));
  p.edge_softness = 0.9f;
  p.blur = 8;
  const cv::Mat wet = watercolor(s.img, identity, p);
  save("tree_wet.png", wet);
  save("crop_wet.png", zoom(wet));
  p = WatercolorParams();
  p.reference_length = 3.0f;
  p.detail = 1.0f;
  p.blur = 3;
  const cv::Mat detailed = watercolor(s.img, identity, p);
  save("tree_detail.png", detailed);
  save("crop_detail.png", zoom(detailed));
}

}  // namespace sylva::test

// Passes that may run on any thread (RenderGraph::Threads::Any): two independent ones run at
// once, one ready beside a pass of the calling thread starts first and runs while it does, one
// that becomes ready while it runs starts then (the worker before it goes on with it), a pass
// still sees every input it reads written, the calling thread's passes run there, a pass's
// exception reaches the caller once the passes beside it have ended, and the values are those of
// running the passes in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/graph/render_graph.h"

namespace sylva {
namespace {

using Threads = RenderGraph::Threads;

// Waits (up to 10 s) until `flag` is set; true if it was.
bool wait_for(const std::atomic<bool>& flag) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!flag && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return flag;
}

TEST(RenderGraphThreads, TwoIndependentPassesRunAtOnce) {
  // Each pass waits for the other to have started: run one after the other, the first would
  // wait for the second in vain.
  RenderGraph g;
  const auto a = g.resource<int>("a"), b = g.resource<int>("b"), sum = g.resource<int>("sum");
  std::atomic<bool> a_started{false}, b_started{false};
  g.add_pass(
      "a", {}, {a},
      [&](PassContext& c) {
        a_started = true;
        c.write(a, wait_for(b_started) ? 1 : -100);
      },
      Threads::Any);
  g.add_pass(
      "b", {}, {b},
      [&](PassContext& c) {
        b_started = true;
        c.write(b, wait_for(a_started) ? 2 : -100);
      },
      Threads::Any);
  g.add_pass("sum", {a, b}, {sum},
             [&](PassContext& c) { c.write(sum, c.read<int>(a) + c.read<int>(b)); });
  g.present(sum);
  g.execute();
  EXPECT_EQ(g.get(sum), 3);
}

TEST(RenderGraphThreads, APassReadyBesideACallingThreadPassRunsWhileItDoes) {
  // "raster" (the calling thread's, declared first) waits for "beside" to have started: had it
  // run first, it would wait in vain, as "beside" would not start before it ended.
  RenderGraph g;
  const auto raster = g.resource<int>("raster"), beside = g.resource<int>("beside");
  const auto out = g.resource<int>("out");
  std::atomic<bool> beside_started{false};
  g.add_pass("raster", {}, {raster},
             [&](PassContext& c) { c.write(raster, wait_for(beside_started) ? 1 : -100); });
  g.add_pass(
      "beside", {}, {beside},
      [&](PassContext& c) {
        beside_started = true;
        c.write(beside, 2);
      },
      Threads::Any);
  g.add_pass("out", {raster, beside}, {out},
             [&](PassContext& c) { c.write(out, c.read<int>(raster) + c.read<int>(beside)); });
  g.present(out);
  g.execute();
  EXPECT_EQ(g.get(out), 3);
}

TEST(RenderGraphThreads, APassThatBecomesReadyWhileACallingThreadPassRunsStartsThen) {
  // "raster" (the calling thread's) waits for "late" to have started; "late" reads "early", which
  // starts beside "raster". The worker that ends "early" goes on with "late" itself: had it
  // waited for the calling thread to start it, "raster" would wait in vain.
  RenderGraph g;
  const auto early = g.resource<int>("early"), late = g.resource<int>("late");
  const auto raster = g.resource<int>("raster"), out = g.resource<int>("out");
  std::atomic<bool> late_started{false};
  g.add_pass("raster", {}, {raster},
             [&](PassContext& c) { c.write(raster, wait_for(late_started) ? 1 : -100); });
  g.add_pass(
      "early", {}, {early}, [&](PassContext& c) { c.write(early, 10); }, Threads::Any);
  g.add_pass(
      "late", {early}, {late},
      [&](PassContext& c) {
        late_started = true;
        c.write(late, c.read<int>(early) * 10);
      },
      Threads::Any);
  g.add_pass("out", {raster, late}, {out},
             [&](PassContext& c) { c.write(out, c.read<int>(raster) + c.read<int>(late)); });
  g.present(out);
  g.execute();
  EXPECT_EQ(g.get(out), 101);
}

TEST(RenderGraphThreads, APassSeesWhatItReadsAndMainPassesRunOnTheCallingThread) {
  // A chain a -> b -> c of passes on any thread beside a slow independent one, and a pass of
  // the calling thread at the end: every value is the one of running them in order.
  RenderGraph g;
  const auto a = g.resource<int>("a"), b = g.resource<int>("b"), c = g.resource<int>("c");
  const auto slow = g.resource<int>("slow"), out = g.resource<int>("out");
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id main_ran_on;
  g.add_pass(
      "a", {}, {a}, [&](PassContext& x) { x.write(a, 1); }, Threads::Any);
  g.add_pass(
      "slow", {}, {slow},
      [&](PassContext& x) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        x.write(slow, 100);
      },
      Threads::Any);
  g.add_pass(
      "b", {a}, {b}, [&](PassContext& x) { x.write(b, x.read<int>(a) * 10); }, Threads::Any);
  g.add_pass(
      "c", {b}, {c}, [&](PassContext& x) { x.write(c, x.read<int>(b) + 5); }, Threads::Any);
  g.add_pass("out", {c, slow}, {out}, [&](PassContext& x) {
    main_ran_on = std::this_thread::get_id();
    x.write(out, x.read<int>(c) + x.read<int>(slow));
  });
  g.present(out);
  std::vector<std::string> order;
  g.execute([&](const std::string& pass) { order.push_back(pass); });
  EXPECT_EQ(g.get(out), 115);
  EXPECT_EQ(main_ran_on, caller);
  ASSERT_EQ(order.size(), 5u);
  EXPECT_EQ(order.back(), "out");
  // "b" after "a" and "c" after "b", whatever ran beside them.
  const auto at = [&](const std::string& p) { return std::find(order.begin(), order.end(), p); };
  EXPECT_LT(at("a"), at("b"));
  EXPECT_LT(at("b"), at("c"));
}

TEST(RenderGraphThreads, AnExceptionReachesTheCallerOnceThePassesBesideItHaveEnded) {
  // "bad" fails at once while "slow", started beside it, still runs: execute() throws only
  // after "slow" has ended (its values are not left to a pass still writing them).
  RenderGraph g;
  const auto bad = g.resource<int>("bad"), slow = g.resource<int>("slow");
  const auto out = g.resource<int>("out");
  std::atomic<bool> slow_ended{false};
  g.add_pass(
      "bad", {}, {bad}, [](PassContext&) { throw std::runtime_error("bad pass"); }, Threads::Any);
  g.add_pass(
      "slow", {}, {slow},
      [&](PassContext& x) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        slow_ended = true;
        x.write(slow, 1);
      },
      Threads::Any);
  bool out_ran = false;
  g.add_pass("out", {bad, slow}, {out}, [&](PassContext& x) {
    out_ran = true;
    x.write(out, 0);
  });
  g.present(out);
  EXPECT_THROW(g.execute(), std::runtime_error);
  EXPECT_TRUE(slow_ended);
  EXPECT_FALSE(out_ran);
}

}  // namespace
}  // namespace sylva

// Keyframed blobs (Dudley 2005 §5.1): the keyframe schedule and its ends, Catmull-Rom through
// the keys (n = 1 is exact, linear motion stays linear), fades for blobs entering and leaving,
// the cross-fade of a depth-order swap, slices and the keyframe cache, and the cache format
// against hostile files.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "npr/blob_keyframes.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

// A blob of `n` control points on a circle of radius r around c.
BlobOutline blob(uint32_t cluster, glm::vec2 c, float r, float depth, int n = 8) {
  BlobOutline b;
  b.cluster = cluster;
  b.wrap.center = c;
  b.wrap.radius = r;
  for (int i = 0; i < n; ++i) {
    const float a = float(2 * M_PI * i / n);
    b.wrap.points.push_back(c + r * glm::vec2(std::sin(a), -std::cos(a)));
  }
  b.min_depth = depth;
  b.pixels = int(r * r);
  return b;
}

// Keyframe k (= frame k * every) of a scene where blob 1 moves right 10 px per keyframe.
std::vector<BlobOutline> moving(int frame, int every) {
  const float k = float(frame) / float(every);
  return {blob(1, {20 + 10 * k, 30}, 8, 2.0f), blob(2, {60, 30}, 6, 3.0f)};
}

TEST(BlobKeyframes, Schedule) {
  EXPECT_EQ(last_keyframe(12, 5), 3);  // keys at 0, 5, 10, 15 (>= frame 11)
  EXPECT_EQ(last_keyframe(11, 5), 2);  // 0, 5, 10 (= frame 10)
  EXPECT_EQ(last_keyframe(1, 5), 0);
  EXPECT_EQ(last_keyframe(5, 20), 1);  // n larger than the frame count: keys 0 and 20
  EXPECT_EQ(keys_needed(0, 5, 12), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(keys_needed(7, 5, 12), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(keys_needed(11, 5, 12), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(keys_needed(3, 20, 5), (std::vector<int>{0, 1}));
  EXPECT_EQ(test::where_of([] { (void)last_keyframe(10, 0); }), "--keyframe-every");
}

// The slices of any split own every keyframe exactly once (a farm's keys jobs fill the cache
// without computing a keyframe twice).
TEST(BlobKeyframes, SlicesOwnEachKeyframeOnce) {
  EXPECT_EQ(keys_owned(0, 6, 4, 24), (std::vector<int>{0, 1}));
  EXPECT_EQ(keys_owned(6, 12, 4, 24), (std::vector<int>{2}));
  EXPECT_EQ(keys_owned(18, 24, 4, 24), (std::vector<int>{5, 6}));  // 24 lies past the end
  EXPECT_EQ(keys_owned(1, 3, 4, 24), (std::vector<int>{}));
  for (int frames : {1, 5, 12, 24, 97})
    for (int every : {1, 2, 5, 20})
      for (int slices : {1, 2, 3, 7}) {
        if (slices > frames) continue;
        std::vector<int> owned;
        for (int t = 0; t < slices; ++t) {
          const std::vector<int> k =
              keys_owned(t * frames / slices, (t + 1) * frames / slices, every, frames);
          owned.insert(owned.end(), k.begin(), k.end());
        }
        std::vector<int> all(last_keyframe(frames, every) + 1);
        for (size_t i = 0; i < all.size(); ++i)
          all[i] = int(i);
        EXPECT_EQ(owned, all) << frames << " frames, every " << every << ", " << slices;
      }
}

TEST(BlobKeyframes, EveryFrameIsExactAndMotionStaysLinear) {
  const int frames = 9;
  // n = 1: every frame is its own keyframe, unchanged.
  BlobKeyframes each(frames, 1, [](int f) { return moving(f, 1); });
  for (int f = 0; f < frames; ++f) {
    const BlobSet s = each.frame(f);
    const std::vector<BlobOutline> want = moving(f, 1);
    ASSERT_EQ(s.blobs.size(), want.size());
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_EQ(s.blobs[i].wrap.points, want[i].wrap.points);
      EXPECT_EQ(s.blobs[i].min_depth, want[i].min_depth);
      EXPECT_EQ(s.blobs[i].opacity, 1.0f);
    }
    EXPECT_EQ(s.order, painter_order(want));
    EXPECT_EQ(s.fade, 0.0f);
  }
  EXPECT_EQ(each.computed(), frames);
  // n = 4: frames between keys follow the linear motion exactly (Catmull-Rom reproduces
  // straight lines, also at the reflected ends).
  BlobKeyframes keyed(frames, 4, [](int f) { return moving(f, 4); });
  for (int f = 0; f < frames; ++f) {
    const BlobSet s = keyed.frame(f);
    EXPECT_NEAR(s.blobs[0].wrap.center.x, 20 + 10 * f / 4.0f, 1e-4f) << f;
    EXPECT_NEAR(s.blobs[0].wrap.points[2].x, 28 + 10 * f / 4.0f, 1e-3f) << f;
  }
  EXPECT_EQ(keyed.computed(), 3);  // keys 0, 4, 8
}

TEST(BlobKeyframes, EnteringBlobFadesAndOrderSwapCrossFades) {
  // Key 0: blob 1 in front; key 1: blob 2 in front, blob 3 appears.
  auto compute = [](int f) {
    if (f == 0)
      return std::vector<BlobOutline>{blob(1, {20, 20}, 8, 1.0f), blob(2, {26, 20}, 8, 2.0f)};
    return std::vector<BlobOutline>{blob(1, {20, 20}, 8, 3.0f), blob(2, {26, 20}, 8, 2.0f),
                                    blob(3, {50, 50}, 5, 4.0f)};
  };
  BlobKeyframes k(5, 4, compute);  // keys at 0 and 4
  for (int f = 0; f < 5; ++f) {
    const BlobSet s = k.frame(f);
    const float u = f / 4.0f;
    if (f == 0) {
      EXPECT_EQ(s.blobs.size(), 2u);  // blob 3 not yet there
    } else {
      ASSERT_EQ(s.blobs.size(), 3u);
      EXPECT_NEAR(s.blobs[2].opacity, f == 4 ? 1.0f : u, 1e-6f);
      for (size_t i = 0; i < s.blobs[2].wrap.points.size(); ++i)  // the borrowed shape
        EXPECT_NEAR(glm::length(s.blobs[2].wrap.points[i] - compute(4)[2].wrap.points[i]), 0.0f,
                    1e-4f);
    }
    if (f > 0 && f < 4) {
      EXPECT_NE(s.order, s.next_order);
      EXPECT_NEAR(s.fade, u, 1e-6f);
    } else {
      EXPECT_EQ(s.fade, 0.0f);
    }
  }
}

TEST(BlobKeyframes, SlicesAndCacheMatchTheFullRun) {
  const int frames = 23, every = 5;
  int calls = 0;
  auto compute = [&](int f) {
    ++calls;
    return moving(f, every);
  };
  BlobKeyframes full(frames, every, compute);
  std::vector<BlobSet> all;
  for (int f = 0; f < frames; ++f)
    all.push_back(full.frame(f));
  const std::string dir = test::temp_dir("blob-keys");
  BlobKeyframes slice(frames, every, compute, dir, "sig A");
  for (int f = 12; f < 17; ++f) {
    const BlobSet s = slice.frame(f);
    ASSERT_EQ(s.blobs.size(), all[f].blobs.size());
    for (size_t i = 0; i < s.blobs.size(); ++i)
      EXPECT_EQ(s.blobs[i].wrap.points, all[f].blobs[i].wrap.points) << f;
  }
  EXPECT_EQ(slice.computed(), 5);  // keys 1 .. 5 for frames 12 .. 16
  // Another job with the same cache reads the keys instead of computing them...
  BlobKeyframes again(frames, every, compute, dir, "sig A");
  const BlobSet s = again.frame(14);
  EXPECT_EQ(again.computed(), 0);
  EXPECT_EQ(again.read(), 4);
  EXPECT_EQ(s.blobs[0].wrap.points, all[14].blobs[0].wrap.points);
  // ...unless the cache was made for something else.
  BlobKeyframes other(frames, every, compute, dir, "sig B");
  (void)other.frame(14);
  EXPECT_EQ(other.computed(), 4);
  EXPECT_EQ(other.read(), 0);
}

TEST(BlobKeyframes, CacheFormatRoundTripsAndRejectsHostileFiles) {
  std::vector<BlobOutline> blobs = {blob(3, {1.25f, 2.5f}, 3.1f, 0.123456789f),
                                    blob(9, {100.0f / 3, 7}, 2, 5)};
  blobs[1].opacity = 0.3f;
  const std::vector<BlobOutline> back = parse_blob_outlines(format_blob_outlines(blobs), "f");
  ASSERT_EQ(back.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].cluster, blobs[i].cluster);
    EXPECT_EQ(back[i].wrap.points, blobs[i].wrap.points);
    EXPECT_EQ(back[i].wrap.center, blobs[i].wrap.center);
    EXPECT_EQ(back[i].min_depth, blobs[i].min_depth);
    EXPECT_EQ(back[i].opacity, blobs[i].opacity);
  }
  for (const char* bad : {"", "blobs", "blobs 2\n1 1 1 1 1 1 1 0\n", "blobs 1\n1 1 nan 1 1 1 1 0\n",
                          "blobs 1\n1 1 1 1 1 1 1 3 1 2\n", "blobs 99999999999\n",
                          "blobs 2\n5 1 1 1 1 1 1 0\n5 1 1 1 1 1 1 0\n", "garbage"})
    EXPECT_EQ(test::where_of([&] { (void)parse_blob_outlines(bad, "key.txt"); }), "key.txt") << bad;
}

}  // namespace
}  // namespace sylva

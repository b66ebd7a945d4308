// The plant's tone as the illustrator reads it (issue "Pen-and-ink that depicts the tree"): how
// dark each place of the plant is among all of its places, so that every plant, a dark conifer
// or a light aspen, gets the same share of lit, half-shadow and deep shadow. The darkness is
// 1 - the Rec. 709 luma of the shaded colour target (for the ink styles Luft et al.'s Eq. 1 with
// the realigned normals and the density ka), averaged over the plant with a Gaussian at the
// picture's scale (crown parts, not the leaves, whose shading changes as they turn), and
// replaced by its rank among the plant's pixels.
//
// Reads a CV_8UC4 colour (alpha = coverage); writes CV_32FC1 images.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace sylva {

// The darkness of a colour image (before smoothing): CV_32FC1 in [0, 1], 0 off the plant
// (alpha < 128).
cv::Mat tone_darkness(const cv::Mat& color);

struct ToneRank {
  cv::Mat plant;  // CV_8UC1 at the working size, 255 = on the plant (area coverage >= 1/2)
  // CV_32FC1 the smoothed darkness, [0, 1]; unranked with a wide Gaussian, at half the working
  // size (dark_near reads it bilinearly).
  cv::Mat dark;
  // CV_32FC1 the darkness area-averaged to the working size, not smoothed (0 off the plant).
  cv::Mat darkness;
  // The plant's smoothed darkness, ascending (empty unless ranked): what a rank is taken among.
  std::vector<float> sorted;
  bool empty() const { return dark.empty(); }
  // The rank of the smoothed darkness at `at` (px at the working size, clamped to it), on the
  // plant or beside it.
  float rank_near(cv::Point2f at) const;
  // The smoothed darkness at `at` (px at the working size, clamped to it).
  float dark_near(cv::Point2f at) const;
  float rank_of(float darkness) const;
};

// At `size` (a working resolution of the colour's frame): the darkness area-averaged to `size`,
// smoothed over the plant by a Gaussian of `sigma` px (at `size`), and, when `ranked`, the
// plant's darkness sorted for its ranks (without it rank_near and rank_of answer 0: for callers
// that read dark_near only; a Gaussian of sigma >= 3 px is then computed at half the size, a
// quarter of the work). Empty when no pixel is on the plant.
ToneRank tone_rank(const cv::Mat& color, cv::Size size, double sigma, bool ranked = true);

}  // namespace sylva

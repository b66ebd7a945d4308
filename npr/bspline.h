// Uniform cubic splines for blob outlines and their animation (Dudley 2005 §4.2.1, §5.1).
// A closed uniform cubic B-spline smooths a blob's control polygon into its outline (it
// approximates the control points, C2 everywhere); a Catmull-Rom spline, the cubic that
// passes through its points, interpolates control points between keyframes, so a keyframe
// interval of 1 reproduces the per-frame outlines exactly.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace sylva {

// Point of the closed uniform cubic B-spline with control points p (indices taken modulo
// p.size()) at parameter t; segment i spans t in [i, i + 1) and is shaped by p[i - 1 .. i + 2].
// t is taken modulo p.size(). p must not be empty.
glm::vec2 closed_bspline_point(const std::vector<glm::vec2>& p, double t);

// The closed B-spline sampled at `samples_per_segment` (>= 1) evenly spaced parameters per
// control point, starting at t = 0; the polygon is closed implicitly (last joins first).
std::vector<glm::vec2> sample_closed_bspline(const std::vector<glm::vec2>& p,
                                             int samples_per_segment);

// Uniform Catmull-Rom interpolation of a sequence: the point at parameter t in [0, n - 1]
// passing through keys[i] at t = i. The ends are defined by reflecting the neighbour
// (keys[-1] = 2 keys[0] - keys[1], keys[n] = 2 keys[n-1] - keys[n-2]), so a sequence of two
// keys is interpolated linearly and one key is constant. t outside the range is clamped.
glm::vec2 catmull_rom(const std::vector<glm::vec2>& keys, double t);
float catmull_rom(const std::vector<float>& keys, double t);

}  // namespace sylva

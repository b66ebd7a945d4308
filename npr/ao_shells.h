// The occluder shells of Hegeman et al.'s approximate ambient occlusion (§3 and §5), fitted
// to the foliage vertices: one bounding sphere, one bounding ellipsoid from the principal
// axes, or k shells from k-means where a point uses the shell whose centre is nearest.
// The visibility model that reads these shells is npr/hegeman_ao.h. All lengths are in
// scene units.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

// Shells are the scene's Sphere (core/scene/scene.h): a fitted one has radius >= 0 (0 = a
// single distinct point); a default-constructed one (radius < 0) is empty and occludes
// nothing.

// The solid ellipsoid { centre + axes * (radii * u) : |u| <= 1 }.
struct Ellipsoid {
  glm::vec3 centre{0.0f};
  glm::mat3 axes{1.0f};   // columns: orthonormal, right-handed directions of the semi-axes
  glm::vec3 radii{0.0f};  // semi-axis lengths along the columns of `axes`, scene units, >= 0
};

// A sphere as the ellipsoid with three equal semi-axes along x, y, z.
Ellipsoid as_ellipsoid(const Sphere& sphere);

// The exact minimal enclosing sphere: Welzl's algorithm in Gärtner's move-to-front form with
// pivoting ("Fast and robust smallest enclosing balls", ESA 1999), in double precision, on a
// shuffle of the points with a fixed seed (expected linear time; recursion depth <= 4).
// Chosen over Ritter's approximation, which can be ~5% too large. Tightness: the optimum up
// to rounding; the radius is then recomputed as the largest distance from the stored float
// centre and padded by a few float ulps, so every input point is inside in float
// arithmetic (excess over the optimum: relative ~1e-6). A single distinct point gives
// radius 0. Throws InputError("foliage vertices", ...) for an empty set or a non-finite
// point.
Sphere fit_bounding_sphere(const std::vector<glm::vec3>& points);

// No semi-axis of a fitted ellipsoid is thinner than this share of its largest one, so
// coplanar or collinear foliage still gets a shell with volume, and mapping into the unit
// sphere (npr/hegeman_ao.h) never divides by zero.
inline constexpr float kMinEllipsoidAxisRatio = 0.01f;

// Bounding ellipsoid from the principal axes (PCA): the eigenvectors of the points'
// covariance (double precision, cv::eigen), sorted by decreasing variance, each signed so its
// largest component is positive and the frame made right-handed, give the directions. The
// centre is the middle of the points' extent along each axis (the oriented bounding box's
// centre: tighter than the mean for lopsided crowns). The semi-axes are proportional to the
// standard deviations along the axes, each at least kMinEllipsoidAxisRatio of the largest,
// scaled by the one factor that puts the farthest point on the surface (then padded by a
// relative 1e-5 so float evaluations keep every point inside). Not the minimum-volume
// ellipsoid: for points filling a box the semi-axes are about sqrt(3) times its half
// extents; for points filling a ball it is close to the bounding sphere. All points equal:
// radii 0 (no volume), axes identity. Throws InputError("foliage vertices", ...) for an
// empty set or a non-finite point.
Ellipsoid fit_bounding_ellipsoid(const std::vector<glm::vec3>& points);

enum class ShellKind : uint8_t { Sphere = 0, Ellipsoid = 1 };

struct ShellOptions {
  int shells = 1;                      // k, [1, 64]
  ShellKind kind = ShellKind::Sphere;  // the shape of each shell
  uint64_t seed = 1;                   // k-means++ seeding
};

// Throws InputError("ao-shells", ...) for k outside [1, 64].
void validate_shell_options(const ShellOptions& options);

// k shells (Hegeman et al. §5). Each shell is the bounding sphere (fit_bounding_sphere) or
// bounding ellipsoid (fit_bounding_ellipsoid) of one k-means cluster of the vertices.
// The "centre" a point is matched to is the cluster's k-means centre (`anchors`), not the
// shell's geometric centre: every input vertex then uses the shell of its own cluster, which
// encloses it. (Matching by the shells' own centres would hand some vertices to a shell
// that does not contain them.)
struct Shells {
  std::vector<Ellipsoid> shells;
  std::vector<glm::vec3> anchors;  // one per shell: the centre the nearest-centre rule uses
  std::vector<uint32_t> labels;    // per input vertex: the shell it belongs to

  // Index of the shell whose anchor is nearest to p (lowest index on ties). Non-finite p
  // gets shell 0. Needs at least one shell.
  size_t nearest(const glm::vec3& p) const;
};

// k-means (Lloyd's algorithm in double precision, k-means++ seeding from a splitmix64 stream
// of `seed`, at most 100 iterations or until no label changes; an emptied cluster is
// re-seeded with the point farthest from its centre). Deterministic: the same points and
// options give the same bytes. k larger than the number of distinct points is clamped to
// that number (each distinct point then gets its own cluster; exact float equality decides
// distinctness), so shells.size() may be smaller than options.shells. Above 20,000 vertices
// the centres are fitted on an evenly strided sample, then every vertex takes its nearest
// centre. k = 1 gives exactly fit_bounding_sphere / fit_bounding_ellipsoid of all points.
// Throws InputError as validate_shell_options and fit_bounding_sphere do.
Shells fit_shells(const std::vector<glm::vec3>& points, const ShellOptions& options);

}  // namespace sylva

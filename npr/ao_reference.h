// The ray-traced ambient visibility that Hegeman et al. compare against (§3, Fig. 2, §4:
// "a standard raytracer (128 directions over a hemisphere)"): the share of rays from a point
// over the hemisphere around its normal that leave the scene, the Monte Carlo estimate of
// Eq. 3's ambient visibility 1/(2 pi) * integral of V over the hemisphere, uniform in solid
// angle (not cosine-weighted). Embree 3 (occlusion rays, any hit) over a triangle soup; an
// optional hit filter lets alpha-cutout leaves pass rays through their transparent texels.
// Meant for fitting alpha_rho (npr/ao_fit.h) and as the AO accuracy reference of tradeoffs.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace sylva {

// Whether a hit on `triangle` at Embree's barycentrics (u, v) blocks the ray: the hit point
// is (1 - u - v) p0 + u p1 + v p2 of the triangle's vertices in index order. Called from
// several threads at once, so it must be thread-safe, and must not throw (an exception
// counts as a blocking hit). An empty filter: every hit blocks.
using AoHitFilter = std::function<bool(uint32_t triangle, float u, float v)>;

// Alpha cutout on top of AoHitFilter: the per-vertex uvs are interpolated at the hit with the
// barycentrics, `alpha(triangle, uv)` returns the coverage there (e.g. a texture lookup),
// and the hit blocks when coverage >= cutoff (glTF MASK semantics; cutoff in [0, 1]).
// Triangles for which `is_cutout(triangle)` is false (e.g. wood) always block; an empty
// is_cutout tests every triangle. uvs has one entry per vertex, indices 3 per triangle (the
// same arrays the scene is built from); they are copied into the filter.
AoHitFilter make_alpha_cutout_filter(std::vector<glm::vec2> uvs, std::vector<uint32_t> indices,
                                     std::function<float(uint32_t triangle, glm::vec2 uv)> alpha,
                                     float cutoff,
                                     std::function<bool(uint32_t triangle)> is_cutout = {});

struct AoReferenceOptions {
  int rays = 64;      // rays per point, [1, 4096]
  uint64_t seed = 1;  // the same seed gives the same directions, for any thread count
  // Ray origins move this far along the normal and rays start at this distance, so a point
  // on a leaf does not hit its own leaf. Scene units, finite, >= 0; 0 = auto:
  // 1e-5 * (bounding-box diagonal + largest absolute coordinate), a few hundred float ulps
  // of the coordinates and far below a leaf's size.
  float origin_offset = 0.0f;
  int threads = 0;  // OpenMP threads, [0, 1024]; 0 = OpenMP's default
};

// Throws InputError("ao-rays" / "ao-origin-offset" / "ao-threads", ...) naming the range.
void validate_ao_reference(const AoReferenceOptions& options);

class AoReferenceScene {
 public:
  // positions: world space; indices: 3 per triangle (checked: SYLVA_CHECK), each < positions
  // size. Builds Embree's BVH (medium quality). Throws InputError("scene", ...) for a
  // non-finite vertex. An empty triangle list is allowed: every ray escapes.
  AoReferenceScene(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                   AoHitFilter filter = {});
  ~AoReferenceScene();
  AoReferenceScene(AoReferenceScene&&) noexcept;
  AoReferenceScene& operator=(AoReferenceScene&&) noexcept;

  size_t triangle_count() const;
  float auto_origin_offset() const;

  // V at each point, in [0, 1] in steps of 1/rays, in parallel (OpenMP). Directions: for ray
  // j of N, cos(theta) = (j + xi_j) / N (stratified, xi_j jittered per ray) and
  // phi = 2 pi frac(j / golden ratio + s) (a golden-ratio lattice with a per-point random
  // shift s), around the unit normal; the random numbers come from splitmix64 keyed by
  // (seed, point index), so results do not depend on the thread count or schedule.
  // A zero or non-finite normal samples the whole sphere (cos(theta) in [-1, 1], no origin
  // offset): the mean of the two hemispheres. A non-finite point gets 1.
  // normals.size() must equal points.size() (SYLVA_CHECK). Throws as validate_ao_reference.
  std::vector<float> visibility(const std::vector<glm::vec3>& points,
                                const std::vector<glm::vec3>& normals,
                                const AoReferenceOptions& options) const;

  // One point; `stream` plays the role of the point index above.
  float visibility_at(const glm::vec3& point, const glm::vec3& normal,
                      const AoReferenceOptions& options, uint64_t stream) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace sylva

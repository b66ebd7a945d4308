#include "npr/realign.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>

#include "core/error.h"

namespace sylva {

namespace {

// nanoflann dataset adaptor over the surface positions. Coordinates are served as double so
// that squared distances are computed in double: float positions differ by amounts a double
// holds (nearly always exactly), and near-ties are then decided on a much finer value.
struct PositionCloud {
  const std::vector<glm::vec3>& positions;
  size_t kdtree_get_point_count() const { return positions.size(); }
  double kdtree_get_pt(size_t idx, size_t dim) const {
    return static_cast<double>(positions[idx][static_cast<glm::length_t>(dim)]);
  }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const {
    return false;  // let nanoflann compute it
  }
};

using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PositionCloud>,
                                        PositionCloud, 3, uint32_t>;

// A one-nearest result set that breaks ties towards the lower index. nanoflann's own
// KNNResultSet keeps the first point found at the smallest distance, which depends on the
// tree layout, and its search only offers points strictly closer than worstDist(). So
// worstDist() is reported slightly above the best distance: tied points (and cells that may
// hold them, despite rounding in nanoflann's incremental cell distances) are still visited,
// and addPoint() decides exactly.
class NearestLowestIndex {
 public:
  using DistanceType = double;
  using IndexType = uint32_t;
  using CountType = size_t;

  // Starts from a known point and its distance (computed as nanoflann does: the squared
  // differences summed x, y, z in double), so the search prunes from the first cell on; the
  // answer is the same as without it.
  void start_from(double dist, uint32_t index) {
    m_found = true;
    m_dist = dist;
    m_index = index;
  }

  bool addPoint(double dist, uint32_t index) {
    if (!m_found || dist < m_dist || (dist == m_dist && index < m_index)) {
      m_found = true;
      m_dist = dist;
      m_index = index;
    }
    return true;  // keep searching: a tie may still come
  }
  double worstDist() const {
    if (!m_found) return std::numeric_limits<double>::max();
    // Relative slack far above the rounding of a 3-term squared distance, far below any
    // difference that matters; the absolute term lets exact duplicates (distance 0) through.
    return m_dist * (1.0 + 1e-9) + std::numeric_limits<double>::denorm_min();
  }
  bool full() const { return m_found; }
  size_t size() const { return m_found ? 1 : 0; }
  bool found() const { return m_found; }
  uint32_t index() const { return m_index; }

 private:
  bool m_found = false;
  double m_dist = 0.0;
  uint32_t m_index = 0;
};

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Unit vector along v in double, robust to tiny and huge components (scales by the largest
// component before squaring). False when v is zero or not finite.
bool unit_direction(const glm::dvec3& v, glm::dvec3& out) {
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))) return false;
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0.0)) return false;
  const glm::dvec3 s = v / m;
  out = s / glm::length(s);
  return true;
}

}  // namespace

std::vector<glm::vec3> nearest_surface_normals(const SurfaceMesh& surface,
                                               const std::vector<glm::vec3>& points) {
  SYLVA_CHECK(!surface.positions.empty(), "the surface has no vertices");
  SYLVA_CHECK(surface.normals.size() == surface.positions.size(), "one normal per surface vertex");
  SYLVA_CHECK(surface.positions.size() <= std::numeric_limits<uint32_t>::max(),
              "surface vertex count fits 32-bit indices");
  for (const glm::vec3& p : surface.positions) {
    SYLVA_CHECK(finite(p), "surface positions are finite");
  }

  const PositionCloud cloud{surface.positions};
  // Leaf size 10: nanoflann's usual sweet spot for 3-D single-nearest queries.
  const KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));

  std::vector<glm::vec3> out(points.size());
  const int64_t n = static_cast<int64_t>(points.size());
  // Each iteration writes only out[i] and the tree is read-only: deterministic for any
  // thread count. Consecutive points (a leaf's corners) are near each other, so each search
  // starts from the previous one's answer: exact still, but deep points inside the crown,
  // far from the surface, no longer wander through the tree's empty interior cells first.
#pragma omp parallel
  {
    uint32_t hint = 0;
#pragma omp for schedule(dynamic, 1024)
    for (int64_t i = 0; i < n; ++i) {
      const glm::vec3& p = points[static_cast<size_t>(i)];
      const double query[3] = {p.x, p.y, p.z};
      NearestLowestIndex result;
      if (finite(p)) {
        double d = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double diff = query[k] - static_cast<double>(surface.positions[hint][k]);
          d += diff * diff;
        }
        result.start_from(d, hint);
      }
      tree.findNeighbors(result, query, nanoflann::SearchParams());
      // Luft et al. §3.3: N' is the normal N_s of the surface vertex v_s nearest to v. A point
      // with an infinite or NaN coordinate is equally far from every vertex (or incomparable):
      // nothing is found and it takes vertex 0, the lowest index, as any full tie does.
      const uint32_t nearest = result.found() ? result.index() : 0;
      out[static_cast<size_t>(i)] = surface.normals[nearest];
      hint = nearest;
    }
  }
  return out;
}

glm::vec3 blend_normal(const glm::vec3& n, const glm::vec3& ns, float blend) {
  // Luft et al. §3.3: "N' is computed as a linear combination of the original normal vector N
  // of v and N_s". Computed in double, so float overflow and underflow cannot occur.
  const double b = blend;
  const glm::dvec3 dn(n);
  const glm::dvec3 dns(ns);
  const glm::dvec3 sum = (1.0 - b) * dn + b * dns;
  // The sum "vanishes" when it is small against the weighted inputs: then its direction is
  // decided by the inputs' rounding (nearly opposite normals at blend 0.5), not by them.
  const double scale = std::abs(1.0 - b) * glm::length(dn) + std::abs(b) * glm::length(dns);
  glm::dvec3 dir;
  if (std::isfinite(scale) && glm::length(sum) > 1e-6 * scale && unit_direction(sum, dir)) {
    return glm::vec3(dir);
  }
  if (unit_direction(dns, dir)) return glm::vec3(dir);
  if (unit_direction(dn, dir)) return glm::vec3(dir);
  // Neither input has a direction: any unit vector keeps the promise of a finite unit
  // result; +z is the one a flat, camera-facing default would give.
  return glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace sylva

#include "npr/ao_shells.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <list>
#include <opencv2/core.hpp>
#include <string>

#include "core/error.h"
#include "core/random.h"

namespace sylva {
namespace {

// k-means centres are fitted on at most this many distinct points (see fit_shells).
constexpr size_t kMaxKMeansPoints = 20000;
constexpr int kMaxKMeansIterations = 100;
// Fixed seed of the shuffle in front of the move-to-front miniball: any order gives the same
// ball, a random one gives the expected linear running time.
constexpr uint64_t kSphereShuffleSeed = 0x5eed5eed5eedull;

void check_points(const std::vector<glm::vec3>& points) {
  if (points.empty()) throw InputError("foliage vertices", "need at least one vertex, got none");
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::vec3& p = points[i];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
      throw InputError("foliage vertices", "vertex " + std::to_string(i) + " is not finite");
  }
}

// Rounds a non-negative length to float and pads it by `rel` so that distances up to `r`
// evaluated in float arithmetic (a few ulps of error) still compare <= the result.
float padded_length(double r, double rel) {
  if (!(r > 0.0)) return 0.0f;
  const float f = float(r * (1.0 + rel));
  return std::nextafter(f, std::numeric_limits<float>::infinity());
}

// Gärtner's move-to-front miniball with pivoting (ESA 1999), d = 3, double precision.
class Miniball {
 public:
  explicit Miniball(std::list<glm::dvec3> points) : m_points(std::move(points)) {
    m_current_c = glm::dvec3(0.0);
    m_current_sqr_r = -1.0;
    pivot_mb(m_points.end());
  }
  glm::dvec3 centre() const { return m_current_c; }

 private:
  using It = std::list<glm::dvec3>::iterator;

  double excess(const glm::dvec3& p) const {
    const glm::dvec3 e = p - m_current_c;
    return glm::dot(e, e) - m_current_sqr_r;
  }

  // Adds p to the set of points forced onto the boundary; false when p is (numerically)
  // affinely dependent on the points already there.
  bool push(const glm::dvec3& p) {
    const int m = m_forced;
    if (m == 0) {
      m_q0 = p;
      m_c[0] = p;
      m_sqr_r[0] = 0.0;
    } else {
      m_v[m] = p - m_q0;
      for (int i = 1; i < m; ++i)
        m_a[m][i] = 2.0 * glm::dot(m_v[i], m_v[m]) / m_z[i];
      for (int i = 1; i < m; ++i)
        m_v[m] -= m_a[m][i] * m_v[i];
      m_z[m] = 2.0 * glm::dot(m_v[m], m_v[m]);
      if (m_z[m] < 1e-32 * m_current_sqr_r) return false;
      const glm::dvec3 e0 = p - m_c[m - 1];
      const double e = glm::dot(e0, e0) - m_sqr_r[m - 1];
      m_f[m] = e / m_z[m];
      m_c[m] = m_c[m - 1] + m_f[m] * m_v[m];
      m_sqr_r[m] = m_sqr_r[m - 1] + e * m_f[m] / 2.0;
    }
    m_current_c = m_c[m];
    m_current_sqr_r = m_sqr_r[m];
    ++m_forced;
    return true;
  }
  void pop() { --m_forced; }

  void move_to_front(It j) {
    if (m_support_end == j) ++m_support_end;
    m_points.splice(m_points.begin(), m_points, j);
  }

  void mtf_mb(It end) {
    m_support_end = m_points.begin();
    if (m_forced == 4) return;
    for (It k = m_points.begin(); k != end;) {
      It j = k++;
      if (excess(*j) > 0.0 && push(*j)) {
        mtf_mb(j);
        pop();
        move_to_front(j);
      }
    }
  }

  void pivot_mb(It end) {
    It t = std::next(m_points.begin());
    mtf_mb(t);
    double max_e = 0.0, old_sqr_r = -1.0;
    do {
      It pivot = m_points.begin();
      max_e = 0.0;
      for (It k = t; k != end; ++k) {
        const double e = excess(*k);
        if (e > max_e) max_e = e, pivot = k;
      }
      if (max_e > 0.0) {
        t = m_support_end;
        if (t == pivot) ++t;
        old_sqr_r = m_current_sqr_r;
        if (!push(*pivot)) break;
        mtf_mb(m_support_end);
        pop();
        move_to_front(pivot);
      }
    } while (max_e > 0.0 && m_current_sqr_r > old_sqr_r);
  }

  std::list<glm::dvec3> m_points;
  It m_support_end;
  int m_forced = 0;
  glm::dvec3 m_q0{0.0};
  glm::dvec3 m_v[4], m_c[4];
  double m_z[4] = {}, m_f[4] = {}, m_a[4][4] = {}, m_sqr_r[4] = {};
  glm::dvec3 m_current_c{0.0};
  double m_current_sqr_r = -1.0;
};

glm::dvec3 bounds_centre(const std::vector<glm::vec3>& points) {
  glm::dvec3 lo(points[0]), hi(points[0]);
  for (const glm::vec3& p : points) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  return 0.5 * (lo + hi);
}

// Lexicographic order of positions (for deduplication).
bool less_xyz(const glm::vec3& a, const glm::vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

size_t nearest_index(const std::vector<glm::vec3>& anchors, const glm::vec3& p) {
  size_t best = 0;
  float best_d = std::numeric_limits<float>::infinity();
  for (size_t c = 0; c < anchors.size(); ++c) {
    const glm::vec3 e = p - anchors[c];
    const float d = glm::dot(e, e);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

// Lloyd's k-means on `pts` (distinct points), k <= pts.size(). Returns the centres.
std::vector<glm::dvec3> kmeans(const std::vector<glm::dvec3>& pts, size_t k, uint64_t seed) {
  const size_t n = pts.size();
  uint64_t rng = seed;
  std::vector<glm::dvec3> centres;
  centres.reserve(k);
  // k-means++ (Arthur & Vassilvitskii 2007): D^2 sampling. Distinct points keep every chosen
  // centre distinct: a chosen point has weight 0 afterwards.
  centres.push_back(pts[std::min(n - 1, size_t(uniform01(rng) * double(n)))]);
  std::vector<double> d2(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 e = pts[i] - centres[0];
    d2[i] = glm::dot(e, e);
  }
  while (centres.size() < k) {
    double total = 0.0;
    for (double w : d2)
      total += w;
    const double target = uniform01(rng) * total;
    size_t pick = n;
    double acc = 0.0;
    for (size_t i = 0; i < n; ++i) {
      acc += d2[i];
      if (d2[i] > 0.0 && acc > target) {
        pick = i;
        break;
      }
    }
    if (pick == n)  // rounding at the end of the sum: the last point with weight
      for (size_t i = n; i-- > 0;)
        if (d2[i] > 0.0) {
          pick = i;
          break;
        }
    SYLVA_CHECK(pick < n, "k-means++ needs k <= distinct points");
    centres.push_back(pts[pick]);
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 e = pts[i] - pts[pick];
      d2[i] = std::min(d2[i], glm::dot(e, e));
    }
  }

  std::vector<size_t> label(n, k);
  std::vector<double> dist(n, 0.0);
  for (int it = 0; it < kMaxKMeansIterations; ++it) {
    bool changed = false;
    for (size_t i = 0; i < n; ++i) {
      size_t best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (size_t c = 0; c < k; ++c) {
        const glm::dvec3 e = pts[i] - centres[c];
        const double d = glm::dot(e, e);
        if (d < best_d) best_d = d, best = c;
      }
      if (label[i] != best) changed = true;
      label[i] = best;
      dist[i] = best_d;
    }
    std::vector<glm::dvec3> sum(k, glm::dvec3(0.0));
    std::vector<size_t> count(k, 0);
    for (size_t i = 0; i < n; ++i) {
      sum[label[i]] += pts[i];
      ++count[label[i]];
    }
    for (size_t c = 0; c < k; ++c) {
      if (count[c] > 0) {
        centres[c] = sum[c] / double(count[c]);
        continue;
      }
      // An emptied cluster takes the point worst served by its centre.
      size_t far = 0;
      for (size_t i = 1; i < n; ++i)
        if (dist[i] > dist[far]) far = i;
      centres[c] = pts[far];
      dist[far] = 0.0;
      label[far] = c;
      changed = true;
    }
    if (!changed) break;
  }
  return centres;
}

}  // namespace

Ellipsoid as_ellipsoid(const Sphere& sphere) {
  Ellipsoid e;
  e.centre = sphere.centre;
  e.axes = glm::mat3(1.0f);
  e.radii = glm::vec3(sphere.radius);
  return e;
}

Sphere fit_bounding_sphere(const std::vector<glm::vec3>& points) {
  check_points(points);
  // Work relative to the box centre: keeps the arithmetic well conditioned for crowns far
  // from the origin.
  const glm::dvec3 origin = bounds_centre(points);
  std::vector<size_t> order(points.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  uint64_t rng = kSphereShuffleSeed;
  for (size_t i = order.size(); i > 1; --i)  // Fisher-Yates
    std::swap(order[i - 1], order[size_t(uniform01(rng) * double(i))]);
  std::list<glm::dvec3> list;
  for (size_t i : order)
    list.push_back(glm::dvec3(points[i]) - origin);
  const glm::dvec3 c = Miniball(std::move(list)).centre() + origin;

  Sphere s;
  s.centre = glm::vec3(c);
  // The radius from the float centre actually stored, so rounding the centre cannot leave a
  // point outside.
  double r2 = 0.0;
  for (const glm::vec3& p : points) {
    const glm::dvec3 e = glm::dvec3(p) - glm::dvec3(s.centre);
    r2 = std::max(r2, glm::dot(e, e));
  }
  s.radius = padded_length(std::sqrt(r2), 4.0 * std::numeric_limits<float>::epsilon());
  return s;
}

Ellipsoid fit_bounding_ellipsoid(const std::vector<glm::vec3>& points) {
  check_points(points);
  const size_t n = points.size();
  glm::dvec3 mean(0.0);
  for (const glm::vec3& p : points)
    mean += glm::dvec3(p);
  mean /= double(n);
  cv::Matx33d cov = cv::Matx33d::zeros();
  for (const glm::vec3& p : points) {
    const glm::dvec3 e = glm::dvec3(p) - mean;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        cov(r, c) += e[r] * e[c];
  }
  cov *= 1.0 / double(n);
  cv::Matx31d values;
  cv::Matx33d vectors;  // rows, by decreasing eigenvalue
  cv::eigen(cov, values, vectors);

  glm::dmat3 axes;
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 v(vectors(a, 0), vectors(a, 1), vectors(a, 2));
    v = glm::normalize(v);
    // Canonical sign: the component of largest magnitude is positive (first one on ties).
    int big = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i]) > std::abs(v[big])) big = i;
    if (v[big] < 0.0) v = -v;
    axes[a] = v;
  }
  // Re-orthonormalise (Gram-Schmidt) and make the frame right-handed.
  axes[1] = glm::normalize(axes[1] - glm::dot(axes[1], axes[0]) * axes[0]);
  axes[2] = glm::cross(axes[0], axes[1]);

  double sd[3];
  for (int a = 0; a < 3; ++a)
    sd[a] = std::sqrt(std::max(values(a), 0.0));
  Ellipsoid e;
  if (!(sd[0] > 0.0)) {  // all points equal: a shell without volume
    e.centre = points[0];
    return e;
  }
  for (int a = 1; a < 3; ++a)
    sd[a] = std::max(sd[a], double(kMinEllipsoidAxisRatio) * sd[0]);

  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const glm::vec3& p : points) {
    const glm::dvec3 q = glm::transpose(axes) * (glm::dvec3(p) - mean);
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  e.centre = glm::vec3(mean + axes * (0.5 * (lo + hi)));
  e.axes = glm::mat3(axes);
  // The scale from the float centre and axes actually stored, evaluated in double.
  const glm::dmat3 stored_axes(e.axes);
  const glm::dvec3 stored_centre(e.centre);
  double scale2 = 0.0;
  for (const glm::vec3& p : points) {
    const glm::dvec3 q = glm::transpose(stored_axes) * (glm::dvec3(p) - stored_centre);
    const glm::dvec3 u(q.x / sd[0], q.y / sd[1], q.z / sd[2]);
    scale2 = std::max(scale2, glm::dot(u, u));
  }
  const double scale = std::sqrt(scale2);
  // 1e-5: a float evaluation of the mapping into the unit sphere has relative error ~1e-7
  // times the axis ratio (at most 1 / kMinEllipsoidAxisRatio).
  for (int a = 0; a < 3; ++a)
    e.radii[a] = padded_length(scale * sd[a], 1e-5);
  return e;
}

void validate_shell_options(const ShellOptions& options) {
  if (options.shells < 1 || options.shells > 64)
    throw InputError("ao-shells", "must be in [1, 64], got " + std::to_string(options.shells));
  if (options.kind != ShellKind::Sphere && options.kind != ShellKind::Ellipsoid)
    throw InputError("ao-shell-kind", "must be sphere or ellipsoid");
}

size_t Shells::nearest(const glm::vec3& p) const {
  SYLVA_CHECK(!anchors.empty(), "Shells::nearest needs at least one shell");
  if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) return 0;
  return nearest_index(anchors, p);
}

Shells fit_shells(const std::vector<glm::vec3>& points, const ShellOptions& options) {
  validate_shell_options(options);
  check_points(points);

  std::vector<glm::vec3> distinct = points;
  std::sort(distinct.begin(), distinct.end(), less_xyz);
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  const size_t k = std::min(size_t(options.shells), distinct.size());
  const size_t stride = std::max<size_t>(1, distinct.size() / kMaxKMeansPoints);
  std::vector<glm::dvec3> sample;
  for (size_t i = 0; i < distinct.size(); i += stride)
    sample.push_back(glm::dvec3(distinct[i]));

  std::vector<glm::vec3> anchors;
  if (k == 1) {
    glm::dvec3 mean(0.0);
    for (const glm::vec3& p : points)
      mean += glm::dvec3(p);
    anchors.push_back(glm::vec3(mean / double(points.size())));
  } else {
    for (const glm::dvec3& c : kmeans(sample, k, options.seed))
      anchors.push_back(glm::vec3(c));
  }

  // Labels by the same float nearest-anchor rule that Shells::nearest applies later.
  std::vector<uint32_t> labels(points.size());
  const long long count = (long long)points.size();
#pragma omp parallel for schedule(static)
  for (long long i = 0; i < count; ++i)
    labels[size_t(i)] = uint32_t(nearest_index(anchors, points[size_t(i)]));

  // Drop anchors that ended up with no vertex (possible only when Lloyd did not converge).
  std::vector<std::vector<glm::vec3>> members(anchors.size());
  for (size_t i = 0; i < points.size(); ++i)
    members[labels[i]].push_back(points[i]);
  Shells out;
  std::vector<uint32_t> renumber(anchors.size(), 0);
  for (size_t c = 0; c < anchors.size(); ++c) {
    if (members[c].empty()) continue;
    renumber[c] = uint32_t(out.anchors.size());
    out.anchors.push_back(anchors[c]);
    out.shells.push_back(options.kind == ShellKind::Sphere
                             ? as_ellipsoid(fit_bounding_sphere(members[c]))
                             : fit_bounding_ellipsoid(members[c]));
  }
  if (out.anchors.size() != anchors.size())
    for (uint32_t& l : labels)
      l = renumber[l];
  out.labels = std::move(labels);
  return out;
}

}  // namespace sylva

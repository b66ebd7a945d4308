#include "samples/lsystem.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"

namespace sylva {

namespace {

constexpr float kPi = 3.14159265358979f;

// Rodrigues rotation of v about the unit axis k.
glm::vec3 rotate(const glm::vec3& v, const glm::vec3& k, float a) {
  float c = std::cos(a), s = std::sin(a);
  return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0f - c));
}

// Any unit vector perpendicular to the unit vector d.
glm::vec3 any_perpendicular(const glm::vec3& d) {
  glm::vec3 a = std::fabs(d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(a - d * glm::dot(a, d));
}

// Uniform [0, 1) from the generator (24 bits; not std::uniform_real_distribution, whose
// output differs between standard libraries).
float unit(std::mt19937_64& g) {
  return static_cast<float>(g() >> 40) * (1.0f / 16777216.0f);
}
float signed_unit(std::mt19937_64& g) {
  return 2.0f * unit(g) - 1.0f;
}

}  // namespace

uint64_t mix_key(uint64_t key, uint64_t salt) {
  uint64_t z = key + 0x9e3779b97f4a7c15ull * (salt + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

float key_unit(uint64_t key) {
  return static_cast<float>(mix_key(key, 0x51a7) >> 40) * (1.0f / 16777216.0f);
}

void Turtle::turn(float a) {
  heading = rotate(heading, up, a);
  left = rotate(left, up, a);
}

void Turtle::pitch(float a) {
  heading = rotate(heading, left, a);
  up = rotate(up, left, a);
}

void Turtle::roll(float a) {
  left = rotate(left, heading, a);
  up = rotate(up, heading, a);
}

void Turtle::bend_towards(const glm::vec3& dir, float weight) {
  glm::vec3 h2 = heading + dir * weight;
  float len = glm::length(h2);
  if (len < 1e-6f) return;
  h2 /= len;
  glm::vec3 axis = glm::cross(heading, h2);
  float s = glm::length(axis);
  if (s < 1e-7f) return;
  float a = std::atan2(s, glm::dot(heading, h2));
  axis /= s;
  heading = h2;
  left = rotate(left, axis, a);
  left = glm::normalize(left - heading * glm::dot(left, heading));
  up = glm::cross(heading, left);
}

int32_t Skeleton::begin_branch(int32_t parent, int32_t parent_internode, int32_t order) {
  Branch b;
  b.parent = parent;
  b.parent_internode = parent_internode;
  b.first = static_cast<int32_t>(internodes.size());
  b.order = order;
  branches.push_back(b);
  return static_cast<int32_t>(branches.size()) - 1;
}

void Skeleton::forward(Turtle& t, float length, float age, bool leafy, uint64_t key) {
  glm::vec3 start = t.pos;
  t.pos += t.heading * length;
  if (internodes.size() >= m_budget || branches.empty()) {
    m_overflow = true;
    return;
  }
  Internode n;
  n.start = start;
  n.end = t.pos;
  n.up = t.up;
  n.age = age;
  n.branch = static_cast<int32_t>(branches.size()) - 1;
  n.leafy = leafy;
  n.key = key;
  internodes.push_back(n);
  branches.back().count++;
  if (leafy) m_leafy++;
}

int32_t Skeleton::end_branch() {
  SYLVA_CHECK(!branches.empty(), "end_branch without begin_branch");
  if (branches.back().count == 0) {
    branches.pop_back();
    return -1;
  }
  return static_cast<int32_t>(branches.size()) - 1;
}

void Skeleton::scale(float s) {
  for (Internode& n : internodes) {
    n.start *= s;
    n.end *= s;
  }
}

Bounds Skeleton::bounds() const {
  Bounds b;
  for (const Internode& n : internodes) {
    b.extend(n.start);
    b.extend(n.end);
  }
  return b;
}

std::vector<float> pipe_diameters(const Skeleton& s, float root_diameter, float min_diameter) {
  const size_t n = s.internodes.size();
  std::vector<double> carried(n, 0.0), attached(n, 0.0);
  std::vector<bool> is_first(n, false);
  for (const Branch& b : s.branches)
    if (b.count > 0) is_first[b.first] = true;
  // Children have larger indices than their attachment internode, so one reverse sweep
  // sees every distal internode before the ones carrying it.
  for (size_t i = n; i-- > 0;) {
    const Internode& in = s.internodes[i];
    const Branch& b = s.branches[in.branch];
    bool has_next = static_cast<int32_t>(i) + 1 < b.first + b.count;
    carried[i] = in.leaf_count + attached[i] + (has_next ? carried[i + 1] : 0.0);
    if (is_first[i] && b.parent_internode >= 0) attached[b.parent_internode] += carried[i];
  }
  double total = n > 0 ? carried[0] : 0.0;
  std::vector<float> d(n, root_diameter);
  for (size_t i = 0; i < n; ++i) {
    double f = total > 0 ? std::sqrt(carried[i] / total) : 1.0;
    d[i] = std::max(min_diameter, static_cast<float>(root_diameter * f));
  }
  return d;
}

void emit_leaves(const Skeleton& s, const LeafStyle& style, uint64_t seed, Mesh& leaves,
                 std::vector<int32_t>& leaf_branch) {
  std::mt19937_64 rng(seed);
  const glm::vec3 world_up(0, 1, 0);
  const float deg = kPi / 180.0f;
  const float angle_jitter = style.jitter * 60.0f * deg;
  for (const Internode& in : s.internodes) {
    if (in.leaf_count <= 0) continue;
    const glm::vec3 h = in.heading();
    const glm::vec3 u0 = glm::normalize(in.up - h * glm::dot(in.up, h));
    const float age_f = std::clamp(in.age / style.max_age, 0.0f, 1.0f);
    const float base_angle = (style.angle_young + (style.angle_old - style.angle_young) * age_f);
    const float base_roll = key_unit(in.key) * 2.0f * kPi;
    const int pairs = (in.leaf_count + 1) / 2;
    for (int j = 0; j < pairs; ++j) {
      const glm::vec3 p = in.start + (in.end - in.start) * (static_cast<float>(j + 1) / pairs);
      const float roll = base_roll + j * 0.5f * kPi + signed_unit(rng) * angle_jitter;
      const glm::vec3 r0 = rotate(u0, h, roll);
      const int in_pair = std::min(2, in.leaf_count - 2 * j);
      for (int k = 0; k < in_pair; ++k) {
        const glm::vec3 r = k == 0 ? r0 : -r0;  // the pair rolled 180 degrees
        const float a = base_angle * deg + signed_unit(rng) * angle_jitter * 0.5f;
        const glm::vec3 d = glm::normalize(h * std::cos(a) + r * std::sin(a));
        glm::vec3 n0 = glm::normalize(glm::cross(glm::cross(h, r), d));
        if (glm::dot(n0, world_up) < 0.0f) n0 = -n0;
        glm::vec3 n_up = world_up - d * glm::dot(world_up, d);
        float n_up_len = glm::length(n_up);
        glm::vec3 n = n0;
        if (n_up_len > 1e-3f) {
          const glm::vec3 blend = n0 + (n_up / n_up_len - n0) * style.face_up;
          if (glm::length(blend) > 1e-3f) n = glm::normalize(blend);
        }
        n = glm::normalize(rotate(n, d, signed_unit(rng) * angle_jitter));
        const glm::vec3 side = glm::normalize(glm::cross(d, n));
        const float len = style.length * (1.0f + style.jitter * signed_unit(rng));
        const glm::vec3 half = side * (0.5f * len * style.aspect);
        const glm::vec3 tip = p + d * len;
        const uint32_t base = static_cast<uint32_t>(leaves.positions.size());
        leaves.positions.insert(leaves.positions.end(),
                                {p - half, p + half, tip + half, tip - half});
        leaves.normals.insert(leaves.normals.end(), {n, n, n, n});
        leaves.uvs.insert(leaves.uvs.end(),
                          {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}});
        leaves.indices.insert(leaves.indices.end(),
                              {base, base + 1, base + 2, base, base + 2, base + 3});
        leaf_branch.push_back(in.branch);
      }
    }
  }
}

void emit_bark(const Skeleton& s, const std::vector<float>& diameters, float thick_diameter,
               uint32_t first_id, Mesh& bark) {
  SYLVA_CHECK(diameters.size() == s.internodes.size(), "one diameter per internode");
  uint32_t id = first_id;
  for (const Branch& b : s.branches) {
    if (b.count <= 0) continue;
    // Twigs far outnumber limbs and are a few pixels wide: fewer sides keep a 100k-leaf tree
    // near 250k triangles.
    const float d0 = diameters[b.first];
    const int sides = d0 >= thick_diameter ? 8 : d0 >= 0.3f * thick_diameter ? 5 : 3;
    const float base_d = diameters[b.first];
    const uint32_t first_vertex = static_cast<uint32_t>(bark.positions.size());
    const int rings = b.count + 1;
    glm::vec3 ref(0.0f);
    glm::vec3 last_dir(0.0f);
    float v = 0.0f;
    int emitted = 0;
    for (int k = 0; k < rings; ++k) {
      const Internode& cur = s.internodes[b.first + std::min(k, b.count - 1)];
      glm::vec3 dir = cur.heading();
      glm::vec3 center = k < b.count ? cur.start : cur.end;
      if (k > 0 && k < b.count) {
        glm::vec3 both = s.internodes[b.first + k - 1].heading() + dir;
        if (glm::length(both) > 1e-4f) dir = glm::normalize(both);
      }
      if (k > 0) v += s.internodes[b.first + k - 1].length() / (kPi * base_d);
      // Thin axes skip rings where they barely bend (cos 12° ≈ 0.978): the tube between the
      // kept rings is straight to within a fraction of its width.
      if (sides < 8 && k > 0 && k < rings - 1 && glm::dot(dir, last_dir) > 0.978f) continue;
      last_dir = dir;
      const float ring_d =
          k < b.count ? diameters[b.first + k] : 0.6f * diameters[b.first + b.count - 1];
      const float radius = 0.5f * ring_d;
      if (k == 0) ref = cur.up;
      ref -= dir * glm::dot(ref, dir);
      ref = glm::length(ref) > 1e-5f ? glm::normalize(ref) : any_perpendicular(dir);
      const glm::vec3 bin = glm::cross(dir, ref);
      for (int j = 0; j <= sides; ++j) {
        float th = 2.0f * kPi * static_cast<float>(j % sides) / sides;
        glm::vec3 off = ref * std::cos(th) + bin * std::sin(th);
        bark.positions.push_back(center + off * radius);
        bark.normals.push_back(off);
        bark.uvs.push_back({static_cast<float>(j) / sides, v});
      }
      ++emitted;
      if (k == rings - 1) {  // tip cone apex
        bark.positions.push_back(center + dir * radius);
        bark.normals.push_back(dir);
        bark.uvs.push_back({0.5f, v});
      }
    }
    const uint32_t stride = sides + 1;
    for (int k = 0; k + 1 < emitted; ++k) {
      for (int j = 0; j < sides; ++j) {
        uint32_t a = first_vertex + k * stride + j, c = a + stride + 1, d = a + stride;
        bark.indices.insert(bark.indices.end(), {a, a + 1, c, a, c, d});
      }
    }
    const uint32_t last_ring = first_vertex + (emitted - 1) * stride;
    const uint32_t apex = last_ring + stride;
    for (int j = 0; j < sides; ++j)
      bark.indices.insert(bark.indices.end(), {last_ring + j, last_ring + j + 1, apex});
    bark.primitive_ids.resize(bark.indices.size() / 3, id++);
  }
}

}  // namespace sylva

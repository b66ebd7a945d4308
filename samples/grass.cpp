#include "samples/grass.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/random.h"

namespace sylva {

namespace {

constexpr float kTwoPi = 6.28318530717959f;
constexpr float kMinHeightShare = 0.6f;  // shortest blade, share of kGrassHeight
constexpr float kMaxLean = 0.35f;        // tip's horizontal offset, share of the blade height
constexpr float kMidWidthShare = 0.6f;   // width at mid-height, share of the root width

float uniform(uint64_t& state, float lo, float hi) {
  return lo + (hi - lo) * static_cast<float>(uniform01(state));
}

}  // namespace

Scene make_grass(const GrassOptions& options) {
  if (options.blades < kMinGrassBlades || options.blades > kMaxGrassBlades)
    throw InputError("--blades", "must be in [" + std::to_string(kMinGrassBlades) + ", " +
                                     std::to_string(kMaxGrassBlades) + "], got " +
                                     std::to_string(options.blades));
  Scene scene;
  scene.report.source = "sample:grass";
  scene.report.foliage_rule = "sample";
  scene.report.foliage_reason = "no foliage; mesh \"grass\" is grass blades";
  Material grass;
  grass.name = "grass";
  grass.base_color = glm::vec4(0.16f, 0.36f, 0.07f, 1.0f);
  grass.double_sided = true;
  scene.materials.push_back(grass);

  Mesh m;
  m.name = "grass";
  m.material = 0;
  const auto n = static_cast<size_t>(options.blades);
  m.positions.reserve(5 * n);
  m.normals.reserve(5 * n);
  m.uvs.reserve(5 * n);
  m.indices.reserve(9 * n);
  uint64_t state = options.seed ^ 0x6772617373ull;  // "grass"
  const float half = 0.5f * kGrassPatchSide;
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  for (size_t b = 0; b < n; ++b) {
    // One draw per statement: the order of a call's arguments is up to the compiler (GCC
    // and clang differ), and the patch must be the same whichever built it.
    // z is drawn first, as GCC ordered it before (the sample stays the same patch).
    const float z = uniform(state, -half, half);
    const glm::vec3 root(uniform(state, -half, half), 0.0f, z);
    const float facing = uniform(state, 0.0f, kTwoPi);
    const float height = kGrassHeight * uniform(state, kMinHeightShare, 1.0f);
    const float lean = height * uniform(state, 0.0f, kMaxLean);
    const float width = kGrassBladeWidth * uniform(state, 0.7f, 1.0f);
    // The blade's flat side faces `face`; it leans along it (forward or back), and its
    // width runs along `across`.
    const glm::vec3 face(std::cos(facing), 0.0f, std::sin(facing));
    const glm::vec3 across(-face.z, 0.0f, face.x);
    // A quadratic bend: the offset grows as the square of the height share, so the blade
    // rises straight from the root and curves over toward the tip.
    auto spine = [&](float t) { return root + up * (height * t) + face * (lean * t * t); };
    auto normal_at = [&](float t) {
      const glm::vec3 tangent = up * height + face * (2.0f * lean * t);
      return glm::normalize(glm::cross(across, tangent));
    };
    const auto base = static_cast<uint32_t>(m.positions.size());
    const glm::vec3 mid = spine(0.5f);
    const float mid_w = 0.5f * width * kMidWidthShare;
    m.positions.push_back(root - across * (0.5f * width));
    m.positions.push_back(root + across * (0.5f * width));
    m.positions.push_back(mid + across * mid_w);
    m.positions.push_back(mid - across * mid_w);
    m.positions.push_back(spine(1.0f));
    const glm::vec3 n0 = normal_at(0.0f), n1 = normal_at(0.5f), n2 = normal_at(1.0f);
    m.normals.insert(m.normals.end(), {n0, n0, n1, n1, n2});
    m.uvs.insert(m.uvs.end(),
                 {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.5f}, {0.0f, 0.5f}, {0.5f, 0.0f}});
    // Counter-clockwise seen from the normal's side.
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3, base + 3,
                                       base + 2, base + 4});
    for (int k = 0; k < 3; ++k)
      m.primitive_ids.push_back(static_cast<uint32_t>(b + 1));
  }
  m.cluster_ids.assign(m.triangle_count(), 1);
  m.roles.assign(m.triangle_count(), Role::Grass);
  scene.meshes.push_back(std::move(m));
  return scene;
}

}  // namespace sylva

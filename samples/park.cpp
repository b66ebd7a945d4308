#include "samples/park.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "core/error.h"
#include "core/random.h"
#include "core/scene/instances.h"

namespace sylva {

namespace {

constexpr float kMaxArea = 1e6f;

void check(const ParkOptions& o, size_t plants) {
  if (plants == 0) throw InputError("--plants", "name at least one plant file");
  if (o.count < 1 || o.count > kMaxParkCount)
    throw InputError("--count", "must be in [1, " + std::to_string(kMaxParkCount) + "], got " +
                                    std::to_string(o.count));
  for (float side : {o.width, o.depth})
    if (!(side > 0.0f && side <= kMaxArea))
      throw InputError("--area", "each side must be in (0, 1e6] scene units");
}

// Plant `source`'s meshes, materials and textures appended to `park` as plant `name`.
void add_plant(Scene& park, const Scene& source, const std::string& name) {
  const Scene flat = flatten(source);
  const int material_base = int(park.materials.size());
  const int texture_base = int(park.textures.size());
  park.textures.insert(park.textures.end(), flat.textures.begin(), flat.textures.end());
  for (Material m : flat.materials) {
    if (m.base_color_texture >= 0) m.base_color_texture += texture_base;
    park.materials.push_back(m);
  }
  Plant plant;
  plant.name = name;
  plant.hierarchy = flat.hierarchy;
  for (Mesh m : flat.meshes) {
    if (m.material >= 0) m.material += material_base;
    plant.meshes.push_back(uint32_t(park.meshes.size()));
    park.meshes.push_back(std::move(m));
  }
  park.plants.push_back(std::move(plant));
}

// The cells in a seeded order (Fisher-Yates with splitmix64).
std::vector<int> shuffled_cells(int cells, uint64_t& rng) {
  std::vector<int> order(size_t(cells), 0);
  for (int i = 0; i < cells; ++i)
    order[size_t(i)] = i;
  for (int i = cells - 1; i > 0; --i)
    std::swap(order[size_t(i)], order[size_t(splitmix64(rng) % uint64_t(i + 1))]);
  return order;
}

// "plan": orthographic, straight down (image up = -Z), the whole area in a square image;
// "overview": perspective from above the +X, +Z corner toward the middle.
void add_cameras(Scene& park, const ParkOptions& o) {
  const Bounds b = park.bounds();
  const float top = std::max(b.max.y, 0.0f);
  const float reach = std::max(o.width, o.depth);
  SceneCamera plan;
  plan.name = "plan";
  plan.orthographic = true;
  plan.ymag = plan.xmag = 0.55f * reach;
  plan.znear = 0.0f;
  plan.zfar = top + 0.2f * reach + std::max(0.0f, -b.min.y) + 1.0f;
  const glm::vec3 above(0.0f, top + 0.1f * reach + 0.5f, 0.0f);
  plan.to_world = glm::inverse(glm::lookAt(above, glm::vec3(0.0f), glm::vec3(0, 0, -1)));
  SceneCamera overview;
  overview.name = "overview";
  overview.yfov = glm::radians(45.0f);
  const glm::vec3 eye(0.7f * o.width, top + 0.45f * reach, 0.95f * o.depth);
  const glm::vec3 target(0.0f, top / 3.0f, 0.0f);
  const float distance = glm::length(eye - target);
  overview.znear = 0.01f * distance;
  overview.zfar = 3.0f * distance;
  overview.to_world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  park.cameras = {plan, overview};
}

}  // namespace

void parse_park_area(const std::string& text, float& width, float& depth) {
  const size_t x = text.find_first_of("xX");
  auto number = [&](const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !(v > 0.0 && v <= double(kMaxArea)))
      throw InputError("--area",
                       "expected WxD or N, each in (0, 1e6] scene units, got '" + text + "'");
    return float(v);
  };
  width = number(text.substr(0, x));
  depth = x == std::string::npos ? width : number(text.substr(x + 1));
}

Scene make_park(const std::vector<Scene>& plants, const std::vector<std::string>& names,
                const ParkOptions& o) {
  check(o, plants.size());
  SYLVA_CHECK(names.size() == plants.size(), "make_park: one name per plant");
  Scene park;
  park.report.source = "sample:park";
  for (size_t p = 0; p < plants.size(); ++p)
    add_plant(park, plants[p], names[p]);
  // Columns and rows of about square cells: cols / rows ~ width / depth, cols * rows >= count.
  const double aspect = double(o.width) / double(o.depth);
  const int cols = std::max(1, int(std::ceil(std::sqrt(double(o.count) * aspect))));
  const int rows = std::max(1, int(std::ceil(double(o.count) / double(cols))));
  const double cw = double(o.width) / cols, cd = double(o.depth) / rows;
  uint64_t rng = o.seed;
  const std::vector<int> cells = shuffled_cells(cols * rows, rng);
  for (int i = 0; i < o.count; ++i) {
    const int cell = cells[size_t(i)];
    const double x = -0.5 * o.width + cw * ((cell % cols) + 0.1 + 0.8 * uniform01(rng));
    const double z = -0.5 * o.depth + cd * ((cell / cols) + 0.1 + 0.8 * uniform01(rng));
    const double angle = 2.0 * std::numbers::pi * uniform01(rng);
    const double scale = 0.8 + 0.4 * uniform01(rng);
    const auto plant = uint32_t(splitmix64(rng) % plants.size());
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0.0, z));
    t = glm::rotate(t, angle, glm::dvec3(0.0, 1.0, 0.0));
    t = glm::scale(t, glm::dvec3(scale));
    park.instances.push_back({plant, glm::mat4(t), names[plant] + "_" + std::to_string(i)});
  }
  // A plant no instance drew is left out.
  std::vector<char> keep(park.meshes.size(), 0);
  for (const Instance& inst : park.instances)
    for (uint32_t m : park.plants[inst.plant].meshes)
      keep[m] = 1;
  remove_meshes(park, keep);
  add_cameras(park, o);
  return park;
}

}  // namespace sylva

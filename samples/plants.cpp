#include "samples/plants.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "core/error.h"
#include "samples/leaf_texture.h"
#include "samples/lsystem.h"

namespace sylva {

namespace {

constexpr float kDeg = 3.14159265358979f / 180.0f;
constexpr float kPlastochron = 1.0f;     // PL of Dudley A.2
constexpr float kThickDiameter = 0.05f;  // bark tubes at least this thick get 8 sides, else 6
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// Per-kind shape and scale. Lengths in scene units (metres).
struct KindParams {
  int default_leaves;
  float height;           // plant height after normalisation
  float root_diameter;    // pipe-model diameter at the base of the root branch
  float min_diameter;     // thinnest twig
  float leaf_length;      // blade length at default_leaves; scales with 1/sqrt(leaves)
  float max_leaf_length;  // cap for small leaf counts
  float pairs_ref;        // leaf pairs per leafy internode ~ sqrt(leaves / pairs_ref)
  LeafTextureKind texture;
  LeafStyle style;  // length is filled in per plant
};

KindParams params_for(PlantKind kind) {
  switch (kind) {
    case PlantKind::Bush:
      return {5000,
              1.6f,
              0.10f,
              0.003f,
              0.09f,
              0.4f,
              1200.0f,
              LeafTextureKind::Broadleaf,
              {0.0f, 0.6f, 40.0f, 70.0f, 6.0f, 0.5f, 0.15f}};
    case PlantKind::Conifer:
      return {20000,
              9.0f,
              0.32f,
              0.004f,
              0.22f,
              1.0f,
              400.0f,
              LeafTextureKind::Needle,
              {0.0f, 0.1f, 45.0f, 60.0f, 4.0f, 0.2f, 0.12f}};
    case PlantKind::Tree:
    default:
      return {10000,
              7.0f,
              0.30f,
              0.004f,
              0.20f,
              1.0f,
              4000.0f,
              LeafTextureKind::Broadleaf,
              {0.0f, 0.6f, 45.0f, 75.0f, 10.0f, 0.5f, 0.15f}};
  }
}

// Sympodial axis rule after Dudley A.2: A(t) -> I(t-PL) roll(90) [+A(t-PL-s)] [-A(t-PL+s)];
// the older child (t + s) continues the axis at a small angle, the younger one starts a
// lateral at ANG. Internodes elongate with age (F(func(internode, t/D))).
struct SympodialRule {
  float dominant_angle;  // degrees, turn of the continuing apex
  float lateral_angle;   // degrees, ANG
  float age_split;       // s (0.3 in A.2)
  float roll;            // degrees per node (90 in A.2)
  float tropism;         // weight per internode towards +y
  float leafy_age;       // internodes younger than this carry leaves
  float len_young;       // internode length at age 0 (abstract units)
  float len_old;         // internode length at the plant's maximum age
};

struct Apex {
  Turtle turtle;
  float age;
  uint64_t key;
  int32_t attach;
};

void grow_sympodial(Skeleton& sk, const SympodialRule& rule, Turtle turtle, float t, float max_t,
                    uint64_t key, int32_t parent, int32_t attach, int32_t order,
                    float prefix_length) {
  sk.begin_branch(parent, attach, order);
  if (prefix_length > 0) sk.forward(turtle, prefix_length, max_t, false, mix_key(key, 999));
  std::vector<Apex> laterals;
  for (uint64_t step = 0; t > kPlastochron && !sk.overflow(); ++step) {
    t -= kPlastochron;
    const uint64_t k = mix_key(key, step);
    const float rel = std::clamp(t / max_t, 0.0f, 1.0f);
    const float len = (rule.len_young + (rule.len_old - rule.len_young) * rel) *
                      (1.0f + 0.15f * key_signed(mix_key(k, 1)));
    sk.forward(turtle, len, t, t < rule.leafy_age, k);
    turtle.roll((rule.roll + 20.0f * key_signed(mix_key(k, 2))) * kDeg);
    Apex lat{turtle, t - rule.age_split + 0.25f * key_signed(mix_key(k, 3)), mix_key(k, 4),
             static_cast<int32_t>(sk.internodes.size()) - 1};
    lat.turtle.turn((rule.lateral_angle + 10.0f * key_signed(mix_key(k, 5))) * kDeg);
    laterals.push_back(lat);
    turtle.turn(-(rule.dominant_angle + 5.0f * key_signed(mix_key(k, 6))) * kDeg);
    turtle.bend_towards(kUp, rule.tropism);
    t += rule.age_split + 0.15f * key_signed(mix_key(k, 7));
  }
  const int32_t b = sk.end_branch();
  if (b < 0) return;
  for (Apex& a : laterals) {
    if (sk.overflow()) return;
    a.turtle.bend_towards(kUp, rule.tropism);
    grow_sympodial(sk, rule, a.turtle, a.age, max_t, a.key, b, a.attach, order + 1, 0.0f);
  }
}

// Broad deciduous crown on a clear bole (~40% of the crown height).
void grow_tree(Skeleton& sk, float age, uint64_t key) {
  const SympodialRule rule{12.0f, 42.0f, 0.3f, 90.0f, 0.06f, 2.2f, 0.25f, 1.0f};
  float crown = 0.0f;  // expected height of the main axis, to size the bole
  for (float t = age - kPlastochron; t > 0; t -= kPlastochron - rule.age_split)
    crown += rule.len_young + (rule.len_old - rule.len_young) * t / age;
  Turtle turtle;
  turtle.roll(60.0f * kDeg);  // RollL(60) of the axiom
  grow_sympodial(sk, rule, turtle, age, age, key, -1, -1, 0, 0.45f * crown + 0.2f);
}

// Turtle heading `dir` with U as close to +y as possible (so turns stay near-horizontal).
Turtle turtle_towards(const glm::vec3& pos, const glm::vec3& dir) {
  Turtle t;
  t.pos = pos;
  t.heading = glm::normalize(dir);
  glm::vec3 up = kUp - t.heading * glm::dot(kUp, t.heading);
  t.up = glm::length(up) > 1e-4f ? glm::normalize(up) : glm::vec3(0, 0, 1);
  t.left = glm::cross(t.up, t.heading);
  return t;
}

// Several splaying stems from a short root collar; low round crown.
void grow_bush(Skeleton& sk, float age, uint64_t key) {
  const SympodialRule rule{15.0f, 45.0f, 0.3f, 90.0f, 0.04f, 3.5f, 0.35f, 1.0f};
  Turtle collar;
  sk.begin_branch(-1, -1, 0);
  sk.forward(collar, 0.1f, age, false, mix_key(key, 1000));
  const int32_t root = sk.end_branch();
  const int stems = 5 + static_cast<int>(mix_key(key, 1001) % 3);
  const float phase = key_unit(mix_key(key, 1002)) * 360.0f;
  for (int i = 0; i < stems && !sk.overflow(); ++i) {
    const uint64_t k = mix_key(key, 2000 + i);
    const float az = (phase + 360.0f * i / stems + 20.0f * key_signed(mix_key(k, 1))) * kDeg;
    const float tilt = (25.0f + 12.0f * key_signed(mix_key(k, 2))) * kDeg;
    glm::vec3 dir(std::sin(tilt) * std::cos(az), std::cos(tilt), std::sin(tilt) * std::sin(az));
    Turtle t = turtle_towards(collar.pos, dir);
    const float stem_age = age - 0.4f * key_unit(mix_key(k, 3));
    grow_sympodial(sk, rule, t, stem_age, age, mix_key(k, 4), root, 0, 1, 0.0f);
  }
}

// Monopodial conifer branch: straight-ish axis with alternate laterals in its plane.
void grow_conifer_branch(Skeleton& sk, Turtle turtle, float t, uint64_t key, int32_t parent,
                         int32_t attach, int32_t order) {
  constexpr float kStep = 0.5f;
  sk.begin_branch(parent, attach, order);
  std::vector<Apex> laterals;
  for (uint64_t step = 0; t > kStep && !sk.overflow(); ++step) {
    t -= kStep;
    const uint64_t k = mix_key(key, step);
    const float len = kStep * (0.6f + 0.4f * std::min(1.0f, t / 3.0f)) *
                      (1.0f + 0.1f * key_signed(mix_key(k, 1)));
    sk.forward(turtle, len, t, t < 2.5f, k);
    if (order < 3) {
      const float side = (step % 2 == 0) ? 1.0f : -1.0f;
      Apex lat{turtle, t - 1.0f - 0.2f * order + 0.2f * key_signed(mix_key(k, 2)), mix_key(k, 3),
               static_cast<int32_t>(sk.internodes.size()) - 1};
      lat.turtle.turn(side * (50.0f + 8.0f * key_signed(mix_key(k, 4))) * kDeg);
      laterals.push_back(lat);
    }
    turtle.turn(4.0f * key_signed(mix_key(k, 5)) * kDeg);
    turtle.bend_towards(-kUp, 0.015f);
  }
  const int32_t b = sk.end_branch();
  if (b < 0) return;
  for (const Apex& a : laterals) {
    if (sk.overflow()) return;
    grow_conifer_branch(sk, a.turtle, a.age, a.key, b, a.attach, order + 1);
  }
}

// Straight trunk with whorls of downward-sloping branches shortening towards the top.
void grow_conifer(Skeleton& sk, float age, uint64_t key) {
  const int whorls = std::max(3, static_cast<int>(2.0f * age));
  Turtle trunk;
  sk.begin_branch(-1, -1, 0);
  sk.forward(trunk, 0.15f * whorls, static_cast<float>(whorls), false, mix_key(key, 1000));
  std::vector<Apex> branches;
  for (int i = 0; i < whorls && !sk.overflow(); ++i) {
    const uint64_t k = mix_key(key, 2000 + i);
    const float to_top = static_cast<float>(whorls - i);
    sk.forward(trunk, 1.0f + 0.1f * key_signed(mix_key(k, 1)), to_top, whorls - i <= 2, k);
    const int n = 4 + static_cast<int>(mix_key(k, 2) % 3);
    const float phase = 137.5f * i + 30.0f * key_signed(mix_key(k, 3));
    const float rel_h = static_cast<float>(i) / whorls;
    for (int j = 0; j < n; ++j) {
      const uint64_t kj = mix_key(k, 10 + j);
      const float az = (phase + 360.0f * j / n + 12.0f * key_signed(mix_key(kj, 1))) * kDeg;
      const float from_up = (97.0f + 18.0f * (1.0f - rel_h) + 5.0f * key_signed(mix_key(kj, 2)));
      const float el = from_up * kDeg;
      glm::vec3 dir(std::sin(el) * std::cos(az), std::cos(el), std::sin(el) * std::sin(az));
      branches.push_back({turtle_towards(trunk.pos, dir),
                          0.32f * to_top + 0.6f + 0.2f * key_signed(mix_key(kj, 3)), mix_key(kj, 4),
                          static_cast<int32_t>(sk.internodes.size()) - 1});
    }
  }
  sk.forward(trunk, 0.8f, 0.5f, true, mix_key(key, 3000));  // the leader
  const int32_t b = sk.end_branch();
  if (b < 0) return;
  for (const Apex& a : branches) {
    if (sk.overflow()) return;
    grow_conifer_branch(sk, a.turtle, a.age, a.key, b, a.attach, 1);
  }
}

void grow(PlantKind kind, Skeleton& sk, float age, uint64_t key) {
  switch (kind) {
    case PlantKind::Tree:
      grow_tree(sk, age, key);
      break;
    case PlantKind::Bush:
      grow_bush(sk, age, key);
      break;
    case PlantKind::Conifer:
      grow_conifer(sk, age, key);
      break;
  }
}

// Grows skeletons of increasing age (bisection) until the number of leafy internodes is
// near `target`; returns the closest one found.
Skeleton fit_skeleton(PlantKind kind, size_t target, uint64_t key) {
  const size_t budget = 4 * target + 256;
  float lo = 1.0f, hi = 40.0f;
  Skeleton best;
  size_t best_err = SIZE_MAX;
  for (int iter = 0; iter < 24; ++iter) {
    const float age = 0.5f * (lo + hi);
    Skeleton sk(budget);
    grow(kind, sk, age, key);
    const size_t count = sk.overflow() ? SIZE_MAX : sk.leafy_count();
    if (!sk.overflow() && count > 0) {
      const size_t err = count > target ? count - target : target - count;
      if (err < best_err) {
        best_err = err;
        best = std::move(sk);
      }
      if (err * 50 <= target) break;  // within 2%: the leaf spread absorbs the rest
    }
    (count > target ? hi : lo) = age;
  }
  SYLVA_CHECK(best_err != SIZE_MAX, "no skeleton fits the leaf target");
  return best;
}

// Spreads `leaves` over the leafy internodes in pairs, as evenly as integer counts allow.
void distribute_leaves(Skeleton& sk, int leaves) {
  std::vector<Internode*> leafy;
  for (Internode& n : sk.internodes)
    if (n.leafy) leafy.push_back(&n);
  const int64_t m = static_cast<int64_t>(leafy.size());
  const int64_t pairs = leaves / 2;
  for (int64_t i = 0; i < m; ++i) {
    const int64_t p = (i + 1) * pairs / m - i * pairs / m;  // Bresenham spread
    leafy[i]->leaf_count = static_cast<int32_t>(2 * p);
  }
  if (leaves % 2 == 1) leafy[m - 1]->leaf_count += 1;
}

Material make_material(const std::string& name, const glm::vec4& color, int texture, AlphaMode mode,
                       bool double_sided) {
  Material m;
  m.name = name;
  m.base_color = color;
  m.base_color_texture = texture;
  m.alpha_mode = mode;
  m.alpha_cutoff = 0.5f;
  m.double_sided = double_sided;
  return m;
}

}  // namespace

PlantKind parse_plant_kind(const std::string& s) {
  if (s == "tree") return PlantKind::Tree;
  if (s == "bush") return PlantKind::Bush;
  if (s == "conifer") return PlantKind::Conifer;
  throw InputError("--kind", "unknown plant kind '" + s + "'; allowed: tree, bush, conifer");
}

const char* plant_kind_name(PlantKind k) {
  switch (k) {
    case PlantKind::Tree:
      return "tree";
    case PlantKind::Bush:
      return "bush";
    case PlantKind::Conifer:
      return "conifer";
  }
  return "tree";
}

int plant_default_leaves(PlantKind kind) {
  return params_for(kind).default_leaves;
}

Scene make_plant(const PlantOptions& options) {
  const KindParams kp = params_for(options.kind);
  const int leaves = options.leaves == 0 ? kp.default_leaves : options.leaves;
  if (leaves < kMinPlantLeaves || leaves > kMaxPlantLeaves)
    throw InputError("--leaves", "must be in [100, 2000000]");

  std::mt19937_64 rng(options.seed);
  const uint64_t growth_key = rng();
  const uint64_t leaf_seed = rng();

  // Skeleton resolution grows like sqrt(leaves); the rest goes into leaves per internode.
  const double pairs = std::max(1.0, std::round(std::sqrt(leaves / double(kp.pairs_ref))));
  const size_t target = std::max<size_t>(1, static_cast<size_t>(leaves / (2.0 * pairs)));
  Skeleton sk = fit_skeleton(options.kind, target, growth_key);
  sk.scale(kp.height / std::max(sk.bounds().max.y, 1e-6f));
  distribute_leaves(sk, leaves);

  LeafStyle style = kp.style;
  style.length =
      std::min(kp.max_leaf_length,
               kp.leaf_length * std::sqrt(static_cast<float>(kp.default_leaves) / leaves));

  Scene scene;
  scene.report.source = std::string("sample:") + plant_kind_name(options.kind);
  scene.report.foliage_rule = "sample";
  scene.report.foliage_reason = "mesh \"leaves\" is the generated foliage";
  scene.textures.push_back(make_leaf_texture(kp.texture));
  scene.textures.push_back(make_bark_texture());
  scene.materials.push_back(make_material("leaves", glm::vec4(1.0f), 0, AlphaMode::Mask, true));
  scene.materials.push_back(
      make_material("bark", glm::vec4(0.16f, 0.09f, 0.045f, 1.0f), 1, AlphaMode::Opaque, false));

  scene.meshes.resize(2);
  Mesh& foliage = scene.meshes[0];
  foliage.name = "leaves";
  foliage.material = 0;
  const size_t n_leaves = static_cast<size_t>(leaves);
  foliage.positions.reserve(4 * n_leaves);
  foliage.normals.reserve(4 * n_leaves);
  foliage.uvs.reserve(4 * n_leaves);
  foliage.indices.reserve(6 * n_leaves);
  scene.hierarchy.leaf_branch.reserve(n_leaves);
  emit_leaves(sk, style, leaf_seed, foliage, scene.hierarchy.leaf_branch);
  SYLVA_CHECK(foliage.triangle_count() == 2 * n_leaves, "leaf count mismatch");

  Mesh& bark = scene.meshes[1];
  bark.name = "bark";
  bark.material = 1;
  const std::vector<float> diameters = pipe_diameters(sk, kp.root_diameter, kp.min_diameter);
  emit_bark(sk, diameters, kThickDiameter, static_cast<uint32_t>(n_leaves) + 1, bark);

  // Leaf i is primitive i + 1 (its two triangles share two vertices).
  foliage.primitive_ids.resize(foliage.triangle_count());
  for (size_t t = 0; t < foliage.triangle_count(); ++t)
    foliage.primitive_ids[t] = static_cast<uint32_t>(t / 2 + 1);
  SYLVA_CHECK(bark.primitive_ids.size() == bark.triangle_count(), "bark id mismatch");
  for (Mesh* m : {&foliage, &bark}) {
    m->cluster_ids.assign(m->triangle_count(), 1);
    m->roles.assign(m->triangle_count(), m == &foliage ? Role::Foliage : Role::Wood);
  }

  for (const Branch& b : sk.branches) {
    scene.hierarchy.branch_parent.push_back(b.parent);
    scene.hierarchy.branch_diameter.push_back(diameters[b.first]);
  }

  // Drooping leaves may reach below the root; keep the plant standing on y = 0.
  const float min_y = scene.bounds().min.y;
  if (min_y < 0.0f)
    for (Mesh& m : scene.meshes)
      for (glm::vec3& p : m.positions)
        p.y -= min_y;
  return scene;
}

}  // namespace sylva

// Tests for the procedural sample plants (samples/plants.h): leaf counts, determinism,
// per-triangle arrays, primitive ids against an independent union-find, hierarchy
// consistency, normals, bounds, materials/textures and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "core/error.h"
#include "samples/leaf_texture.h"
#include "samples/plants.h"

namespace sylva {
namespace {

const PlantKind kKinds[] = {PlantKind::Tree, PlantKind::Bush, PlantKind::Conifer};

Scene plant(PlantKind kind, int leaves, uint64_t seed = 1) {
  PlantOptions o;
  o.kind = kind;
  o.leaves = leaves;
  o.seed = seed;
  return make_plant(o);
}

size_t leaf_count(const Scene& s) {
  size_t n = 0;
  for (const Mesh& m : s.meshes)
    for (Role r : m.roles)
      n += r == Role::Foliage ? 1 : 0;
  return n / 2;
}

// Independent reference: connected components over shared vertex indices, 1-based,
// numbered in order of each component's first triangle, meshes in order.
struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

std::vector<std::vector<uint32_t>> reference_ids(const Scene& s) {
  std::vector<std::vector<uint32_t>> out;
  uint32_t next = 0;
  for (const Mesh& m : s.meshes) {
    UnionFind uf(m.positions.size());
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      uf.unite(m.indices[3 * t], m.indices[3 * t + 1]);
      uf.unite(m.indices[3 * t], m.indices[3 * t + 2]);
    }
    std::vector<uint32_t> root_id(m.positions.size(), 0);
    std::vector<uint32_t> ids(m.triangle_count());
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      uint32_t r = uf.find(m.indices[3 * t]);
      if (root_id[r] == 0) root_id[r] = ++next;
      ids[t] = root_id[r];
    }
    out.push_back(std::move(ids));
  }
  return out;
}

bool same_geometry(const Scene& a, const Scene& b) {
  if (a.meshes.size() != b.meshes.size()) return false;
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const Mesh& ma = a.meshes[i];
    const Mesh& mb = b.meshes[i];
    if (ma.positions.size() != mb.positions.size() || ma.indices != mb.indices) return false;
    if (std::memcmp(ma.positions.data(), mb.positions.data(),
                    ma.positions.size() * sizeof(glm::vec3)) != 0)
      return false;
    if (std::memcmp(ma.normals.data(), mb.normals.data(), ma.normals.size() * sizeof(glm::vec3)))
      return false;
  }
  return true;
}

TEST(Plants, LeafCountHitsTarget) {
  for (PlantKind kind : kKinds) {
    std::vector<int> targets = {100, 1000, 10000};
    if (kind == PlantKind::Tree) targets.push_back(100000);
    for (int target : targets) {
      Scene s = plant(kind, target);
      const double n = static_cast<double>(leaf_count(s));
      EXPECT_NEAR(n, target, 0.1 * target) << plant_kind_name(kind) << " " << target;
      EXPECT_EQ(s.meshes[0].triangle_count(), 2u * static_cast<size_t>(n));
    }
  }
}

TEST(Plants, DefaultLeafCounts) {
  EXPECT_EQ(plant_default_leaves(PlantKind::Tree), 10000);
  EXPECT_EQ(plant_default_leaves(PlantKind::Bush), 5000);
  EXPECT_EQ(plant_default_leaves(PlantKind::Conifer), 20000);
  for (PlantKind kind : kKinds) {
    const double n = static_cast<double>(leaf_count(plant(kind, 0)));
    const double want = plant_default_leaves(kind);
    EXPECT_NEAR(n, want, 0.1 * want) << plant_kind_name(kind);
  }
}

TEST(Plants, Deterministic) {
  for (PlantKind kind : kKinds) {
    Scene a = plant(kind, 2000, 7), b = plant(kind, 2000, 7), c = plant(kind, 2000, 8);
    EXPECT_TRUE(same_geometry(a, b)) << plant_kind_name(kind);
    EXPECT_EQ(a.hierarchy.leaf_branch, b.hierarchy.leaf_branch);
    EXPECT_EQ(a.hierarchy.branch_diameter, b.hierarchy.branch_diameter);
    EXPECT_EQ(a.textures[0].rgba, b.textures[0].rgba);
    EXPECT_FALSE(same_geometry(a, c)) << plant_kind_name(kind);
  }
}

TEST(Plants, MeshLayoutAndArrays) {
  for (PlantKind kind : kKinds) {
    Scene s = plant(kind, 1000);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].name, "leaves");
    EXPECT_EQ(s.meshes[1].name, "bark");
    EXPECT_EQ(s.report.source, std::string("sample:") + plant_kind_name(kind));
    for (const Mesh& m : s.meshes) {
      const size_t t = m.triangle_count();
      EXPECT_EQ(m.indices.size() % 3, 0u);
      EXPECT_EQ(m.primitive_ids.size(), t);
      EXPECT_EQ(m.cluster_ids.size(), t);
      EXPECT_EQ(m.roles.size(), t);
      EXPECT_EQ(m.normals.size(), m.positions.size());
      EXPECT_EQ(m.uvs.size(), m.positions.size());
      for (uint32_t i : m.indices)
        ASSERT_LT(i, m.positions.size());
      for (uint32_t c : m.cluster_ids)
        EXPECT_EQ(c, 1u);
      const Role want = &m == &s.meshes[0] ? Role::Foliage : Role::Wood;
      for (Role r : m.roles)
        ASSERT_EQ(r, want);
    }
  }
}

TEST(Plants, LeavesAreSeparateQuads) {
  Scene s = plant(PlantKind::Tree, 500);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 4 * leaf_count(s));
  for (size_t l = 0; l < leaf_count(s); ++l) {
    const uint32_t b = static_cast<uint32_t>(4 * l);
    const std::vector<uint32_t> want = {b, b + 1, b + 2, b, b + 2, b + 3};
    ASSERT_TRUE(std::equal(want.begin(), want.end(), m.indices.begin() + 6 * l));
    const glm::vec3 n = m.normals[b];
    const glm::vec3 e1 = m.positions[b + 1] - m.positions[b];
    const glm::vec3 e2 = m.positions[b + 3] - m.positions[b];
    EXPECT_NEAR(glm::dot(n, glm::normalize(e1)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(n, glm::normalize(e2)), 0.0f, 1e-4f);
    EXPECT_GT(glm::dot(glm::cross(e1, e2), n), 0.0f);  // counter-clockwise seen from n
    for (int k = 1; k < 4; ++k)
      EXPECT_EQ(m.normals[b + k], n);
    EXPECT_EQ(m.uvs[b], glm::vec2(0, 1));
    EXPECT_EQ(m.uvs[b + 2], glm::vec2(1, 0));
  }
}

TEST(Plants, PrimitiveIdsAreConnectedComponents) {
  for (PlantKind kind : kKinds) {
    Scene s = plant(kind, 3000, 3);
    std::vector<std::vector<uint32_t>> ref = reference_ids(s);
    for (size_t i = 0; i < s.meshes.size(); ++i)
      EXPECT_EQ(s.meshes[i].primitive_ids, ref[i]) << plant_kind_name(kind) << " mesh " << i;
    // Leaves are 1..L in mesh order; one bark component per branch.
    const size_t leaves = leaf_count(s);
    EXPECT_EQ(s.meshes[0].primitive_ids.back(), leaves);
    EXPECT_EQ(s.max_primitive_id(), leaves + s.hierarchy.branch_parent.size());
  }
}

TEST(Plants, HierarchyIsConsistent) {
  for (PlantKind kind : kKinds) {
    Scene s = plant(kind, 4000, 5);
    const Hierarchy& h = s.hierarchy;
    const int32_t branches = static_cast<int32_t>(h.branch_parent.size());
    ASSERT_GT(branches, 1);
    ASSERT_EQ(h.branch_diameter.size(), h.branch_parent.size());
    ASSERT_EQ(h.leaf_branch.size(), leaf_count(s));
    EXPECT_EQ(h.branch_parent[0], -1);
    for (int32_t b = 1; b < branches; ++b) {
      const int32_t p = h.branch_parent[b];
      ASSERT_GE(p, 0) << "only branch 0 is a root";
      ASSERT_LT(p, b) << "parents precede children, so the parent links form a tree";
      EXPECT_LE(h.branch_diameter[b], h.branch_diameter[p]);
    }
    for (float d : h.branch_diameter)
      EXPECT_GT(d, 0.0f);
    for (int32_t b : h.leaf_branch) {
      ASSERT_GE(b, 0);
      ASSERT_LT(b, branches);
    }
  }
}

TEST(Plants, NormalsUnitAndFinite) {
  for (PlantKind kind : kKinds) {
    Scene s = plant(kind, 2000);
    for (const Mesh& m : s.meshes) {
      for (const glm::vec3& n : m.normals) {
        ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
      }
      for (const glm::vec3& p : m.positions)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    }
  }
}

TEST(Plants, SizeAndBounds) {
  struct Want {
    PlantKind kind;
    float min_h, max_h;
  };
  for (Want w : {Want{PlantKind::Tree, 4, 10}, Want{PlantKind::Bush, 0.8f, 3},
                 Want{PlantKind::Conifer, 5, 12}}) {
    for (int leaves : {100, 10000, 200000}) {
      Scene s = plant(w.kind, leaves);
      const Bounds all = s.bounds(), foliage = s.bounds(Role::Foliage);
      EXPECT_NEAR(all.min.y, 0.0f, 1e-4f);
      EXPECT_GE(all.max.y, w.min_h) << plant_kind_name(w.kind) << " " << leaves;
      EXPECT_LE(all.max.y, w.max_h) << plant_kind_name(w.kind) << " " << leaves;
      EXPECT_LT(std::fabs(all.center().x), 0.25f * all.max.y);
      EXPECT_LT(std::fabs(all.center().z), 0.25f * all.max.y);
      ASSERT_FALSE(foliage.empty());
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(foliage.min[k], all.min[k]);
        EXPECT_LE(foliage.max[k], all.max[k]);
      }
    }
  }
}

TEST(Plants, LeavesShrinkAsTheyMultiply) {
  auto leaf_length = [](const Scene& s) {
    const Mesh& m = s.meshes[0];
    double sum = 0;
    for (size_t b = 0; b < m.positions.size(); b += 4)
      sum += glm::length(m.positions[b + 3] - m.positions[b]);
    return sum / (m.positions.size() / 4);
  };
  for (PlantKind kind : kKinds)
    EXPECT_LT(leaf_length(plant(kind, 40000)), 0.6 * leaf_length(plant(kind, 4000)));
}

TEST(Plants, MaterialsAndTextures) {
  for (PlantKind kind : kKinds) {
    Scene s = plant(kind, 500);
    const Material& leaves = s.materials.at(s.meshes[0].material);
    const Material& bark = s.materials.at(s.meshes[1].material);
    EXPECT_EQ(leaves.name, "leaves");
    EXPECT_EQ(leaves.alpha_mode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(leaves.alpha_cutoff, 0.5f);
    EXPECT_TRUE(leaves.double_sided);
    EXPECT_EQ(bark.name, "bark");
    EXPECT_EQ(bark.alpha_mode, AlphaMode::Opaque);
    EXPECT_FALSE(bark.double_sided);
    EXPECT_GT(bark.base_color.r, bark.base_color.b);  // brown
    const Texture& t = s.textures.at(leaves.base_color_texture);
    ASSERT_EQ(t.rgba.size(), static_cast<size_t>(t.width) * t.height * 4);
    auto texel = [&](int x, int y, int c) {
      return t.rgba[(static_cast<size_t>(y) * t.width + x) * 4 + c];
    };
    EXPECT_EQ(texel(0, 0, 3), 0);                         // corner outside the blade
    EXPECT_EQ(texel(t.width / 2, t.height / 2, 3), 255);  // centre inside
    EXPECT_GT(texel(t.width / 3, t.height / 2, 1), texel(t.width / 3, t.height / 2, 0));  // green
  }
}

TEST(Plants, LeafTextureShapes) {
  Texture leaf = make_leaf_texture(LeafTextureKind::Broadleaf);
  Texture needle = make_leaf_texture(LeafTextureKind::Needle);
  EXPECT_EQ(leaf.width, 128);
  EXPECT_EQ(leaf.height, 128);
  EXPECT_EQ(needle.height, 128);
  EXPECT_LT(needle.width, needle.height);
  auto coverage = [](const Texture& t) {
    size_t n = 0;
    for (size_t i = 3; i < t.rgba.size(); i += 4)
      n += t.rgba[i] >= 128;
    return static_cast<double>(n) / (t.width * t.height);
  };
  EXPECT_GT(coverage(leaf), 0.4);  // an ovate blade, not a sliver
  EXPECT_LT(coverage(leaf), 0.8);  // and not the whole quad
  EXPECT_GT(coverage(needle), 0.5);
  EXPECT_EQ(make_leaf_texture(LeafTextureKind::Broadleaf).rgba, leaf.rgba);
  Texture bark = make_bark_texture();
  EXPECT_EQ(bark.rgba.size(), static_cast<size_t>(bark.width) * bark.height * 4);
}

TEST(Plants, LeafRangeExtremes) {
  EXPECT_EQ(leaf_count(plant(PlantKind::Conifer, 100)), 100u);
  for (PlantKind kind : kKinds) {
    for (int bad : {99, 2000001, -1}) {
      try {
        plant(kind, bad);
        FAIL() << "leaves " << bad << " accepted";
      } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--leaves");
        EXPECT_NE(std::string(e.what()).find("[100, 2000000]"), std::string::npos);
      }
    }
  }
}

TEST(Plants, MaximumLeafCount) {
  Scene s = plant(PlantKind::Tree, 2000000);
  EXPECT_NEAR(static_cast<double>(leaf_count(s)), 2e6, 2e5);
  EXPECT_EQ(s.meshes[0].positions.size(), 4 * leaf_count(s));
}

TEST(Plants, ParseKind) {
  for (PlantKind kind : kKinds)
    EXPECT_EQ(parse_plant_kind(plant_kind_name(kind)), kind);
  for (const char* bad : {"", "Tree", "oak", "tree "}) {
    try {
      parse_plant_kind(bad);
      FAIL() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "--kind");
      EXPECT_NE(std::string(e.what()).find("tree, bush, conifer"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace sylva

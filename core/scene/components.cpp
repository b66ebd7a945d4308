#include "core/scene/components.h"

#include <numeric>

#include "core/error.h"
#include "core/scene/instances.h"

namespace sylva {
namespace {

// Union-find with path halving and union by index (the smaller root wins), so finds stay
// short without a rank array.
uint32_t find(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

void unite(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
  a = find(parent, a);
  b = find(parent, b);
  if (a < b)
    parent[b] = a;
  else if (b < a)
    parent[a] = b;
}

// Ids 1, 2, ... over `meshes` in order.
void assign_plant_ids(Scene& scene, const std::vector<uint32_t>& meshes) {
  uint32_t next = 1;
  std::vector<uint32_t> parent, id_of_root;
  for (uint32_t mi : meshes) {
    Mesh& mesh = scene.meshes[mi];
    const size_t nv = mesh.positions.size();
    const size_t nt = mesh.triangle_count();
    parent.resize(nv);
    std::iota(parent.begin(), parent.end(), 0u);
    for (size_t t = 0; t < nt; ++t) {
      const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1],
                     c = mesh.indices[3 * t + 2];
      SYLVA_CHECK(a < nv && b < nv && c < nv, "index out of range in assign_primitive_ids");
      unite(parent, a, b);
      unite(parent, a, c);
    }
    id_of_root.assign(nv, 0u);
    mesh.primitive_ids.resize(nt);
    for (size_t t = 0; t < nt; ++t) {
      const uint32_t root = find(parent, mesh.indices[3 * t]);
      if (id_of_root[root] == 0) id_of_root[root] = next++;
      mesh.primitive_ids[t] = id_of_root[root];
    }
  }
}

}  // namespace

void assign_primitive_ids(Scene& scene) {
  for (size_t p = 0; p < scene.plant_count(); ++p)
    assign_plant_ids(scene, plant_meshes(scene, p));
}

}  // namespace sylva

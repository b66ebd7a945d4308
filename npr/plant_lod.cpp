#include "npr/plant_lod.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/cache/content_hash.h"
#include "core/error.h"
#include "core/random.h"
#include "core/scene/instances.h"
#include "lod_code_version.h"  // generated: SYLVA_LOD_CODE_VERSION
#include "npr/open_mesh.h"

namespace sylva {

namespace {

using OMesh = OpenTriMesh;

// A triangle soup being decimated, with each vertex's and face's origin in the plant mesh.
struct Decimating {
  OMesh mesh;
  OpenMesh::VPropHandleT<uint32_t> source;
  OpenMesh::FPropHandleT<uint32_t> triangle;
  Decimating() {
    mesh.add_property(source);
    mesh.add_property(triangle);
  }
};

void add_triangle(Decimating& d, std::vector<OMesh::VertexHandle>& handle, const Mesh& m,
                  uint32_t t) {
  std::array<OMesh::VertexHandle, 3> f;
  for (int k = 0; k < 3; ++k) {
    const uint32_t v = m.indices[3 * t + size_t(k)];
    if (!handle[v].is_valid()) {
      const glm::vec3 p = m.positions[v];
      handle[v] = d.mesh.add_vertex(OMesh::Point(p.x, p.y, p.z));
      d.mesh.property(d.source, handle[v]) = v;
    }
    f[size_t(k)] = handle[v];
  }
  if (!can_add_face(d.mesh, f)) {
    for (auto& h : f) {
      const OMesh::VertexHandle copy = d.mesh.add_vertex(d.mesh.point(h));
      d.mesh.property(d.source, copy) = d.mesh.property(d.source, h);
      h = copy;
    }
  }
  const OMesh::FaceHandle face = d.mesh.add_face(f[0], f[1], f[2]);
  if (face.is_valid()) d.mesh.property(d.triangle, face) = t;
}

// Quadric decimation (halfedge collapses, no face turned by more than 45 degrees) to
// `target` faces.
void decimate_to(Decimating& d, size_t target) {
  const size_t faces = d.mesh.n_faces();
  if (faces <= target) return;
  d.mesh.request_face_normals();
  d.mesh.update_face_normals();
  OpenMesh::Decimater::DecimaterT<OMesh> decimater(d.mesh);
  OpenMesh::Decimater::ModQuadricT<OMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<OMesh>::Handle no_flips;
  decimater.add(quadric);
  decimater.add(no_flips);
  decimater.module(quadric).unset_max_err();
  decimater.module(no_flips).set_max_normal_deviation(45.0);
  decimater.initialize();
  decimater.decimate_to_faces(0, std::max<size_t>(1, target));
  d.mesh.garbage_collection();
}

// The decimated part into `out`: vertices at their own positions.
void append_decimated(const Decimating& d, LodMesh& out) {
  const auto base = uint32_t(out.positions.size());
  for (const auto v : d.mesh.vertices()) {
    const auto& p = d.mesh.point(v);
    out.source.push_back(d.mesh.property(d.source, v));
    out.positions.emplace_back(float(p[0]), float(p[1]), float(p[2]));
  }
  for (const auto f : d.mesh.faces()) {
    for (const auto v : f.vertices())
      out.indices.push_back(base + uint32_t(v.idx()));
    out.triangle_source.push_back(d.mesh.property(d.triangle, f));
  }
}

// A small foliage component (a leaf) of one mesh: its triangles and vertices.
struct Leaf {
  std::vector<uint32_t> triangles, vertices;
  glm::vec3 centre{0.0f};
};

// Whether leaf `id` survives at keep fraction `f`: a seeded hash against f, so a leaf kept at
// one level is kept at every coarser one that keeps more.
bool keeps(uint32_t id, double f) {
  uint64_t state = 0x5eed1eafULL ^ (uint64_t(id) << 17);
  return uniform01(state) < f;
}

// The leaves kept at fraction f, enlarged by `scale` about their centres, into `out`.
void append_pruned(const std::vector<Leaf>& leaves, const std::vector<uint32_t>& ids, const Mesh& m,
                   double f, float scale, LodMesh& out) {
  for (size_t l = 0; l < leaves.size(); ++l) {
    if (!keeps(ids[l], f)) continue;
    const Leaf& leaf = leaves[l];
    std::map<uint32_t, uint32_t> at;
    for (uint32_t v : leaf.vertices) {
      at[v] = uint32_t(out.positions.size());
      out.source.push_back(v);
      out.positions.push_back(leaf.centre + scale * (m.positions[v] - leaf.centre));
    }
    for (uint32_t t : leaf.triangles) {
      for (int k = 0; k < 3; ++k)
        out.indices.push_back(at[m.indices[3 * t + size_t(k)]]);
      out.triangle_source.push_back(t);
    }
  }
}

// Mesh m's leaves (foliage components of at most kLodLeafTriangles triangles), their ids, and
// the triangles left for decimation.
void split_mesh(const Mesh& m, std::vector<Leaf>& leaves, std::vector<uint32_t>& ids,
                std::vector<uint32_t>& rest) {
  std::map<uint32_t, size_t> size;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    if (m.roles[t] == Role::Foliage) ++size[m.primitive_ids[t]];
  std::map<uint32_t, size_t> leaf_of;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const uint32_t id = m.primitive_ids[t];
    if (m.roles[t] != Role::Foliage || size[id] > kLodLeafTriangles) {
      rest.push_back(uint32_t(t));
      continue;
    }
    auto [it, added] = leaf_of.emplace(id, leaves.size());
    if (added) {
      leaves.emplace_back();
      ids.push_back(id);
    }
    leaves[it->second].triangles.push_back(uint32_t(t));
  }
  for (Leaf& leaf : leaves) {
    for (uint32_t t : leaf.triangles)
      for (int k = 0; k < 3; ++k)
        leaf.vertices.push_back(m.indices[3 * t + size_t(k)]);
    std::sort(leaf.vertices.begin(), leaf.vertices.end());
    leaf.vertices.erase(std::unique(leaf.vertices.begin(), leaf.vertices.end()),
                        leaf.vertices.end());
    glm::dvec3 sum(0.0);
    for (uint32_t v : leaf.vertices)
      sum += glm::dvec3(m.positions[v]);
    leaf.centre = glm::vec3(sum / double(leaf.vertices.size()));
  }
}

// A connected piece of the triangles left for decimation (a branch, a frond) and its size.
struct Piece {
  std::vector<uint32_t> triangles;
  float diagonal = 0.0f;
};

// The pieces of `rest` by primitive id, largest first (ties: first triangle).
std::vector<Piece> pieces_of(const Mesh& m, const std::vector<uint32_t>& rest) {
  std::map<uint32_t, size_t> index;
  std::vector<Piece> pieces;
  std::vector<Bounds> bounds;
  for (uint32_t t : rest) {
    auto [it, added] = index.emplace(m.primitive_ids[t], pieces.size());
    if (added) pieces.emplace_back(), bounds.emplace_back();
    pieces[it->second].triangles.push_back(t);
    for (int k = 0; k < 3; ++k)
      bounds[it->second].extend(m.positions[m.indices[3 * t + size_t(k)]]);
  }
  for (size_t i = 0; i < pieces.size(); ++i)
    pieces[i].diagonal = bounds[i].diagonal();
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const Piece& a, const Piece& b) { return a.diagonal > b.diagonal; });
  return pieces;
}

// The pieces at `target` triangles: the largest ones that fit (twigs go first, the trunk
// stays), decimated when the largest alone is more.
void append_pieces(const Mesh& m, const std::vector<Piece>& pieces, size_t target, LodMesh& out) {
  Decimating d;
  std::vector<OMesh::VertexHandle> handle(m.positions.size());
  size_t kept = 0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    if (i > 0 && kept + pieces[i].triangles.size() > target) break;
    for (uint32_t t : pieces[i].triangles)
      add_triangle(d, handle, m, t);
    kept += pieces[i].triangles.size();
  }
  decimate_to(d, target);
  append_decimated(d, out);
}

// Levels 1..kLodLevels of one mesh.
std::vector<LodMesh> mesh_levels(const Mesh& m) {
  std::vector<Leaf> leaves;
  std::vector<uint32_t> ids, rest;
  split_mesh(m, leaves, ids, rest);
  const std::vector<Piece> pieces = pieces_of(m, rest);
  std::vector<LodMesh> out(kLodLevels);
  for (int l = 1; l <= kLodLevels; ++l) {
    LodMesh& lod = out[size_t(l - 1)];
    append_pruned(leaves, ids, m, std::pow(0.5, l), float(std::pow(std::sqrt(2.0), l)), lod);
    append_pieces(m, pieces, std::max<size_t>(1, rest.size() >> l), lod);
  }
  return out;
}

std::string lod_key(const Scene& plant) {
  ContentHash h;
  h.add(std::string(SYLVA_LOD_CODE_VERSION));
  h.add(uint64_t(plant.meshes.size()));
  for (const Mesh& m : plant.meshes) {
    h.add(m.positions);
    h.add(m.indices);
    h.add(m.primitive_ids);
    h.add(m.roles);
  }
  return h.hex();
}

std::string serialize(const PlantLod& lod) {
  ByteWriter w;
  for (const std::vector<LodMesh>& level : lod.levels)
    for (const LodMesh& m : level) {
      w.put(m.source);
      w.put(m.positions);
      w.put(m.indices);
      w.put(m.triangle_source);
    }
  return w.take();
}

// False when the payload does not fit the plant (counts, indices, finite positions).
bool deserialize(const std::string& payload, const Scene& plant, PlantLod& out) {
  ByteReader in(payload);
  out.levels.assign(kLodLevels, std::vector<LodMesh>(plant.meshes.size()));
  for (std::vector<LodMesh>& level : out.levels)
    for (size_t k = 0; k < level.size(); ++k) {
      LodMesh& m = level[k];
      if (!in.get(m.source) || !in.get(m.positions) || !in.get(m.indices) ||
          !in.get(m.triangle_source))
        return false;
      const Mesh& src = plant.meshes[k];
      if (m.source.size() != m.positions.size() || m.indices.size() % 3 != 0 ||
          m.triangle_source.size() * 3 != m.indices.size())
        return false;
      for (uint32_t v : m.source)
        if (v >= src.positions.size()) return false;
      for (uint32_t i : m.indices)
        if (i >= m.positions.size()) return false;
      for (uint32_t t : m.triangle_source)
        if (t >= src.triangle_count()) return false;
      for (const glm::vec3& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    }
  return in.done();
}

}  // namespace

PlantLod make_plant_lod(const Scene& plant) {
  for (const Mesh& m : plant.meshes)
    SYLVA_CHECK(
        m.roles.size() == m.triangle_count() && m.primitive_ids.size() == m.triangle_count(),
        "make_plant_lod needs roles and primitive ids (finish_scene)");
  PlantLod lod;
  lod.levels.assign(kLodLevels, {});
  for (const Mesh& m : plant.meshes) {
    std::vector<LodMesh> levels = mesh_levels(m);
    for (int l = 0; l < kLodLevels; ++l)
      lod.levels[size_t(l)].push_back(std::move(levels[size_t(l)]));
  }
  return lod;
}

std::vector<PlantLod> scene_lods(const Scene& scene, const ResultCache* cache) {
  std::vector<PlantLod> out;
  if (!scene.instanced()) return out;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    const Scene plant = plant_scene(scene, p, false);
    const std::string key = cache ? lod_key(plant) : "";
    PlantLod lod;
    if (cache)
      if (std::optional<std::string> bytes = cache->load("lod", key))
        if (deserialize(*bytes, plant, lod)) {
          out.push_back(std::move(lod));
          continue;
        }
    lod = make_plant_lod(plant);
    if (cache) cache->store("lod", key, serialize(lod));
    out.push_back(std::move(lod));
  }
  return out;
}

}  // namespace sylva

// Marching cubes (Lorensen & Cline 1987, as used by Luft et al. §3.1) on the zero level
// set of a ScalarGrid. The per-configuration polygons are not typed in from the classic
// 256-case table: they are derived once at start-up from the cube's faces. On every face
// the sign changes are joined into oriented segments; ambiguous faces (diagonal corners
// alike) are resolved with the asymptotic decider (Nielson & Hamann 1991), which depends
// only on the face's four values, so the two cells sharing a face always agree and the
// mesh has no cracks (unlike the classic table, whose ambiguous cases can leave holes).
// Each cell's segments close into loops, triangulated as fans (or, for the rare loop that
// crosses faces twice everywhere, around a centre vertex). Ambiguities inside a cell
// (tunnels of the trilinear interpolant) are not resolved; the mesh is still closed.
// Inside is value > 0: exact zeros are outside, and the surface passes through them.
#include "npr/implicit_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.h"

namespace sylva {
namespace {

// Corner i of a cell sits at offset (i & 1, (i >> 1) & 1, (i >> 2) & 1).
// Edge 4k + j runs along axis k from the j-th corner (ascending) whose bit k is 0.
struct CellCase {
  uint8_t n_loops = 0;
  std::array<uint8_t, 4> loop_size{};  // a loop has >= 3 edges, so at most 4 loops
  std::array<bool, 4> loop_centre{};   // triangulate around an added centre vertex
  std::array<uint8_t, 12> edges{};     // loops one after another, counter-clockwise from outside
};

struct Tables {
  std::array<std::array<uint8_t, 2>, 12> edge_corners{};
  std::array<std::array<uint8_t, 4>, 6> face_corners{};  // counter-clockwise seen from outside
  std::array<uint8_t, 256> n_ambiguous{};
  std::array<std::array<uint8_t, 6>, 256> ambiguous_faces{};
  std::array<uint32_t, 256> case_offset{};  // + bit mask of "join inside" over ambiguous faces
  std::vector<CellCase> cases;
};

int edge_between(const Tables& t, int a, int b) {
  for (int e = 0; e < 12; ++e) {
    const auto& c = t.edge_corners[size_t(e)];
    if ((c[0] == a && c[1] == b) || (c[0] == b && c[1] == a)) return e;
  }
  SYLVA_CHECK(false, "corners do not share a cell edge");
  return -1;
}

bool face_is_ambiguous(const Tables& t, int config, int f) {
  const auto& fc = t.face_corners[size_t(f)];
  const bool i0 = (config >> fc[0]) & 1, i1 = (config >> fc[1]) & 1;
  const bool i2 = (config >> fc[2]) & 1, i3 = (config >> fc[3]) & 1;
  return i0 == i2 && i1 == i3 && i0 != i1;
}

int edge_faces(const Tables& t, int e) {
  int mask = 0;
  for (int f = 0; f < 6; ++f) {
    const auto& fc = t.face_corners[size_t(f)];
    const auto& ec = t.edge_corners[size_t(e)];
    const bool has0 = std::find(fc.begin(), fc.end(), ec[0]) != fc.end();
    const bool has1 = std::find(fc.begin(), fc.end(), ec[1]) != fc.end();
    if (has0 && has1) mask |= 1 << f;
  }
  return mask;
}

// A loop that crosses one face twice (through both segments of an ambiguous face) has
// two non-adjacent vertices on that face. A fan diagonal between them would lie in the
// face, where the neighbouring cell may use the same diagonal: four triangles on one
// edge. So the fan starts at a vertex on no such face (rotating the loop), or, when every
// vertex touches one, the loop is fanned around an added centre vertex instead.
void choose_fan_apex(const Tables& t, uint8_t* loop, int n, bool& centre) {
  std::array<int, 6> visits{};
  for (int i = 0; i < n; ++i) {
    const int shared = edge_faces(t, loop[i]) & edge_faces(t, loop[(i + 1) % n]);
    SYLVA_CHECK(shared != 0 && (shared & (shared - 1)) == 0, "loop step not within one face");
    for (int f = 0; f < 6; ++f)
      visits[size_t(f)] += (shared >> f) & 1;
  }
  int twice = 0;
  for (int f = 0; f < 6; ++f)
    twice |= int(visits[size_t(f)] > 1) << f;
  centre = false;
  if (twice == 0) return;
  for (int i = 0; i < n; ++i) {
    if ((edge_faces(t, loop[i]) & twice) == 0) {
      std::rotate(loop, loop + i, loop + n);
      return;
    }
  }
  centre = true;
}

// Segments run from the edge where (walking a face counter-clockwise seen from outside)
// the sign goes outside -> inside to an edge where it goes inside -> outside; this keeps
// the inside on one fixed side, so the closed loops come out counter-clockwise seen from
// the outside region.
CellCase make_case(const Tables& t, int config, int join_mask) {
  std::array<int, 12> next;
  next.fill(-1);
  int ambiguous_index = 0;
  for (int f = 0; f < 6; ++f) {
    const auto& fc = t.face_corners[size_t(f)];
    std::array<bool, 4> in{};
    std::array<int, 4> fe{};
    for (int i = 0; i < 4; ++i) {
      in[size_t(i)] = (config >> fc[size_t(i)]) & 1;
      fe[size_t(i)] = edge_between(t, fc[size_t(i)], fc[size_t((i + 1) % 4)]);
    }
    std::array<int, 4> enter{}, leave{};  // positions (0..3) of the face's crossing edges
    int n_enter = 0, n_leave = 0;
    for (int i = 0; i < 4; ++i) {
      const bool a = in[size_t(i)], b = in[size_t((i + 1) % 4)];
      if (!a && b) enter[size_t(n_enter++)] = i;
      if (a && !b) leave[size_t(n_leave++)] = i;
    }
    SYLVA_CHECK(n_enter == n_leave, "unbalanced face crossings");
    if (n_enter == 1) {
      next[size_t(fe[size_t(enter[0])])] = fe[size_t(leave[0])];
    } else if (n_enter == 2) {
      const bool join = (join_mask >> ambiguous_index++) & 1;
      for (int k = 0; k < 2; ++k) {
        const int i = enter[size_t(k)];
        // Around the inside corner i+1 alone (separate), or around the outside corner i.
        const int partner = join ? (i + 3) % 4 : (i + 1) % 4;
        next[size_t(fe[size_t(i)])] = fe[size_t(partner)];
      }
    }
  }
  CellCase c;
  std::array<bool, 12> used{};
  int n_edges = 0;
  for (int start = 0; start < 12; ++start) {
    if (next[size_t(start)] < 0 || used[size_t(start)]) continue;
    SYLVA_CHECK(c.n_loops < 4, "too many loops in a cell");
    int size = 0;
    for (int e = start; !used[size_t(e)]; e = next[size_t(e)]) {
      SYLVA_CHECK(e >= 0, "open contour in a cell");
      used[size_t(e)] = true;
      c.edges[size_t(n_edges++)] = uint8_t(e);
      ++size;
    }
    SYLVA_CHECK(size >= 3, "contour loop shorter than a triangle");
    choose_fan_apex(t, &c.edges[size_t(n_edges - size)], size, c.loop_centre[c.n_loops]);
    c.loop_size[c.n_loops++] = uint8_t(size);
  }
  return c;
}

Tables build_tables() {
  Tables t;
  for (int k = 0, e = 0; k < 3; ++k) {
    for (int a = 0; a < 8; ++a) {
      if ((a >> k) & 1) continue;
      t.edge_corners[size_t(e++)] = {uint8_t(a), uint8_t(a | (1 << k))};
    }
  }
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;  // u x v = +k
    for (int side = 0; side < 2; ++side) {
      std::array<uint8_t, 4> c{};
      const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // counter-clockwise about +k
      for (int i = 0; i < 4; ++i) {
        c[size_t(i)] = uint8_t((side << k) | (uv[i][0] << u) | (uv[i][1] << v));
      }
      if (side == 0) std::reverse(c.begin(), c.end());  // seen from -k
      t.face_corners[size_t(2 * k + side)] = c;
    }
  }
  for (int config = 0; config < 256; ++config) {
    t.case_offset[size_t(config)] = uint32_t(t.cases.size());
    for (int f = 0; f < 6; ++f) {
      if (face_is_ambiguous(t, config, f)) {
        t.ambiguous_faces[size_t(config)][t.n_ambiguous[size_t(config)]++] = uint8_t(f);
      }
    }
    for (int mask = 0; mask < (1 << t.n_ambiguous[size_t(config)]); ++mask) {
      t.cases.push_back(make_case(t, config, mask));
    }
  }
  return t;
}

const Tables& tables() {
  static const Tables t = build_tables();
  return t;
}

bool inside(float v) {
  return v > 0.0f;
}  // exact zeros (and NaN) count as outside

class Extractor {
 public:
  explicit Extractor(const ScalarGrid& grid)
      : m_grid(grid), m_nx(grid.dims.x), m_ny(grid.dims.y), m_plane(size_t(m_nx) * size_t(m_ny)) {
    for (auto& p : m_planes) {
      p.xe.assign(m_plane, -1);
      p.ye.assign(m_plane, -1);
      p.corner.assign(m_plane, -1);
      p.in.assign(m_plane, 0);
      p.code.assign(m_plane, 0);
    }
    m_ze.assign(m_plane, -1);
  }

  SurfaceMesh run() {
    const int nz = m_grid.dims.z;
    Plane* bottom = &m_planes[0];
    Plane* top = &m_planes[1];
    std::fill(bottom->corner.begin(), bottom->corner.end(), -1);
    fill_plane_edges(*bottom, 0);
    for (int z = 0; z + 1 < nz; ++z) {
      std::fill(top->corner.begin(), top->corner.end(), -1);
      fill_plane_edges(*top, z + 1);
      fill_z_edges(*bottom, *top, z);
      polygonise_layer(*bottom, *top, z);
      std::swap(bottom, top);
    }
    drop_unused_vertices();
    return std::move(m_mesh);
  }

 private:
  struct Plane {
    std::vector<int32_t> xe, ye, corner;  // vertex id per node (edge starting there) or -1
    std::vector<uint8_t> in;              // per node: inside
    std::vector<uint8_t> code;            // per cell (x, y): inside bits of its 4 corners here
  };

  int32_t corner_vertex(std::vector<int32_t>& corners, size_t i, const glm::vec3& p) {
    if (corners[i] < 0) corners[i] = add_vertex(p);
    return corners[i];
  }

  int32_t add_vertex(const glm::vec3& p) {
    SYLVA_CHECK(m_mesh.positions.size() < size_t(INT32_MAX), "too many surface vertices");
    m_mesh.positions.push_back(p);
    return int32_t(m_mesh.positions.size() - 1);
  }

  // The vertex on the grid edge a -> b (along `axis`), which changes sign. A vertex that
  // lands on a grid node (exact zero or rounding) is that node's vertex, so no two
  // vertices share a position and degenerate triangles show up as repeated ids.
  int32_t edge_vertex(int x, int y, int za, int zb, int axis, std::vector<int32_t>& corners_a,
                      size_t ia, std::vector<int32_t>& corners_b, size_t ib) {
    const int xb = x + (axis == 0), yb = y + (axis == 1);
    const float va = m_grid.at(x, y, za), vb = m_grid.at(xb, yb, zb);
    const bool in_a = inside(va);
    const glm::vec3 pa = m_grid.position(x, y, za), pb = m_grid.position(xb, yb, zb);
    // t from the inside node p towards the outside node q.
    const double vp = in_a ? va : vb, vq = in_a ? vb : va;
    double t = vp / (vp - vq);
    if (!(t == t)) t = 0.5;  // infinite samples: no better guess, but never NaN
    t = std::clamp(t, 0.0, 1.0);
    const double lo = in_a ? pa[axis] : pb[axis], hi = in_a ? pb[axis] : pa[axis];
    const float c = float(lo + t * (hi - lo));
    if (c == float(lo) || c == float(hi)) {
      const bool at_a = (c == pa[axis]);
      return at_a ? corner_vertex(corners_a, ia, pa) : corner_vertex(corners_b, ib, pb);
    }
    glm::vec3 p = pa;
    p[axis] = c;
    return add_vertex(p);
  }

  void fill_plane_edges(Plane& plane, int z) {
    const float* v = m_grid.values.data() + m_plane * size_t(z);
    uint8_t* in = plane.in.data();
    for (size_t i = 0; i < m_plane; ++i)
      in[i] = inside(v[i]);
    const size_t nx = size_t(m_nx);
    for (int y = 0; y < m_ny; ++y) {
      const size_t row = nx * size_t(y);
      const bool last_row = y + 1 == m_ny;
      for (int x = 0; x < m_nx; ++x) {
        const size_t i = row + size_t(x);
        const bool last_col = x + 1 == m_nx;
        plane.xe[i] = !last_col && in[i] != in[i + 1]
                          ? edge_vertex(x, y, z, z, 0, plane.corner, i, plane.corner, i + 1)
                          : -1;
        plane.ye[i] = !last_row && in[i] != in[i + nx]
                          ? edge_vertex(x, y, z, z, 1, plane.corner, i, plane.corner, i + nx)
                          : -1;
        plane.code[i] =
            last_row || last_col
                ? 0
                : uint8_t(in[i] | in[i + 1] << 1 | in[i + nx] << 2 | in[i + nx + 1] << 3);
      }
    }
  }

  void fill_z_edges(Plane& bottom, Plane& top, int z) {
    for (int y = 0; y < m_ny; ++y) {
      for (int x = 0; x < m_nx; ++x) {
        const size_t i = size_t(x) + size_t(m_nx) * size_t(y);
        m_ze[i] = bottom.in[i] != top.in[i]
                      ? edge_vertex(x, y, z, z + 1, 2, bottom.corner, i, top.corner, i)
                      : -1;
      }
    }
  }

  void polygonise_layer(const Plane& bottom, const Plane& top, int z) {
    const Tables& tab = tables();
    // Where each cell edge's vertex id lives, relative to the cell's node index.
    std::array<const int32_t*, 12> arrays{};
    std::array<size_t, 12> offsets{};
    for (int e = 0; e < 12; ++e) {
      const int a = tab.edge_corners[size_t(e)][0];
      const int axis = e / 4;
      const bool upper = (a >> 2) & 1;
      const Plane& p = upper ? top : bottom;
      arrays[size_t(e)] = axis == 0 ? p.xe.data() : axis == 1 ? p.ye.data() : m_ze.data();
      offsets[size_t(e)] = size_t(a & 1) + size_t(m_nx) * size_t((a >> 1) & 1);
    }
    const std::array<size_t, 8> corner_offset = {
        0,       1,           size_t(m_nx),           size_t(m_nx) + 1,
        m_plane, m_plane + 1, m_plane + size_t(m_nx), m_plane + size_t(m_nx) + 1};
    const float* values = m_grid.values.data();
    const size_t layer_base = m_plane * size_t(z);
    for (int y = 0; y + 1 < m_ny; ++y) {
      for (int x = 0; x + 1 < m_nx; ++x) {
        const size_t node = size_t(x) + size_t(m_nx) * size_t(y);
        const int config = bottom.code[node] | top.code[node] << 4;
        if (config == 0 || config == 255) continue;
        int mask = 0;
        const int n_ambiguous = tab.n_ambiguous[size_t(config)];
        if (n_ambiguous > 0) {
          const float* v0 = values + layer_base + node;
          std::array<float, 8> v;
          for (int c = 0; c < 8; ++c)
            v[size_t(c)] = v0[corner_offset[size_t(c)]];
          for (int j = 0; j < n_ambiguous; ++j) {
            const auto& fc = tab.face_corners[tab.ambiguous_faces[size_t(config)][size_t(j)]];
            // Asymptotic decider: the bilinear saddle (ac - bd) / (a + c - b - d) is inside
            // iff ac > bd (the denominator is positive). Products of floats are exact in
            // double and symmetric, so the neighbouring cell decides the same way.
            const bool first_in = inside(v[fc[0]]);
            const double a = v[fc[first_in ? 0 : 1]], c = v[fc[first_in ? 2 : 3]];
            const double b = v[fc[first_in ? 1 : 0]], d = v[fc[first_in ? 3 : 2]];
            if (a * c > b * d) mask |= 1 << j;
          }
        }
        const CellCase& cc = tab.cases[tab.case_offset[size_t(config)] + size_t(mask)];
        int k = 0;
        for (int l = 0; l < cc.n_loops; ++l) {
          std::array<int32_t, 12> loop;
          const int n = cc.loop_size[size_t(l)];
          for (int i = 0; i < n; ++i, ++k) {
            const int e = cc.edges[size_t(k)];
            loop[size_t(i)] = arrays[size_t(e)][node + offsets[size_t(e)]];
            SYLVA_CHECK(loop[size_t(i)] >= 0, "missing edge vertex");
          }
          emit_polygon(loop.data(), n, cc.loop_centre[size_t(l)]);
        }
      }
    }
  }

  // A loop of vertex ids; ids repeat where vertices snapped onto a grid node. Consecutive
  // repeats are dropped and a loop pinched at a repeated vertex is split in two.
  void emit_polygon(const int32_t* in, int n_in, bool centre) {
    std::array<int32_t, 12> p;
    int n = 0;
    for (int i = 0; i < n_in; ++i) {
      if (n == 0 || p[size_t(n - 1)] != in[i]) p[size_t(n++)] = in[i];
    }
    while (n > 1 && p[0] == p[size_t(n - 1)])
      --n;
    if (n < 3) return;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 2; j < n; ++j) {
        if (p[size_t(i)] != p[size_t(j)]) continue;
        std::array<int32_t, 12> q;
        int m = 0;
        for (int r = j; r < n; ++r)
          q[size_t(m++)] = p[size_t(r)];
        for (int r = 0; r < i; ++r)
          q[size_t(m++)] = p[size_t(r)];
        emit_polygon(p.data() + i, j - i, centre);
        emit_polygon(q.data(), m, centre);
        return;
      }
    }
    if (centre && n > 3) {
      glm::dvec3 sum(0.0);
      for (int i = 0; i < n; ++i)
        sum += glm::dvec3(m_mesh.positions[size_t(p[size_t(i)])]);
      const int32_t c = add_vertex(glm::vec3(sum / double(n)));
      for (int i = 0; i < n; ++i)
        emit_triangle(c, p[size_t(i)], p[size_t((i + 1) % n)]);
      return;
    }
    if (n == 4) {
      // Split a quad along its shorter diagonal for better-shaped triangles.
      const auto& pos = m_mesh.positions;
      const glm::vec3 d02 = pos[size_t(p[2])] - pos[size_t(p[0])];
      const glm::vec3 d13 = pos[size_t(p[3])] - pos[size_t(p[1])];
      if (glm::dot(d13, d13) < glm::dot(d02, d02)) {
        emit_triangle(p[1], p[2], p[3]);
        emit_triangle(p[1], p[3], p[0]);
        return;
      }
    }
    for (int i = 1; i + 1 < n; ++i)
      emit_triangle(p[0], p[size_t(i)], p[size_t(i + 1)]);
  }

  void emit_triangle(int32_t a, int32_t b, int32_t c) {
    const auto& pos = m_mesh.positions;
    const glm::dvec3 pa(pos[size_t(a)]);
    const glm::dvec3 n =
        glm::cross(glm::dvec3(pos[size_t(b)]) - pa, glm::dvec3(pos[size_t(c)]) - pa);
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) return;  // collinear: zero area
    m_mesh.indices.push_back(uint32_t(a));
    m_mesh.indices.push_back(uint32_t(b));
    m_mesh.indices.push_back(uint32_t(c));
  }

  // Vertices whose triangles all degenerated are removed, keeping the order of the rest.
  void drop_unused_vertices() {
    std::vector<uint32_t> remap(m_mesh.positions.size(), 0);
    for (uint32_t i : m_mesh.indices)
      remap[i] = 1;
    uint32_t n = 0;
    for (auto& r : remap)
      r = r ? n++ : UINT32_MAX;
    if (n == m_mesh.positions.size()) return;
    std::vector<glm::vec3> kept;
    kept.reserve(n);
    for (size_t i = 0; i < remap.size(); ++i) {
      if (remap[i] != UINT32_MAX) kept.push_back(m_mesh.positions[i]);
    }
    m_mesh.positions = std::move(kept);
    for (auto& i : m_mesh.indices)
      i = remap[i];
  }

  const ScalarGrid& m_grid;
  int m_nx, m_ny;
  size_t m_plane;
  std::array<Plane, 2> m_planes;
  std::vector<int32_t> m_ze;  // z-edges between the bottom and the top plane
  SurfaceMesh m_mesh;
};

}  // namespace

SurfaceMesh extract_isosurface(const ScalarGrid& grid) {
  if (grid.empty()) return {};
  SYLVA_CHECK(grid.dims.x >= 2 && grid.dims.y >= 2 && grid.dims.z >= 2, "grid dims must be >= 2");
  SYLVA_CHECK(grid.values.size() == size_t(grid.dims.x) * size_t(grid.dims.y) * size_t(grid.dims.z),
              "grid values do not match dims");
  SYLVA_CHECK(std::isfinite(grid.spacing) && grid.spacing > 0, "grid spacing must be > 0");
  SYLVA_CHECK(
      std::isfinite(grid.origin.x) && std::isfinite(grid.origin.y) && std::isfinite(grid.origin.z),
      "grid origin must be finite");
  return Extractor(grid).run();
}

}  // namespace sylva

#include "npr/leaf_pieces.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "core/error.h"

namespace sylva {

namespace {

// What a sample belongs to: its instance, its element and the cell of the plant's space it lies
// in (cells are fixed in world space, so the cut moves with the scene).
struct PieceKey {
  uint32_t instance, primitive;
  int32_t x, y, z;
  auto tie() const { return std::tie(instance, primitive, x, y, z); }
  bool operator<(const PieceKey& o) const { return tie() < o.tie(); }
  bool operator==(const PieceKey& o) const { return tie() == o.tie(); }
};

int32_t cell_of(float v, float cell) {
  const double c = std::floor(double(v) / double(cell));
  return int32_t(std::clamp(c, -2.0e9, 2.0e9));
}

// Area-weighted centre and covariance of samples[order[begin, end)], in double about the first
// sample (the positions may be far from the origin in a park).
LeafPiece make_piece(const SurfaceSamples& s, const std::vector<uint32_t>& order, size_t begin,
                     size_t end) {
  const glm::dvec3 origin(s.positions[order[begin]]);
  double w = 0.0;
  glm::dvec3 m(0.0);
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (size_t k = begin; k < end; ++k) {
    const uint32_t i = order[k];
    const double a = s.areas[i];
    const glm::dvec3 p = glm::dvec3(s.positions[i]) - origin;
    w += a;
    m += a * p;
    xx += a * p.x * p.x, xy += a * p.x * p.y, xz += a * p.x * p.z;
    yy += a * p.y * p.y, yz += a * p.y * p.z, zz += a * p.z * p.z;
  }
  LeafPiece piece;
  const glm::dvec3 c = m / w;
  piece.centre = glm::vec3(origin + c);
  const double cov[6] = {xx / w - c.x * c.x, xy / w - c.x * c.y, xz / w - c.x * c.z,
                         yy / w - c.y * c.y, yz / w - c.y * c.z, zz / w - c.z * c.z};
  for (int j = 0; j < 6; ++j)
    piece.cov[j] = float(cov[j]);
  // Rounding can leave a tiny negative variance for a flat piece.
  for (int j : {0, 3, 5})
    piece.cov[j] = std::max(piece.cov[j], 0.0f);
  piece.area = float(w);
  piece.cluster = s.clusters[order[begin]];
  piece.instance = s.instances.empty() ? 0 : s.instances[order[begin]];
  return piece;
}

// Keyed samples [begin, end) of one element: its extent (box diagonal) and area.
std::pair<float, double> element_size(const SurfaceSamples& s, const std::vector<uint32_t>& order,
                                      size_t begin, size_t end) {
  glm::vec3 lo(s.positions[order[begin]]), hi = lo;
  double area = 0.0;
  for (size_t k = begin; k < end; ++k) {
    lo = glm::min(lo, s.positions[order[k]]);
    hi = glm::max(hi, s.positions[order[k]]);
    area += s.areas[order[k]];
  }
  return {glm::length(hi - lo), area};
}

// The area-weighted median of the elements' extents (keyed by element, then cell): each run of
// one (instance, element) is an element; element 0 (none named) is left out.
float median_extent(const SurfaceSamples& s,
                    const std::vector<std::pair<PieceKey, uint32_t>>& keyed,
                    const std::vector<uint32_t>& order) {
  std::vector<std::pair<float, double>> sizes;
  for (size_t begin = 0; begin < keyed.size();) {
    const PieceKey& k = keyed[begin].first;
    size_t end = begin + 1;
    while (end < keyed.size() && keyed[end].first.instance == k.instance &&
           keyed[end].first.primitive == k.primitive)
      ++end;
    if (k.primitive != 0) sizes.push_back(element_size(s, order, begin, end));
    begin = end;
  }
  if (sizes.empty()) return 0.0f;
  std::sort(sizes.begin(), sizes.end());
  double total = 0.0;
  for (const auto& e : sizes)
    total += e.second;
  double below = 0.0;
  for (const auto& [extent, area] : sizes)
    if ((below += area) >= 0.5 * total) return extent;
  return sizes.back().first;
}

}  // namespace

LeafPieces make_leaf_pieces(const SurfaceSamples& s, uint32_t wood, float cell) {
  SYLVA_CHECK(std::isfinite(cell) && cell > 0.0f, "make_leaf_pieces: cell > 0");
  const bool with_primitives = s.primitives.size() == s.size();
  std::vector<std::pair<PieceKey, uint32_t>> keyed;
  keyed.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    const uint32_t cluster = s.clusters[i];
    if (cluster == 0 || cluster == wood || !(s.areas[i] > 0.0f)) continue;
    const glm::vec3& p = s.positions[i];
    PieceKey k{s.instances.empty() ? 0u : s.instances[i], with_primitives ? s.primitives[i] : 0u,
               cell_of(p.x, cell), cell_of(p.y, cell), cell_of(p.z, cell)};
    keyed.emplace_back(k, uint32_t(i));
  }
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && a.second < b.second);
  });
  std::vector<uint32_t> order(keyed.size());
  for (size_t k = 0; k < keyed.size(); ++k)
    order[k] = keyed[k].second;
  LeafPieces out;
  out.cell = cell;
  for (size_t begin = 0; begin < keyed.size();) {
    size_t end = begin + 1;
    while (end < keyed.size() && keyed[end].first == keyed[begin].first)
      ++end;
    out.pieces.push_back(make_piece(s, order, begin, end));
    // Pieces of one element follow each other: an element with more than one is cut.
    const PieceKey& k = keyed[begin].first;
    const size_t n = out.pieces.size();
    if (with_primitives && k.primitive != 0 && n > 1 && begin > 0 &&
        keyed[begin - 1].first.instance == k.instance &&
        keyed[begin - 1].first.primitive == k.primitive)
      out.pieces[n - 1].cut = out.pieces[n - 2].cut = true;
    begin = end;
  }
  if (with_primitives) out.leaf_extent = median_extent(s, keyed, order);
  return out;
}

namespace {

std::shared_ptr<const LeafPieces> memo_pieces(const std::shared_ptr<const SurfaceSamples>& samples,
                                              uint32_t wood, LeafPieceMemo* memo) {
  std::unique_lock<std::mutex> lock;
  if (memo) {
    lock = std::unique_lock<std::mutex>(memo->mutex);
    if (memo->pieces && memo->from == samples) return memo->pieces;
  }
  // The samples' spacing is 1/400 of the foliage's diagonal (npr/surface_samples.h).
  const float cell = samples->spacing * 400.0f * kPieceCells;
  auto pieces = std::make_shared<const LeafPieces>(
      cell > 0.0f && std::isfinite(cell) ? make_leaf_pieces(*samples, wood, cell) : LeafPieces{});
  if (memo) {
    memo->from = samples;
    memo->pieces = pieces;
  }
  return pieces;
}

}  // namespace

LeafPiecesHandle add_leaf_pieces_pass(RenderGraph& graph, SamplesHandle samples, uint32_t wood,
                                      std::shared_ptr<LeafPieceMemo> memo) {
  SYLVA_CHECK(samples.valid(), "leaf pieces need the surface samples");
  const auto out = graph.resource<std::shared_ptr<const LeafPieces>>("leaf-pieces");
  graph.add_pass("leaf-pieces", {samples}, {out}, [=](PassContext& ctx) {
    ctx.write(out, memo_pieces(ctx.read<std::shared_ptr<const SurfaceSamples>>(samples), wood,
                               memo.get()));
  });
  return out;
}

}  // namespace sylva

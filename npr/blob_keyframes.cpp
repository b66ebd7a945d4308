#include "npr/blob_keyframes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "npr/bspline.h"

namespace sylva {

int last_keyframe(int frames, int every) {
  if (every < 1)
    throw InputError("--keyframe-every", "must be at least 1, got " + std::to_string(every));
  SYLVA_CHECK(frames >= 1, "last_keyframe: no frames");
  return (frames - 1 + every - 1) / every;
}

std::vector<int> keys_owned(int begin, int end, int every, int frames) {
  const int last = last_keyframe(frames, every);
  SYLVA_CHECK(0 <= begin && begin < end && end <= frames, "keys_owned: bad slice");
  std::vector<int> out;
  for (int k = (begin + every - 1) / every;
       k <= last && (int64_t(k) * every < end || end == frames); ++k)
    out.push_back(k);
  return out;
}

std::vector<int> keys_needed(int frame, int every, int frames) {
  const int last = last_keyframe(frames, every);
  const int j = frame / every;
  std::vector<int> out;
  for (int k = std::max(0, j - 1); k <= std::min(last, j + 2); ++k)
    out.push_back(k);
  return out;
}

namespace {

const BlobOutline* find_cluster(const std::vector<BlobOutline>& blobs, uint32_t cluster) {
  auto it = std::lower_bound(blobs.begin(), blobs.end(), cluster,
                             [](const BlobOutline& b, uint32_t c) { return b.cluster < c; });
  return it != blobs.end() && it->cluster == cluster ? &*it : nullptr;
}

std::vector<size_t> order_by(const std::vector<float>& depth, const std::vector<BlobOutline>& b) {
  std::vector<size_t> order(b.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) {
    if (depth[x] != depth[y]) return depth[x] > depth[y];
    return b[x].cluster < b[y].cluster;
  });
  return order;
}

}  // namespace

BlobSet interpolate_blob_keys(const std::map<int, std::vector<BlobOutline>>& keys, int frame,
                              int every, int frames) {
  const std::vector<int> window = keys_needed(frame, every, frames);
  const int j = frame / every;
  const float u = static_cast<float>(frame % every) / static_cast<float>(every);
  const int lo = window.front();
  const double t = (j - lo) + static_cast<double>(u);
  std::vector<const std::vector<BlobOutline>*> sets;
  for (int k : window) {
    const auto it = keys.find(k);
    SYLVA_CHECK(it != keys.end(),
                "interpolate_blob_keys: keyframe " + std::to_string(k) + " missing");
    sets.push_back(&it->second);
  }
  std::vector<uint32_t> clusters;
  for (const auto* s : sets)
    for (const BlobOutline& b : *s)
      clusters.push_back(b.cluster);
  std::sort(clusters.begin(), clusters.end());
  clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());

  const size_t n = sets.size();
  const size_t at_j = static_cast<size_t>(j - lo);
  const size_t at_next = std::min(at_j + 1, n - 1);
  BlobSet out;
  std::vector<float> depth_j, depth_next;
  for (uint32_t c : clusters) {
    std::vector<const BlobOutline*> seq(n);
    for (size_t k = 0; k < n; ++k)
      seq[k] = find_cluster(*sets[k], c);
    const float present_j = seq[at_j] ? 1.0f : 0.0f;
    const float present_next = seq[at_next] ? 1.0f : 0.0f;
    const float opacity = (1.0f - u) * present_j + u * present_next;
    if (!(opacity > 0.0f)) continue;
    // A key without the blob borrows the nearest key that has it (the later one on a tie).
    std::vector<const BlobOutline*> full(n);
    for (size_t k = 0; k < n; ++k) {
      const BlobOutline* best = nullptr;
      size_t best_d = n + 1;
      for (size_t m = 0; m < n; ++m) {
        if (!seq[m]) continue;
        const size_t d = m > k ? m - k : k - m;
        if (d <= best_d) {
          best = seq[m];
          best_d = d;
        }
      }
      full[k] = best;
    }
    const size_t points = full[at_j]->wrap.points.size();
    bool same_count = true;
    for (const BlobOutline* b : full)
      same_count = same_count && b->wrap.points.size() == points;
    SYLVA_CHECK(same_count, "interpolate_blob_keys: keyframes with different control points");
    BlobOutline b;
    b.cluster = c;
    b.opacity = opacity;
    std::vector<glm::vec2> seq2(n);
    for (size_t k = 0; k < n; ++k)
      seq2[k] = full[k]->wrap.center;
    b.wrap.center = catmull_rom(seq2, t);
    for (size_t i = 0; i < points; ++i) {
      for (size_t k = 0; k < n; ++k)
        seq2[k] = full[k]->wrap.points[i];
      b.wrap.points.push_back(catmull_rom(seq2, t));
    }
    std::vector<float> seq1(n);
    for (size_t k = 0; k < n; ++k)
      seq1[k] = full[k]->min_depth;
    b.min_depth = catmull_rom(seq1, t);
    b.wrap.radius =
        full[at_j]->wrap.radius + u * (full[at_next]->wrap.radius - full[at_j]->wrap.radius);
    b.pixels = u == 0.0f ? full[at_j]->pixels : full[at_next]->pixels;
    depth_j.push_back(full[at_j]->min_depth);
    depth_next.push_back(full[at_next]->min_depth);
    out.blobs.push_back(std::move(b));
  }
  out.order = order_by(depth_j, out.blobs);
  out.next_order = order_by(depth_next, out.blobs);
  out.fade = out.order == out.next_order ? 0.0f : u;
  return out;
}

BlobKeyframes::BlobKeyframes(int frames, int every, Compute compute, std::string cache_dir,
                             std::string signature)
    : m_frames(frames),
      m_every(every),
      m_compute(std::move(compute)),
      m_dir(std::move(cache_dir)),
      m_signature(std::move(signature)) {
  (void)last_keyframe(frames, every);  // validates every
  std::replace(m_signature.begin(), m_signature.end(), '\n', ' ');
}

const std::vector<BlobOutline>& BlobKeyframes::key(int index) {
  const auto it = m_keys.find(index);
  if (it != m_keys.end()) return it->second;
  std::string path;
  if (!m_dir.empty()) {
    char name[32];
    std::snprintf(name, sizeof name, "key-%05d.txt", index);
    path = (std::filesystem::path(m_dir) / name).string();
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) {
      const std::string text = read_file_bytes(path);
      const size_t eol = text.find('\n');
      if (eol != std::string::npos && text.compare(0, eol, m_signature) == 0) {
        ++m_read;
        return m_keys[index] = parse_blob_outlines(text.substr(eol + 1), path);
      }
    }
  }
  std::vector<BlobOutline> blobs = m_compute(index * m_every);
  ++m_computed;
  if (!path.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(m_dir, ec);
    write_file_atomic(path, m_signature + "\n" + format_blob_outlines(blobs));
  }
  return m_keys[index] = std::move(blobs);
}

BlobSet BlobKeyframes::frame(int frame) {
  SYLVA_CHECK(frame >= 0 && frame < m_frames, "BlobKeyframes: frame out of range");
  std::map<int, std::vector<BlobOutline>> window;
  for (int k : keys_needed(frame, m_every, m_frames))
    window[k] = key(k);
  return interpolate_blob_keys(window, frame, m_every, m_frames);
}

std::string format_blob_outlines(const std::vector<BlobOutline>& blobs) {
  std::ostringstream s;
  char buf[64];
  auto num = [&](float v) {
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
    return std::string(buf);
  };
  s << "blobs " << blobs.size() << '\n';
  for (const BlobOutline& b : blobs) {
    s << b.cluster << ' ' << b.pixels << ' ' << num(b.min_depth) << ' ' << num(b.opacity) << ' '
      << num(b.wrap.center.x) << ' ' << num(b.wrap.center.y) << ' ' << num(b.wrap.radius) << ' '
      << b.wrap.points.size();
    for (const glm::vec2& p : b.wrap.points)
      s << ' ' << num(p.x) << ' ' << num(p.y);
    s << '\n';
  }
  return s.str();
}

std::vector<BlobOutline> parse_blob_outlines(const std::string& text, const std::string& where) {
  std::istringstream s(text);
  std::string word;
  size_t count = 0;
  if (!(s >> word >> count) || word != "blobs" || count > 1'000'000)
    throw InputError(where, "not a blob keyframe file (expected 'blobs N')");
  // Grown as the blobs are read, so a short file that claims many allocates little.
  std::vector<BlobOutline> out;
  for (size_t i = 0; i < count; ++i) {
    BlobOutline& b = out.emplace_back();
    size_t points = 0;
    if (!(s >> b.cluster >> b.pixels >> b.min_depth >> b.opacity >> b.wrap.center.x >>
          b.wrap.center.y >> b.wrap.radius >> points) ||
        points > 4096)
      throw InputError(where, "truncated or malformed blob keyframe");
    if (b.cluster == 0 || b.pixels < 0 || !(b.opacity >= 0.0f && b.opacity <= 1.0f) ||
        !(b.wrap.radius >= 0.0f))
      throw InputError(where, "blob keyframe with a value out of range");
    b.wrap.points.resize(points);
    bool finite = std::isfinite(b.min_depth) && std::isfinite(b.opacity) &&
                  std::isfinite(b.wrap.center.x) && std::isfinite(b.wrap.center.y) &&
                  std::isfinite(b.wrap.radius);
    for (glm::vec2& p : b.wrap.points) {
      if (!(s >> p.x >> p.y)) throw InputError(where, "truncated blob keyframe");
      finite = finite && std::isfinite(p.x) && std::isfinite(p.y);
    }
    if (!finite) throw InputError(where, "blob keyframe with a non-finite number");
  }
  for (size_t i = 1; i < out.size(); ++i)
    if (out[i].cluster <= out[i - 1].cluster)
      throw InputError(where, "blob keyframe clusters out of order");
  return out;
}

}  // namespace sylva

#include "npr/leaf_clusters.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/core.hpp>

#include "core/csv.h"
#include "core/error.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"

namespace sylva {
namespace {

// Leaves beyond this count are clustered through a strided sample (see kmeans_labels).
constexpr size_t kMaxKMeansPoints = 20000;

// Leaves are the foliage primitives, in primitive-id order (the order Hierarchy::leaf_branch
// uses). leaf_of[id] is the leaf index of primitive `id`, or -1.
struct Leaves {
  std::vector<int32_t> leaf_of;
  size_t count = 0;
};

Leaves find_leaves(const Scene& scene) {
  Leaves leaves;
  leaves.leaf_of.assign(size_t(scene.max_primitive_id()) + 1, -1);
  std::vector<char> foliage(leaves.leaf_of.size(), 0);
  for (const Mesh& mesh : scene.meshes)
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
      if (mesh.roles[t] == Role::Foliage) foliage[mesh.primitive_ids[t]] = 1;
  for (size_t id = 1; id < foliage.size(); ++id)
    if (foliage[id]) leaves.leaf_of[id] = int32_t(leaves.count++);
  return leaves;
}

// Dudley §3.2: walk up from the leaf's branch while the parent is still thinner than the
// division diameter; the last branch reached roots the cluster.
std::vector<int32_t> hierarchy_labels(const Hierarchy& h, float division) {
  std::vector<int32_t> root_of(h.leaf_branch.size());
  for (size_t l = 0; l < h.leaf_branch.size(); ++l) {
    int32_t root = h.leaf_branch[l];
    if (h.branch_diameter[size_t(root)] < division) {
      for (size_t steps = 0; steps < h.branch_parent.size(); ++steps) {  // bounded: no cycles
        const int32_t p = h.branch_parent[size_t(root)];
        if (p < 0 || !(h.branch_diameter[size_t(p)] < division)) break;
        root = p;
      }
    }
    root_of[l] = root;
  }
  return root_of;
}

std::vector<int32_t> kmeans_labels(const Scene& scene, const Leaves& leaves, int k, uint64_t seed) {
  cv::Mat points = cv::Mat::zeros(int(leaves.count), 3, CV_32F);
  std::vector<int> weight(leaves.count, 0);
  for (const Mesh& mesh : scene.meshes) {
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      const int32_t l = leaves.leaf_of[mesh.primitive_ids[t]];
      if (l < 0 || mesh.roles[t] != Role::Foliage) continue;
      glm::vec3 c(0.0f);
      for (int v = 0; v < 3; ++v)
        c += mesh.positions[mesh.indices[3 * t + size_t(v)]] / 3.0f;
      for (int d = 0; d < 3; ++d)
        points.at<float>(l, d) += c[d];
      ++weight[size_t(l)];
    }
  }
  for (size_t l = 0; l < leaves.count; ++l)
    for (int d = 0; d < 3; ++d)
      points.at<float>(int(l), d) /= float(std::max(weight[l], 1));
  std::vector<int32_t> labels(leaves.count, 0);
  if (k <= 1) return labels;
  // Large foliage: fit the centres on an evenly strided sample, then label every leaf by its
  // nearest centre. Keeps millions of leaves at a fraction of a second, deterministically.
  const size_t stride = std::max<size_t>(1, leaves.count / kMaxKMeansPoints);
  cv::Mat sample = points;
  if (stride > 1) {
    sample = cv::Mat(int((leaves.count + stride - 1) / stride), 3, CV_32F);
    for (int r = 0; r < sample.rows; ++r)
      points.row(r * int(stride)).copyTo(sample.row(r));
  }
  k = std::min(k, sample.rows);
  cv::RNG& rng = cv::theRNG();
  const uint64 saved = rng.state;
  rng.state = seed ? seed : 0xffffffffu;  // cv::RNG treats state 0 as this value too
  cv::Mat out, centres;
  cv::kmeans(sample, k, out,
             cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-6), 3,
             cv::KMEANS_PP_CENTERS, centres);
  rng.state = saved;
  for (size_t l = 0; l < leaves.count; ++l) {
    if (stride == 1) {
      labels[l] = out.at<int>(int(l));
      continue;
    }
    float best = std::numeric_limits<float>::max();
    const float* p = points.ptr<float>(int(l));
    for (int c = 0; c < k; ++c) {
      const float* q = centres.ptr<float>(c);
      const float d = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                      (p[2] - q[2]) * (p[2] - q[2]);
      if (d < best) {
        best = d;
        labels[l] = c;
      }
    }
  }
  return labels;
}

size_t count_roots(const std::vector<int32_t>& roots, size_t branches) {
  std::vector<char> seen(branches, 0);
  size_t n = 0;
  for (int32_t r : roots)
    if (!seen[size_t(r)]) seen[size_t(r)] = 1, ++n;
  return n;
}

// Automatic division diameter: among the hierarchy's own diameters (plus one above them all,
// which puts every leaf in one cluster), the one whose cluster count is closest to `target`.
// The count falls monotonically as the division grows, so a binary search finds it.
float auto_division(const Hierarchy& h, size_t target) {
  std::vector<float> d = h.branch_diameter;
  std::sort(d.begin(), d.end());
  d.erase(std::unique(d.begin(), d.end()), d.end());
  d.push_back(d.empty() ? 1.0f : d.back() * 2.0f + 1.0f);
  const auto count = [&](size_t i) {
    return count_roots(hierarchy_labels(h, d[i]), h.branch_parent.size());
  };
  size_t lo = 0, hi = d.size() - 1;  // first index whose count <= target
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if (count(mid) <= target)
      hi = mid;
    else
      lo = mid + 1;
  }
  if (lo > 0) {
    const size_t above = count(lo - 1), below = count(lo);
    if (above - target < target - below) return d[lo - 1];
  }
  return d[lo];
}

size_t default_cluster_count(size_t leaves) {
  return std::clamp<size_t>(size_t(std::lround(std::sqrt(double(leaves) / 2.0))), 1, 64);
}

// The clusters of a flat scene (or one plant's).
void assign_plant_clusters(Scene& scene, const ClusterOptions& options) {
  const Leaves leaves = find_leaves(scene);
  const Hierarchy& h = scene.hierarchy;
  std::vector<int32_t> labels;
  if (options.use_hierarchy && !h.empty() && leaves.count > 0) {
    validate_hierarchy(h, "sylva_hierarchy");
    if (h.leaf_branch.size() == leaves.count) {
      const float division =
          options.division_diameter > 0.0f
              ? options.division_diameter
              : auto_division(h, options.clusters > 0 ? size_t(options.clusters)
                                                      : default_cluster_count(leaves.count));
      labels = hierarchy_labels(h, division);
      scene.report.cluster_method = format_number("hierarchy (division diameter %g)", division);
    } else {
      scene.report.warnings.push_back("hierarchy has " + std::to_string(h.leaf_branch.size()) +
                                      " leaves but the scene has " + std::to_string(leaves.count) +
                                      "; using k-means");
    }
  }
  if (labels.empty() && leaves.count > 0) {
    int k = options.clusters;
    if (k == 0) k = int(default_cluster_count(leaves.count));
    k = std::min<int>(k, int(leaves.count));
    labels = kmeans_labels(scene, leaves, k, options.seed);
    scene.report.cluster_method =
        "k-means (k=" + std::to_string(k) + ", seed " + std::to_string(options.seed) + ")";
  }
  if (leaves.count == 0) scene.report.cluster_method = "none (no foliage)";

  // Renumber by first appearance over leaves so ids do not depend on label values.
  std::vector<uint32_t> id_of_label;
  std::vector<uint32_t> leaf_cluster(leaves.count);
  uint32_t clusters = 0;
  for (size_t l = 0; l < leaves.count; ++l) {
    const size_t label = size_t(labels[l]);
    if (label >= id_of_label.size()) id_of_label.resize(label + 1, 0);
    if (id_of_label[label] == 0) id_of_label[label] = ++clusters;
    leaf_cluster[l] = id_of_label[label];
  }
  for (Mesh& mesh : scene.meshes) {
    mesh.cluster_ids.resize(mesh.triangle_count());
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      const int32_t l = leaves.leaf_of[mesh.primitive_ids[t]];
      mesh.cluster_ids[t] =
          mesh.roles[t] == Role::Foliage && l >= 0 ? leaf_cluster[size_t(l)] : clusters + 1;
    }
  }
}

}  // namespace

void assign_clusters(Scene& scene, const ClusterOptions& options) {
  if (options.clusters < 0 || options.clusters > 4096)
    throw InputError("--clusters", "must be in [0, 4096], got " + std::to_string(options.clusters));
  if (!std::isfinite(options.division_diameter) || options.division_diameter < 0.0f)
    throw InputError("--division-diameter", "must be a finite value >= 0 (scene units)");
  for (const Mesh& mesh : scene.meshes)
    SYLVA_CHECK(mesh.roles.size() == mesh.triangle_count() &&
                    mesh.primitive_ids.size() == mesh.triangle_count(),
                "assign_clusters needs roles and primitive ids (finish_scene)");
  if (!scene.instanced()) {
    assign_plant_clusters(scene, options);
    return;
  }
  // Each plant alone, in its own space, as it would be clustered alone.
  std::vector<std::string> methods;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    Scene plant = plant_scene(scene, p, false);
    assign_plant_clusters(plant, options);
    const std::vector<uint32_t>& meshes = scene.plants[p].meshes;
    for (size_t k = 0; k < meshes.size(); ++k)
      scene.meshes[meshes[k]].cluster_ids = std::move(plant.meshes[k].cluster_ids);
    for (const std::string& w : plant.report.warnings)
      scene.report.warn("clusters", "plant '" + scene.plants[p].name + "': " + w);
    methods.push_back(scene.plants[p].name + ": " + plant.report.cluster_method);
  }
  scene.report.cluster_method.clear();
  for (const std::string& m : methods)
    scene.report.cluster_method += (scene.report.cluster_method.empty() ? "" : "; ") + m;
}

}  // namespace sylva

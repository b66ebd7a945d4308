// Sample trees for the benchmarks, generated once per program and leaf count.
#pragma once

#include <map>

#include "samples/plants.h"

namespace sylva::perf {

inline const Scene& sample_tree(int leaves) {
  static std::map<int, Scene> trees;
  auto it = trees.find(leaves);
  if (it != trees.end()) return it->second;
  PlantOptions o;
  o.kind = PlantKind::Tree;
  o.leaves = leaves;
  return trees.emplace(leaves, make_plant(o)).first->second;
}

}  // namespace sylva::perf

// The scene the cache harness reads results for, shared with the seed maker so that its seed
// is a real cache file of that scene: the 100-leaf sample tree (seed 1), loaded as a file
// would be, its leaves only, with the default foliage parameters but a 16-cell surface grid (so
// that the cache file, and the fuzzer's inputs, stay small), and their cache key.
#pragma once

#include <string>

#include "core/scene/load.h"
#include "npr/foliage_cache.h"
#include "samples/plants.h"

namespace sylva::fuzz {

struct CacheScene {
  Scene scene;
  FoliageParams params;
  std::string kind = "foliage";  // npr/foliage_cache.cpp's kind
  std::string key;
};

inline const CacheScene& cache_scene() {
  static const CacheScene c = [] {
    CacheScene s;
    PlantOptions o;
    o.leaves = 100;
    s.scene = make_plant(o);
    s.scene.meshes.resize(1);  // the leaves
    s.scene.hierarchy = {};
    finish_scene(s.scene, LoadOptions{}, true);
    s.params.grid = 16;
    s.key = foliage_cache_key(s.scene, s.params);
    return s;
  }();
  return c;
}

}  // namespace sylva::fuzz

// A park: a seeded layout of instances of given plants on a flat area, as an instanced scene
// (each plant's meshes stored once; `sylva sample park` writes it as glTF with shared meshes),
// for landscape plans and the benchmarks. The area W x D (scene units, centred on the origin,
// y = 0 up) is divided into a grid of about square cells, at least `count` of them; the
// instances take `count` cells in a seeded random order, each placed at a random point of its
// inner 80 % (so neighbours keep a gap of a fifth of a cell), turned about +Y by a random angle
// and scaled by a random factor in [0.8, 1.2]; its plant is drawn uniformly from the list.
// The park carries two cameras: "plan", orthographic straight down over the whole area (image
// up = -Z), and "overview", perspective (45 degrees) from above the +X, +Z corner.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

struct ParkOptions {
  int count = 100;       // instances, [1, kMaxParkCount]
  float width = 100.0f;  // area along X, scene units, (0, 1e6]
  float depth = 100.0f;  // area along Z, scene units, (0, 1e6]
  uint64_t seed = 1;
};
inline constexpr int kMaxParkCount = 100000;

// `plants` are finished flat scenes (load_scene; an instanced one is flattened first), named
// by `names` (the plants' and their instances' names). Each plant's meshes keep their own
// space: a plant's origin is where its instances stand. Throws InputError("--count",
// "--area" or "--plants", ...) on a value out of range or an empty plant list.
Scene make_park(const std::vector<Scene>& plants, const std::vector<std::string>& names,
                const ParkOptions& options);

// "WxD" or "N" (square), each a number in (0, 1e6]. Throws InputError("--area", ...).
void parse_park_area(const std::string& text, float& width, float& depth);

}  // namespace sylva

// Primitive ids: a primitive is a connected component of triangles sharing vertex indices
// within one mesh (a leaf, for foliage). Ids are 1-based, numbered in the order of each
// component's first triangle, meshes in order, unique within each plant (a flat scene: the
// scene), so a plant gets the ids it has alone.
#pragma once

#include "core/scene/scene.h"

namespace sylva {

void assign_primitive_ids(Scene& scene);

}  // namespace sylva

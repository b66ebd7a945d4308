// Foliage detection: which triangles are leaves. Rules, in order: an explicit --foliage
// value ("none", "all", or a case-insensitive glob on material/mesh names); else material or
// mesh names containing leaf/leaves/foliage/needle (case-insensitive); else meshes whose
// material is alpha MASK. Everything else is grass if named grass/lawn (Hegeman et al.
// Eq. 9 blades), wood if named like bark/trunk/branch/wood/stem, ground if named
// ground/terrain/soil, other otherwise. Writes Scene::report.foliage_*.
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

// foliage_option: "auto" (default), "none", "all" or a glob. In "auto", meshes that already
// carry roles (glTF "sylva_role" extras) keep them. A glob matching no material or mesh name
// throws InputError("--foliage", ...) listing the names. report.foliage_rule is one of
// "--foliage none", "--foliage all", "--foliage '<glob>'", "name match", "alpha MASK",
// "no foliage found", "sylva_role extras" (possibly "<rule> + sylva_role extras (N meshes)").
void classify_roles(Scene& scene, const std::string& foliage_option);

// Case-insensitive glob with * and ?.
bool glob_match(const std::string& pattern, const std::string& text);

}  // namespace sylva

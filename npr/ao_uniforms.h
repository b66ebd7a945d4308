// Hegeman et al.'s shells (npr/ao_shells.h) turned into the raster pass's AO uniforms
// (core/gl/ao_shading.h), with alpha * rho given or fitted (npr/ao_fit.h) to a ray tracer.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "core/gl/ao_shading.h"
#include "core/scene/scene.h"

namespace sylva {

struct Shells;  // npr/ao_shells.h

// The uniforms of one shell set (1 to kMaxAoShells shells, one anchor each): each shell's
// L = axes * diag(radii) in double precision, as npr/hegeman_ao.cpp's ellipsoid_cap; a shell
// without volume gets volume_scale 0 (visibility 1, as on the CPU). `crown` is the sphere
// whose solid angle occludes everything that is not foliage (Hegeman et al. Eq. 7-8); empty
// (the default) = no such occlusion.
AoShading ao_shading(const Shells& shells, float alpha_rho, const Sphere& crown = {});

// Ray-traced visibility of points with normals (e.g. AoReferenceScene::visibility).
using AoTracer = std::function<std::vector<float>(const std::vector<glm::vec3>& points,
                                                  const std::vector<glm::vec3>& normals)>;

struct AoShellFit {
  bool ellipsoid = false;  // shell shape: bounding sphere or PCA ellipsoid
  int shells = 1;          // k, [1, 64]
  uint64_t seed = 1;       // k-means seeding and the choice of fit samples
  float alpha_rho = -1;    // >= 0: used as given; < 0: auto, fitted to `trace`
  // Auto: candidate sample points on the foliage with a normal each; up to 256 of them are
  // picked (seeded), each traced with its normal and with the opposite one (a double-sided
  // leaf is seen from either side, and the raster pass evaluates Eq. 6 with the side facing
  // the viewer), and alpha_rho fitted by least squares (fit_alpha_rho) to all of them, each
  // weighted by its traced visibility (how likely a camera outside the crown sees it).
  std::vector<glm::vec3> sample_points, sample_normals;
  AoTracer trace;
};

// Fits the shells to `foliage` (fit_shells) and returns their uniforms, with the crown sphere
// of Eq. 7-8 the foliage's bounding sphere (fit_bounding_sphere: the shell of
// hegeman-sphere, whichever shells are fitted). Throws InputError as fit_shells does, and
// InputError("ao.alpha_rho", ...) for auto without samples.
AoShading fit_ao_shading(const std::vector<glm::vec3>& foliage, const AoShellFit& fit);

}  // namespace sylva

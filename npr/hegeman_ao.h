// The approximate ambient visibility of Hegeman et al. 2006: a point x with normal n inside a
// crown shell (npr/ao_shells.h) sees the sky through the occluders in the part of the shell
// in front of its tangent plane (§3, Eq. 4-6); an object near a crown loses the solid angle
// the crown's sphere covers (Eq. 7-8); a grass blade sees the sky by its height and
// orientation (Eq. 9). Visibility is the uniform hemisphere average of Eq. 3 (1 = open sky,
// 0 = fully occluded). Every function here returns a finite value in [0, 1] for finite inputs.
//
// Zero normals: a normal of zero length (or with a non-finite component) carries no
// orientation, and never produces NaN. What each function uses instead is stated next to it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "npr/ao_shells.h"

namespace sylva {

// alpha * rho of Eq. 6: occluder density times occluder size, per scene unit cubed (the
// exponent is alpha_rho times a volume), finite and >= 0; 0 = no occlusion. It depends on
// the crown's scale: fit it with npr/ao_fit.h. For leaves scattered uniformly in a sphere of
// radius R with extinction sigma (leaves per volume * half a leaf's area, per scene unit),
// alpha_rho = sigma R / (2/3 pi R^3) makes Eq. 6 exact at the centre. Throws
// InputError("alpha-rho", ...) outside the range.
void validate_alpha_rho(float alpha_rho);

// Eq. 4: V_cap = pi h^2 (3R - h) / 3, the volume of the part of a sphere of radius R cut off
// by a plane at height h from the sphere's surface. h is clamped to [0, 2R] (0 = nothing in
// front of the plane, 2R = the whole ball); R <= 0 gives 0. Scene units cubed.
double cap_volume(double h, double radius);

// Eq. 5: f = h^2 / (h^2 + d^2) in [0, 1], the squared cosine of the off-centre angle. h and
// d are taken as magnitudes. h = d = 0 gives 1: the limit along d = 0 (the point at the centre
// of the cap's base disk, which is f = 1 for every h > 0); the visibility does not depend on
// this choice, because V_cap(0) = 0 makes the exponent 0.
double off_centre_factor(double h, double d);

// The tangent plane of (x, n) cutting a shell.
struct CapGeometry {
  double h = 0;                // cap height of the part on the normal's side, in [0, 2R]
  double d = 0;                // distance in the plane from x to the foot of the centre, >= 0
  double radius = 0;           // R of the sphere h and d are measured in
  double volume = 0;           // V_cap of that part, scene units cubed
  double f = 1;                // Eq. 5
  double weighted_volume = 0;  // f * volume: the exponent of Eq. 6 per unit alpha_rho
};

// Sphere: h = R + n.(c - x) clamped to [0, 2R]; d = |(c - x) - (n.(c - x)) n|. A point
// outside the sphere is treated the same way: facing away (h = 0) it is unoccluded; facing
// the crown it sees the whole cap in front of its plane whatever its distance (use
// object_visibility for points outside a crown). Zero normal: the outward direction x - c
// (the best-lit orientation); at the centre every plane gives h = R, d = 0.
// R <= 0 (or non-finite): no volume, weighted_volume = 0.
CapGeometry sphere_cap(const Sphere& sphere, const glm::vec3& x, const glm::vec3& n);

// Ellipsoid, by the affine map that takes it onto the unit ball (Hegeman §3): with
// L = axes * diag(radii), the point maps to u = L^-1 (x - c) and the plane normal to
// L^T n (the inverse-transpose of L^-1; planes map to planes, so the cap maps onto the unit
// ball's cap exactly). h, d, radius (= 1) and f are measured in the unit ball; volume is the
// unit-ball cap volume times |det L| = the cap's volume in scene units, so alpha_rho keeps
// its meaning (occluders per scene volume) and an ellipsoid with equal radii R gives
// exactly the sphere of radius R. f is computed in the unit ball (it is not affine
// invariant; Hegeman et al. do the same). Zero normal: outward in the unit ball, as for the
// sphere. A flat or degenerate ellipsoid (a radius <= 0, det L = 0 or non-finite) has no
// volume: weighted_volume = 0. `axes` need not be orthonormal, only invertible.
CapGeometry ellipsoid_cap(const Ellipsoid& ellipsoid, const glm::vec3& x, const glm::vec3& n);

// Eq. 6: V = exp(-alpha_rho * f * V_cap): 1 for alpha_rho = 0 or h = 0, in (0, 1) for
// moderate exponents, exactly 0 (finite) once the exponent exceeds ~104 (float underflow).
// Negative or NaN alpha_rho counts as 0 (validate it with validate_alpha_rho).
// Accuracy, measured on a uniform random leaf sphere (sigma R ~ 1) against ray-traced
// visibility (tests/npr/test_ao_reference.cpp): RMSE ~0.17 even with the best alpha_rho.
// Eq. 6 takes the exponential of an average depth where the truth averages exponentials, so
// it overstates how much the normal's orientation matters (a point on the rim facing
// inward, centre-exact alpha_rho: model 0.14, truth 0.42); the paper aims at plausibility.
float hegeman_visibility(const Sphere& sphere, const glm::vec3& x, const glm::vec3& n,
                         float alpha_rho);
float hegeman_visibility(const Ellipsoid& ellipsoid, const glm::vec3& x, const glm::vec3& n,
                         float alpha_rho);
// k shells (Hegeman §5): the shell whose anchor is nearest to x (Shells::nearest).
float hegeman_visibility(const Shells& shells, const glm::vec3& x, const glm::vec3& n,
                         float alpha_rho);

// Eq. 7 (the paper's small-angle approximation) or the exact solid angle of a sphere.
enum class SolidAngleModel : uint8_t { Paper = 0, Exact = 1 };

// The solid angle of a sphere of radius r seen from distance `dist` from its centre, in
// steradians, [0, 2 pi]. Paper: pi (r/dist)^2; Exact: 2 pi (1 - sqrt(1 - (r/dist)^2)).
// Inside or on the sphere (dist <= r) both are clamped to their value at dist = r (pi and
// 2 pi), so they are continuous at the boundary. r <= 0 gives 0.
double sphere_solid_angle(double r, double dist, SolidAngleModel model);

// The solid angle of the cone of half-angle beta in [0, pi/2] whose axis makes the angle
// gamma in [0, pi] with n, restricted to the hemisphere around n: the closed form for two
// intersecting spherical caps (Mazonka 2012, "Solid angle of conical surfaces, polyhedral
// cones, and intersecting spherical caps", with the second cap a hemisphere). Steradians,
// [0, 2 pi (1 - cos beta)].
double cone_solid_angle_above_horizon(double beta, double gamma);

struct ObjectOcclusion {
  SolidAngleModel model = SolidAngleModel::Exact;
  // true: only the part of the crown above x's tangent plane occludes (a wall facing away
  // from the tree keeps its sky); the clipped share of the exact cone scales the chosen
  // model's solid angle. false: the paper's Eq. 8 as printed, the whole solid angle counts
  // whatever the normal.
  bool horizon_clip = true;
};

// Eq. 8: V = 1 - A / (2 pi), the occlusion of a point outside a crown by the crown's
// sphere (e.g. the ground under a tree). Inside the sphere A takes its boundary value along
// the ray from the centre through x (with horizon clipping and x at the centre: half of it).
// Zero normal: no horizon clipping. r <= 0: V = 1.
float object_visibility(const Sphere& crown, const glm::vec3& x, const glm::vec3& n,
                        const ObjectOcclusion& options = {});

// Eq. 9: V = P_z / (2h) (1 + cos theta) for a grass blade of height h, P_z the height of the
// point above the ground clamped to [0, h], theta the angle between the normal and `up`
// (normal up: 1 at the tip; horizontal: P_z / 2h; down: 0). h <= 0 or non-finite: no grass,
// V = 1. Zero normal (or zero up): cos theta = 0, the average over all orientations.
// Default up: +Y (glTF, the project's convention).
float grass_visibility(float height_above_ground, float blade_height, const glm::vec3& normal,
                       const glm::vec3& up = glm::vec3(0.0f, 1.0f, 0.0f));

// Not in the paper: the share of a point's hemisphere (uniform measure, as Eq. 3) that an
// infinite ground plane below it hides, theta / pi with theta the angle between the normal
// and `up` (the two hemispheres meet in a lune of 2 (pi - theta) steradians): 0 facing up,
// 1/2 for an upright wall (a trunk), 1 facing down. The crown lies above the plane, so the
// two occluders hide disjoint directions and their shares subtract: V = V_crown - this.
// A point below the plane (height < 0) or a non-finite height: 0. Zero normal: 1/2 (the
// average over orientations). Zero up: 0. Default up: +Y.
float ground_plane_occlusion(float height_above_ground, const glm::vec3& normal,
                             const glm::vec3& up = glm::vec3(0.0f, 1.0f, 0.0f));

}  // namespace sylva

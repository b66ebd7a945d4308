// The camera's depth range fitted to a whole scene: Scene::framing_sphere leaves ground
// triangles out (so a `--ground` plane a few times the plant's size does not shrink the
// plant), and the orbit camera's near/far planes hug that sphere, which would clip the
// ground. This widens them to hold everything.
#pragma once

#include "core/gl/camera.h"
#include "core/scene/scene.h"

namespace sylva {

// For a scene with ground triangles (Role::Ground): widens the camera's near/far planes
// (never narrows them) to hold the circumscribed sphere of the scene's bounds (1% margin);
// a new near plane stays >= 1/1000 of far, as make_orbit_camera keeps it (the old one is
// kept when it is nearer). Only the projection's depth terms change: the framing (field of
// view, orthographic extent) and the view stay. Scenes without ground triangles: no change,
// so their images are exactly as before.
void fit_camera_depth(Camera& camera, const Scene& scene);

}  // namespace sylva

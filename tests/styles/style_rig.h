// A small uploaded scene for the style tests: a 300-leaf sample bush, a GL context with its
// rasteriser, and a size x size orbit camera with the three-point lights.
#pragma once

#include <memory>

#include "core/gl/raster_pass.h"
#include "samples/plants.h"

namespace sylva::test {

struct StyleRig {
  Scene scene;
  std::unique_ptr<GlContext> ctx = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  RasterSetup rs;
  explicit StyleRig(int size = 64) {
    PlantOptions po;
    po.kind = PlantKind::Bush;
    po.leaves = 300;
    scene = make_plant(po);
    raster = std::make_unique<Rasterizer>(*ctx);
    raster->upload(scene);
    rs.rasterizer = raster.get();
    rs.camera = make_orbit_camera(scene.bounds(), OrbitParams{}, size, size);
    rs.lighting = Lighting::three_point();
  }
};

}  // namespace sylva::test

// Hegeman AO for a scene of many plants (npr/ao_plants.h): each plant's shells are those it
// gets alone, each instance's crown is its plant's crown moved and scaled by its transform.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/scene/instances.h"
#include "npr/ao_plants.h"
#include "samples/plants.h"

namespace sylva {
namespace {

Scene park_of_two() {
  PlantOptions o;
  o.leaves = 600;
  o.seed = 3;
  const Scene tree = make_plant(o);
  Scene park;
  park.meshes = tree.meshes;
  park.materials = tree.materials;
  park.textures = tree.textures;
  Plant plant{"tree", {}, tree.hierarchy};
  for (size_t m = 0; m < park.meshes.size(); ++m)
    plant.meshes.push_back(uint32_t(m));
  park.plants = {plant};
  const glm::mat4 moved =
      glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, -4)), glm::vec3(1.5f));
  park.instances = {{0, glm::mat4(1.0f), "a"}, {0, moved, "b"}};
  return park;
}

TEST(AoPlants, EachPlantIsFittedAloneAndEachInstanceCarriesItsCrown) {
  const Scene park = park_of_two();
  AoSettings s;
  s.model = AoModel::HegemanEllipsoid;
  s.alpha_rho = "2.5";
  const AoShading ao = plants_ao_shading(park, s, 7);
  const AoShading alone = scene_ao_shading(plant_scene(park, 0), s, 7);
  ASSERT_EQ(ao.plant_shells.size(), 1u);
  EXPECT_EQ(ao.plant_shells[0].centres, alone.centres);
  EXPECT_EQ(ao.plant_shells[0].inverse, alone.inverse);
  EXPECT_EQ(ao.plant_shells[0].alpha_rho, alone.alpha_rho);
  ASSERT_EQ(ao.crowns.size(), 2u);
  EXPECT_EQ(glm::vec3(ao.crowns[0]), alone.crown_centre);
  EXPECT_FLOAT_EQ(ao.crowns[0].w, alone.crown_radius);
  const glm::vec3 moved = glm::vec3(10, 0, -4) + 1.5f * alone.crown_centre;
  EXPECT_NEAR(glm::length(glm::vec3(ao.crowns[1]) - moved), 0.0f, 1e-4f);
  EXPECT_FLOAT_EQ(ao.crowns[1].w, 1.5f * alone.crown_radius);
  EXPECT_TRUE(ao.centres.empty());  // the flat fields stay unused
}

TEST(AoPlants, AParkWithoutFoliageIsAnError) {
  Scene park = park_of_two();
  for (Mesh& m : park.meshes)
    m.roles.assign(m.triangle_count(), Role::Wood);
  AoSettings s;
  s.model = AoModel::HegemanSphere;
  EXPECT_THROW(plants_ao_shading(park, s, 1), InputError);
}

}  // namespace
}  // namespace sylva

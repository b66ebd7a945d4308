// sylva sample tree|bush|conifer [--seed N] [--leaves N] -o OUT.glb
// sylva sample grass [--seed N] [--blades N] -o OUT.glb
// sylva sample park --plants A.glb,B.glb [--count N] [--area WxD] [--seed N] -o OUT.glb
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "core/error.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "samples/grass.h"
#include "samples/park.h"
#include "samples/plants.h"

namespace sylva::cli {

namespace {

// sylva sample park: the plants loaded (as `render` loads them), laid out and written with
// shared meshes.
template <class Opts>
void write_park(const Opts& o) {
  ParkOptions po;
  po.count = o.count;
  po.seed = o.seed;
  parse_park_area(o.area, po.width, po.depth);
  check_output_path("--output", o.out, {".glb"});
  std::vector<Scene> scenes;
  std::vector<std::string> names;
  std::stringstream list(o.plants);
  for (std::string path; std::getline(list, path, ',');) {
    if (path.empty()) throw InputError("--plants", "an empty name in '" + o.plants + "'");
    scenes.push_back(load_scene(path));
    names.push_back(std::filesystem::path(path).stem().string());
  }
  const Scene park = make_park(scenes, names, po);
  write_glb(park, o.out);
  std::printf("wrote %s (%zu instances of %zu plants, %zu triangles drawn, %zu distinct)\n",
              o.out.c_str(), park.instance_count(), park.plant_count(), park.drawn_triangle_count(),
              park.triangle_count());
}

}  // namespace

Action add_sample_command(CLI::App& app) {
  struct Opts {
    std::string kind;
    uint64_t seed = 1;
    int leaves = 0;
    int blades = 0;
    std::string plants, area = "100x100";
    int count = 100;
    std::string out;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand(
      "sample",
      "Generate a procedural L-system plant (tree, bush, conifer), a grass patch, or a park of "
      "instanced plants as a .glb");
  cmd->add_option("kind", o->kind, "tree, bush, conifer, grass or park")->required();
  cmd->add_option("--seed", o->seed, "Random seed; same seed, same bytes")->capture_default_str();
  cmd->add_option("--leaves", o->leaves,
                  "Target leaf count in [100, 2000000]; 0 = the kind's default")
      ->capture_default_str();
  cmd->add_option("--blades", o->blades,
                  "grass: blade count in [1, 200000] on a 1 m x 1 m patch; 0 = 2000")
      ->capture_default_str();
  CLI::Option* plants = cmd->add_option(
      "--plants", o->plants, "park: comma-separated plant files (.glb, .gltf, .obj, ...)");
  CLI::Option* count =
      cmd->add_option("--count", o->count, "park: instances, [1, 100000]")->capture_default_str();
  CLI::Option* area =
      cmd->add_option("--area", o->area, "park: area WxD or N (square), scene units, (0, 1e6]")
          ->capture_default_str();
  cmd->add_option("-o,--output", o->out, "Output .glb file")->required();
  return [o, plants, count, area] {
    const bool park_options = plants->count() + count->count() + area->count() > 0;
    if (o->kind == "park") {
      if (o->leaves != 0) throw InputError("--leaves", "applies to tree, bush and conifer");
      if (o->blades != 0) throw InputError("--blades", "applies to grass only");
      write_park(*o);
      return;
    }
    if (park_options)
      throw InputError(plants->count()  ? "--plants"
                       : count->count() ? "--count"
                                        : "--area",
                       "applies to park only");
    if (o->kind == "grass") {
      if (o->leaves != 0) throw InputError("--leaves", "applies to tree, bush and conifer");
      GrassOptions go;
      go.seed = o->seed;
      if (o->blades != 0) go.blades = o->blades;
      check_output_path("--output", o->out, {".glb"});
      Scene scene = make_grass(go);
      write_glb(scene, o->out);
      std::printf("wrote %s (%zu triangles, %d blades)\n", o->out.c_str(), scene.triangle_count(),
                  go.blades);
      return;
    }
    if (o->blades != 0) throw InputError("--blades", "applies to grass only");
    PlantOptions po;
    po.kind = parse_plant_kind(o->kind);
    po.seed = o->seed;
    po.leaves = o->leaves;
    check_output_path("--output", o->out, {".glb"});
    Scene scene = make_plant(po);
    write_glb(scene, o->out);
    std::printf("wrote %s (%zu triangles, %zu leaves)\n", o->out.c_str(), scene.triangle_count(),
                scene.hierarchy.leaf_branch.size());
  };
}

}  // namespace sylva::cli

// sylva sample tree|bush|conifer [--seed N] [--leaves N] -o OUT.glb
// sylva sample grass [--seed N] [--blades N] -o OUT.glb
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "core/scene/gltf_write.h"
#include "samples/grass.h"
#include "samples/plants.h"

namespace sylva::cli {

Action add_sample_command(CLI::App& app) {
  struct Opts {
    std::string kind;
    uint64_t seed = 1;
    int leaves = 0;
    int blades = 0;
    std::string out;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand(
      "sample",
      "Generate a procedural L-system plant (tree, bush, conifer) or a grass patch as a .glb");
  cmd->add_option("kind", o->kind, "tree, bush, conifer or grass")->required();
  cmd->add_option("--seed", o->seed, "Random seed; same seed, same bytes")->capture_default_str();
  cmd->add_option("--leaves", o->leaves,
                  "Target leaf count in [100, 2000000]; 0 = the kind's default")
      ->capture_default_str();
  cmd->add_option("--blades", o->blades,
                  "grass: blade count in [1, 200000] on a 1 m x 1 m patch; 0 = 2000")
      ->capture_default_str();
  cmd->add_option("-o,--output", o->out, "Output .glb file")->required();
  return [o] {
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

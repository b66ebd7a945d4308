// sylva sample tree|bush|conifer [--seed N] [--leaves N] -o OUT.glb
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/scene/gltf_write.h"
#include "samples/plants.h"

namespace sylva::cli {

Action add_sample_command(CLI::App& app) {
  struct Opts {
    std::string kind;
    uint64_t seed = 1;
    int leaves = 0;
    std::string out;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand(
      "sample", "Generate a procedural L-system plant (tree, bush, conifer) as a .glb");
  cmd->add_option("kind", o->kind, "tree, bush or conifer")->required();
  cmd->add_option("--seed", o->seed, "Random seed; same seed, same bytes")->capture_default_str();
  cmd->add_option("--leaves", o->leaves,
                  "Target leaf count in [100, 2000000]; 0 = the kind's default")
      ->capture_default_str();
  cmd->add_option("-o,--output", o->out, "Output .glb file")->required();
  return [o] {
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

// sylva bake SCENE [scene options] [foliage illumination options] -o OUT.glb
// Runs the Luft, Balzer & Deussen preprocessing once and writes the scene with its result per
// vertex, for other engines: unit realigned normals (§3.3) as NORMAL, the ambient coefficient
// ka (Eq. 4, §3.2) as "_AMBIENT" and as a grey COLOR_0 (core/scene/gltf_write.h), and the
// resolved parameters in scenes[0].extras.sylva_baked. `sylva render OUT.glb` reads ka back.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/illumination_options.h"
#include "core/error.h"
#include "core/scene/gltf_write.h"

namespace sylva::cli {

namespace {

// The shortest decimal that reads back as `f`, so 0.3f is written 0.3, not 0.30000001192092896.
double shortest(float f) {
  for (int digits = 6; digits < 9; ++digits) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, double(f));
    const double d = std::strtod(buf, nullptr);
    if (float(d) == f) return d;
  }
  return double(f);
}

// What made the baked data, with every "auto" resolved, so a file documents itself. No
// timings: the same inputs must give the same bytes.
std::string baked_note(const FoliageParams& p, const FoliageStats& s) {
  nlohmann::json j = {
      {"method", "Luft, Balzer & Deussen 2007: realigned normals, ka by Eq. 4"},
      {"leaves", s.leaves},
      {"generators", s.generators},
      {"fraction", s.fraction},
      {"per_triangle", p.per_triangle},
      {"rho", s.rho},
      {"tau", shortest(float(s.tau))},
      {"grid", p.grid},
      {"blend", shortest(float(p.blend))},
      {"normal_source", p.normals == NormalSource::Surface ? "surface" : "gradient"},
      {"ka_min", shortest(float(p.ambient.ka_min))},
      {"d_min", shortest(float(s.d_min))},
      {"exponent", shortest(float(p.ambient.exponent))},
      {"smooth", p.optimize.smooth_iterations},
      {"decimate", p.optimize.keep_fraction},
      {"seed", p.seed}};
  // A scene of many plants: what each plant resolved alone (the fields above: the first's).
  for (const FoliageStats& plant : s.plants)
    j["plants"].push_back({{"name", plant.plant},
                           {"leaves", plant.leaves},
                           {"generators", plant.generators},
                           {"fraction", plant.fraction},
                           {"rho", plant.rho},
                           {"tau", shortest(float(plant.tau))},
                           {"d_min", shortest(float(plant.d_min))}});
  return j.dump();
}

}  // namespace

Action add_bake_command(CLI::App& app) {
  struct Opts {
    SceneOptions scene;
    FoliageRunOptions foliage;
    std::string out;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand(
      "bake", "Bake the foliage illumination (realigned normals, ambient coefficient) into a .glb");
  add_scene_options(*cmd, o->scene);
  // ka is written both ways (NORMAL unit, _AMBIENT and COLOR_0), so no --ka-encoding.
  add_illumination_options(*cmd, &o->foliage, {"foliage.ka_encoding"});
  cmd->add_option("-o,--output", o->out,
                  "Output scene (.glb): NORMAL, COLOR_0 = ka and _AMBIENT = ka per vertex")
      ->required();
  return [o, cmd] {
    check_output_path("--output", o->out, {".glb"});
    if (o->foliage.surface_out == o->out)
      throw InputError("--surface-out", "must differ from --output '" + o->out + "'");
    FoliageSettings settings;
    ParamSet set;
    bind_foliage_params(set, settings);
    apply_foliage_options(*cmd, set);
    const FoliageRun run = foliage_run(o->foliage);
    const Scene scene = load_scene_for_cli(o->scene);
    IlluminationSetup setup = foliage_setup(settings, run, o->scene.seed, scene);
    setup.parameter_names = foliage_parameter_names(set);
    setup.encoding = KaEncoding::Attribute;  // unit normals and ka apart, as the file wants
    auto stats = std::make_shared<FoliageStats>();
    setup.on_done = [stats, report = setup.on_done](const FoliageStats& s) {
      *stats = s;
      if (report) report(s);
    };
    const FoliageParams params = setup.params;
    RenderGraph graph;
    const auto shading = add_foliage_illumination_pass(graph, std::move(setup));
    graph.present(shading);
    graph.compile();
    graph.execute();
    const auto& result = graph.get(shading);
    GlbVertexData data;
    data.normals = result->normals;
    data.ka = result->ka;
    data.note_json = baked_note(params, *stats);
    write_glb(scene, o->out, &data);
    std::printf("wrote %s\n", o->out.c_str());
  };
}

}  // namespace sylva::cli

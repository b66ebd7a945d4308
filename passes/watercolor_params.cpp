// The watercolor.* parameters (passes/watercolor.h WatercolorParams): names, units, ranges.
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/scene/scene_length.h"
#include "passes/watercolor.h"

namespace sylva {

void bind_watercolor_params(ParamSet& set, WatercolorParams& p) {
  set.add_float(
      "watercolor.blur", p.blur, 0.0, 64.0, "px at 1024 px",
      "Gaussian sigma of each wash's mask (a mass or a leaf cluster) before thresholding");
  set.add_float("watercolor.edge_softness", p.edge_softness, 0.0, 1.0, "",
                "threshold width: 0 hard wet-on-dry edges, 1 soft wet-on-wet edges");
  set.add_float("watercolor.edge_darkening", p.edge_darkening, 0.0, 1.0, "",
                "pigment pooling along each wash's rim");
  set.add_float("watercolor.rim_step", p.rim_step, 0.0, 1.0, "of the plant's depth",
                "depth step between two washes above which the nearer one's rim darkens");
  set.add_float("watercolor.mass", p.mass, 0.0, 1024.0, "px at 1024 px",
                "size of the masses the crown is painted as (0 = one wash per leaf cluster)");
  set.add_float("watercolor.gradation", p.gradation, 0.0, 1.0, "",
                "wet-in-wet: how far a wash's value follows the light inside it (0 = flat)");
  set.add_float("watercolor.paper_strength", p.paper_strength, 0.0, 1.0, "",
                "pigment density modulation by the paper grain (Bousseau's beta)");
  set.add_float("watercolor.turbulence_strength", p.turbulence_strength, 0.0, 1.0, "",
                "pigment density modulation by world-space turbulence (Bousseau's beta)");
  set.add_text(
      "watercolor.turbulence_size", p.turbulence_size,
      [](const std::string& text, const std::string& where) {
        (void)SceneLength::parse(text, where);
      },
      "\"auto\", a length in scene units (\"0.3\") or a share of the scene (\"6%\")",
      "feature size of the turbulence noise; auto = 6% of the scene");
  set.add_float("watercolor.wobble", p.wobble, 0.0, 8.0, "px at 1024 px",
                "RMS displacement of the wash outlines along the paper gradient");
  set.add_float("watercolor.strength", p.strength, 0.05, 1.0, "",
                "pigment the washes carry: their optical density scaled (1 full, 0.5 dilute)");
  set.add_float("watercolor.detail", p.detail, 0.0, 1.0, "",
                "leaf shading kept inside a wash where leaves stand in front (blurred depth test)");
  set.add_float(
      "watercolor.marks", p.marks, 0.0, 1.0, "",
      "pigment of the leaf-scale marks glazed over the washes, denser in shadow (0 = none)");
  set.add_float("watercolor.mark_size", p.mark_size, 2.0, 64.0, "px at 1024 px",
                "the smallest leaf mark's diameter (marks take each leaf's own shape)");
  set.add_float("watercolor.shadow", p.shadow, 0.0, 1.0, "",
                "glaze where the key light does not reach through the crown (0 = none)");
  set.add_float("watercolor.warm_cool", p.warm_cool, 0.0, 1.0, "",
                "warm light, cool shade: the shadow glaze ultramarine and lit washes warmer");
  set.add_float("watercolor.grain", p.grain, 1.0, 16.0, "px at 1024 px",
                "finest period of the generated paper grain");
  set.add_text(
      "watercolor.paper", p.paper,
      [](const std::string& text, const std::string& where) {
        if (text == "generated") return;
        std::error_code ec;
        if (text.empty() || !std::filesystem::is_regular_file(text, ec))
          throw InputError(where, "watercolor.paper: no such image file '" + text +
                                      "' (use \"generated\" or the path of a paper image)");
      },
      "\"generated\" or the path of a grey-scale paper image",
      "paper texture: generated from the seed, or an image tiled at 1 px per px at 1024 px");
  set.add_color("watercolor.paper_color", p.paper_color, "colour of the bare paper");
  set.add_choice("watercolor.pigment", p.pigment,
                 {{"shaded", Pigment::Shaded}, {"albedo", Pigment::Albedo}},
                 "pigment colour of a wash: the cluster's mean shaded or albedo colour");
  set.add_int("watercolor.seed", p.seed, 0, 2147483647, "",
              "seed of the generated paper and the turbulence noise");
}

}  // namespace sylva

#include "styles/style_params.h"

namespace sylva {

void bind_style_params(ParamSet& set, StyleParams& p) {
  set.add_choice("style.normals", p.normals, normal_mode_choices(),
                 "normals the raster pass draws with (Luft §3.3, Fig. 7c)");
  set.add_choice("style.albedo", p.albedo,
                 {{"textured", AlbedoSource::Textured}, {"flat", AlbedoSource::Flat}},
                 "albedo colours: the textures' texels, or each texture's mean (flat tones)");
  bind_foliage_params(set, p.foliage);
  bind_ao_params(set, p.ao);
  bind_edge_params(set, p.edges);
  bind_ink_params(set, p.ink);
  bind_ink_line_params(set, p.lines);
  bind_leaf_params(set, p.leaves);
  bind_pen_params(set, p.pen);
  bind_toon_params(set, p.toon);
  bind_watercolor_params(set, p.watercolor);
  bind_blob_params(set, p.blobs);
}

}  // namespace sylva

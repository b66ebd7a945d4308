#include "styles/style.h"

#include "core/error.h"

namespace sylva {

int build_standard(RenderGraph&, const GBufferHandles& gbuffer) {
  return gbuffer.color;
}

int build_expressive(RenderGraph&, const GBufferHandles& gbuffer) {
  return gbuffer.color;
}

const std::vector<StyleInfo>& style_table() {
  static const std::vector<StyleInfo> table = {
      {"standard", "local illumination (Luft et al. Eq. 1) with the model's own normals",
       &build_standard, NormalMode::Original},
      {"expressive",
       "Luft et al.: normals realigned to the foliage's implicit surface, ambient darkened by "
       "the leaf density (Eq. 1, 4)",
       &build_expressive, NormalMode::Realigned},
  };
  return table;
}

const StyleInfo& find_style(const std::string& name) {
  std::string names;
  for (const StyleInfo& s : style_table()) {
    if (s.name == name) return s;
    names += (names.empty() ? "" : ", ") + s.name;
  }
  throw InputError("--style", "unknown style '" + name + "' (available: " + names + ")");
}

}  // namespace sylva

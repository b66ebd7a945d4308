// Procedural textures for the sample plants: a broad ovate leaf (green blade, lighter
// midrib and veins, smooth alpha-cutout silhouette with a short petiole), a conifer needle
// and a bark modulation pattern. Deterministic (no randomness: a hash of the texel
// position). RGBA8, sRGB colour, rows top to bottom; in glTF UVs (v down) the leaf base
// (petiole) is at v = 1 and the tip at v = 0, the blade centred on u = 0.5.
#pragma once

#include "core/scene/scene.h"

namespace sylva {

enum class LeafTextureKind { Broadleaf, Needle };

// Width / length of the quad the texture is drawn for (physical aspect of the blade
// quad). The silhouette fills about 90% of the quad width at its widest point.
float leaf_quad_aspect(LeafTextureKind kind);

// Leaf or needle texture with alpha = coverage (0 outside, 255 inside, a ~1 texel smooth
// edge). height: texels along the leaf, default 128, range [16, 1024]; the width follows
// (Broadleaf: square, Needle: height / 4). Colour outside the silhouette is the blade's
// edge colour so filtering never bleeds black.
Texture make_leaf_texture(LeafTextureKind kind, int height = 128);

// Bark modulation texture: light grey (sRGB ~170..255) vertical furrows, alpha 255, to be
// multiplied with the bark material's brown base colour factor. size: texels, default 64,
// range [8, 1024]; tiles seamlessly in u and v.
Texture make_bark_texture(int size = 64);

}  // namespace sylva

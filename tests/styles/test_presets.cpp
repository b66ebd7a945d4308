// Style presets: inheritance order, --set overrides, and every kind of bad preset as a clear
// InputError naming the file and the key.
#include <gtest/gtest.h>

#include "core/error.h"
#include "styles/style.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

std::string write_preset(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name + ".toml";
  write_file(path, text);
  return path;
}

// The InputError's where() and what() for building a Style.
std::string error_of(const std::string& preset, const std::vector<std::string>& sets = {}) {
  try {
    Style s(preset, sets);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Presets, BuiltinsLoadAndNameABuilder) {
  const std::vector<std::string> names = builtin_preset_names();
  ASSERT_GE(names.size(), 2u);
  for (const std::string& n : names) {
    const Style s(n);
    EXPECT_NE(s.info().builder.empty(), s.info().layers.empty()) << n;  // one or the other
    EXPECT_EQ(s.layers().size(), s.info().layers.size()) << n;
    EXPECT_FALSE(s.info().description.empty()) << n;
    EXPECT_EQ(s.info().source, "built-in");
  }
  EXPECT_EQ(Style("standard").normals(), NormalMode::Original);
  EXPECT_EQ(Style("expressive").normals(), NormalMode::Realigned);
}

TEST(Presets, InheritanceIsOrderedAndOwnKeysWin) {
  const std::string dir = temp_dir("presets");
  write_preset(dir, "a", "builder = \"shaded\"\n[foliage]\ngrid = 40\nka_min = 0.3\n");
  write_preset(dir, "b", "[foliage]\ngrid = 50\nexponent = 2\n");
  const std::string c = write_preset(dir, "c",
                                     "description = \"mine\"\ninherits = [\"a\", \"b.toml\"]\n"
                                     "[foliage]\nexponent = 3\n");
  // "a" is not a path: a built-in name is looked up, and there is none called "a".
  EXPECT_NE(error_of(c).find("unknown style 'a'"), std::string::npos) << error_of(c);
  write_preset(dir, "c",
               "description = \"mine\"\ninherits = [\"expressive\", \"a.toml\", \"b.toml\"]\n"
               "[foliage]\nexponent = 3\n");
  const Style s(c, {"foliage.ka_min=0.4"});
  EXPECT_EQ(s.params().foliage.grid, 50);              // b after a
  EXPECT_FLOAT_EQ(s.params().foliage.ka_min, 0.4f);    // --set last
  EXPECT_FLOAT_EQ(s.params().foliage.exponent, 3.0f);  // own key over b's
  EXPECT_EQ(s.normals(), NormalMode::Realigned);       // from expressive
  EXPECT_EQ(s.info().builder, "shaded");
  EXPECT_EQ(s.info().description, "mine");
  EXPECT_EQ(s.info().chain, (std::vector<std::string>{"expressive", "a", "b", "c"}));
}

TEST(Presets, BadPresetsNameFileAndKey) {
  const std::string dir = temp_dir("bad-presets");
  struct Case {
    std::string text, needle;
  } cases[] = {
      {"builder = \"shaded\"\n[foliage\ngrid = 3\n", "line 2"},                // syntax error
      {"builder = \"shaded\"\n[foliage]\ngird = 40\n", "foliage.gird"},        // unknown key
      {"builder = \"shaded\"\n[foliage]\ngrid = \"many\"\n", "foliage.grid"},  // wrong type
      {"builder = \"shaded\"\n[foliage]\ngrid = 1\n", "[2, 1024]"},            // out of range
      {"builder = \"shaded\"\n[foliage]\ngrid = 40.5\n", "whole number"},
      {"builder = \"shaded\"\n[foliage]\nblend = [1]\n", "list"},
      {"builder = \"shaded\"\n[style]\nnormals = \"bent\"\n", "original"},
      {"builder = \"sketchy\"\n", "unknown builder 'sketchy'"},
      {"description = \"no builder\"\n", "names no builder"},
      {"builder = \"shaded\"\ncolour = 3\n", "unknown top-level key 'colour'"},
      {"builder = \"shaded\"\ninherits = \"standard\"\n", "inherits must be a list"},
      {"builder = \"shaded\"\n[foliage]\nrho = \"-3\"\n", "foliage.rho"},
      {"builder = \"shaded\"\n[foliage]\nper_triangle = 1\n", "true or false"},
  };
  int i = 0;
  for (const Case& c : cases) {
    std::string name = "p";
    name += std::to_string(i++);  // (not "p" + ...: GCC 12 warns falsely, -Wrestrict)
    const std::string path = write_preset(dir, name, c.text);
    const std::string what = error_of(path);
    EXPECT_NE(what.find(path), std::string::npos) << c.text << " -> " << what;
    EXPECT_NE(what.find(c.needle), std::string::npos) << c.text << " -> " << what;
  }
  // Inheritance cycles, direct and indirect.
  write_preset(dir, "x", "builder = \"shaded\"\ninherits = [\"y.toml\"]\n");
  const std::string y = write_preset(dir, "y", "inherits = [\"x.toml\"]\n");
  EXPECT_NE(error_of(y).find("inheritance cycle"), std::string::npos) << error_of(y);
  const std::string self = write_preset(dir, "self", "inherits = [\"self.toml\"]\n");
  EXPECT_NE(error_of(self).find("inheritance cycle"), std::string::npos);
  EXPECT_NE(error_of(dir + "/missing.toml").find("missing.toml"), std::string::npos);
  EXPECT_NE(error_of("nonesuch").find("unknown style 'nonesuch'"), std::string::npos);
}

TEST(Presets, StackedPresetsHoldALayerPerPresetWithTheStacksKeysOnEach) {
  const Style s("pen-and-wash", {"ink.detail=6", "watercolor.blur=9"});
  ASSERT_EQ(s.layers().size(), 2u);
  EXPECT_EQ(s.layers()[0]->info().builder, "watercolor");
  EXPECT_EQ(s.layers()[1]->info().builder, "ink");
  for (const auto& layer : s.layers()) {
    EXPECT_FLOAT_EQ(layer->params().lines.detail, 6.0f);
    EXPECT_FLOAT_EQ(layer->params().watercolor.blur, 9.0f);
  }
  EXPECT_TRUE(s.has_strokes());
  // The G-buffers follow the line layer.
  EXPECT_EQ(s.normals(), Style("ink").normals());
  EXPECT_FLOAT_EQ(s.params().lines.detail, 6.0f);
  RasterRequest request;
  s.configure(request);
  EXPECT_EQ(request.id_kind, IdKind::Cluster);
  EXPECT_EQ(request.background.a, 0.0f);  // ink reads the colour's alpha as coverage

  const std::string dir = temp_dir("layer-presets");
  const std::string mine =
      write_preset(dir, "mine", "layers = [\"toon\", \"pen\"]\n[pen]\nspacing = 6\n");
  const Style m(mine);
  EXPECT_FLOAT_EQ(m.layers()[0]->params().pen.spacing, 6.0f);
  EXPECT_FLOAT_EQ(m.layers()[1]->params().pen.spacing, 6.0f);
  EXPECT_EQ(m.layers()[1]->params().pen.tone, PenTone::Hatching);  // pen's own keys kept
}

TEST(Presets, BadLayersNameFileAndReason) {
  const std::string dir = temp_dir("bad-layers");
  write_preset(dir, "stack", "layers = [\"watercolor\", \"ink\"]\n");
  struct Case {
    std::string text, needle;
  } cases[] = {
      {"layers = []\n", "one or more"},
      {"layers = \"ink\"\n", "layers must be a list"},
      {"layers = [3]\n", "layers must list strings"},
      {"builder = \"ink\"\nlayers = [\"ink\"]\n", "both a builder ('ink') and layers"},
      {"layers = [\"ink\", \"toon\"]\n", "layer 'toon' draws no lines"},
      {"layers = [\"ink\", \"ink\"]\n", "named twice"},
      {"layers = [\"stack.toml\", \"ink\"]\n", "itself a stack"},
      {"layers = [\"nonesuch\"]\n", "unknown style 'nonesuch'"},
  };
  int i = 0;
  for (const Case& c : cases) {
    std::string name = "l";
    name += std::to_string(i++);
    const std::string path = write_preset(dir, name, c.text);
    const std::string what = error_of(path);
    EXPECT_NE(what.find(c.needle), std::string::npos) << c.text << " -> " << what;
  }
}

TEST(Presets, SetOverridesAreCheckedLikePresetKeys) {
  EXPECT_EQ(error_of("standard", {"foliage.grid=64"}), "");
  EXPECT_NE(error_of("standard", {"foliage.grid=0"}).find("--set"), std::string::npos);
  EXPECT_NE(error_of("standard", {"foliage.grid"}).find("section.key=value"), std::string::npos);
  EXPECT_NE(error_of("standard", {"edgez.width=2"}).find("unknown key"), std::string::npos);
  EXPECT_NE(error_of("standard", {"foliage.ka_min=abc"}).find("[0, 1]"), std::string::npos);
  EXPECT_NE(error_of("standard", {"foliage.per_triangle=maybe"}).find("true or false"),
            std::string::npos);
  const Style s("standard",
                {"foliage.rho=5%", "foliage.per_triangle=true", "style.normals=realigned-scaled"});
  EXPECT_EQ(s.params().foliage.rho, "5%");
  EXPECT_TRUE(s.params().foliage.per_triangle);
  EXPECT_EQ(s.normals(), NormalMode::RealignedScaled);
}

}  // namespace
}  // namespace sylva::test

// `sylva` on OBJ files the strict reader refuses (issue 37; core/scene/obj_read.cpp): exit 2,
// one error line naming the file, the line and the token, and no output (nor a temporary file)
// left; the OBJ variants it accepts (`v x y z w`, vertex colours) render.
#include <gtest/gtest.h>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(ObjCli, RefusedFilesExitTwoAndWriteNothing) {
  const std::string dir = temp_dir("obj-cli-refused");
  const std::string index =
      "expected a vertex index (1 to 3, or -1 to -3 counting back from the "
      "last 'v'), got ";
  const struct {
    const char* name;
    std::string text, error;
  } cases[] = {
      {"wrap.obj", kTriangle + "f 1 2 4294967299\n", "line 4: " + index + "'4294967299'"},
      {"relative.obj", kTriangle + "f 1 2 -5\n", "line 4: " + index + "'-5'"},
      {"garbage.obj", kTriangle + "f 1 2 3x\n", "line 4: " + index + "'3x'"},
      {"nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
       "line 1: expected a finite number (magnitude at most 3.4e38), got 'nan'"},
      {"junk.obj", "v 0 0 0 junk\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
       "line 1: expected a number, got 'junk'"},
      {"uv.obj", kTriangle + "f 1/1/1 2//2 3\n",
       "line 4: expected a texture coordinate index of a 'vt' line before this one (there is "
       "none), got '1' in '1/1/1'"},
  };
  for (const auto& c : cases) {
    const std::string path = dir + "/" + c.name, out = dir + "/out";
    write_file(path, c.text);
    expect_input_error("info " + path, path + ": " + c.error);
    expect_input_error("render " + path + " --size 32 -o " + out + ".png", path + ": " + c.error);
    expect_input_error("render " + path + " --size 32 --style ink -o " + out + ".svg",
                       path + ": " + c.error);
  }
  std::vector<std::string> names = listing(dir);
  EXPECT_EQ(names, (std::vector<std::string>{"garbage.obj", "junk.obj", "nan.obj", "relative.obj",
                                             "uv.obj", "wrap.obj"}));
}

TEST(ObjCli, WeightsAndColoursRender) {
  const std::string dir = temp_dir("obj-cli-variants");
  write_file(dir + "/w.obj", "v 0 0 0 1\nv 1 0 0 1\nv 1 1 0 0.5\nv 0 1 0 1\nf 1 2 3 4\n");
  write_file(dir + "/rgb.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  for (const char* name : {"w", "rgb"}) {
    const std::string path = dir + "/" + name;
    const RunResult r = run_sylva("render " + path + ".obj --size 32 -o " + path + ".png");
    EXPECT_EQ(r.status, 0) << name << "\n" << r.output;
    EXPECT_TRUE(file_exists(path + ".png")) << name;
  }
}

}  // namespace
}  // namespace sylva::test

// sylva.load, sylva.sample and the Scene object (python/binding.h).
#include <stdlib.h>  // mkdtemp

#include <filesystem>

#include "core/cache/result_cache.h"
#include "core/scene/gltf_write.h"
#include "core/scene/scene_info.h"
#include "python/binding.h"
#include "samples/grass.h"
#include "samples/plants.h"

namespace fs = std::filesystem;

namespace sylva::python {

namespace {

// The cache folder of cache_dir=: None = the CLI's default (SYLVA_CACHE_DIR, ...), "" or
// False = none.
std::string cache_dir_of(const py::object& cache_dir) {
  if (cache_dir.is_none()) return default_cache_dir();
  if (py::isinstance<py::bool_>(cache_dir))
    return cache_dir.cast<bool>() ? default_cache_dir() : "";
  return cache_dir.cast<std::string>();
}

struct LoadArgs {
  SceneOptions scene;
  ViewOptions view;
  std::string cache_dir;
};

LoadArgs load_args(const std::string& path, const std::string& foliage, int clusters, uint64_t seed,
                   bool ground, const std::string& ground_color, bool lod,
                   const py::object& cache_dir) {
  LoadArgs a;
  a.scene.path = path;
  a.scene.foliage = foliage;
  a.scene.clusters = clusters;
  a.scene.seed = seed;
  a.view.ground = ground;
  a.view.ground_color = ground_color;
  a.view.lod = lod ? "on" : "off";
  a.cache_dir = cache_dir_of(cache_dir);
  return a;
}

// The loader's warnings as Python's (UserWarning), each the line the CLI prints after
// "sylva: warning: ".
void warn(const PyScene& s) {
  for (const std::string& w : s.frame->scene.report.warning_lines()) {
    const std::string line = s.options.path + ": " + w;
    if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 1) != 0) throw py::error_already_set();
  }
}

// Loads (as `sylva render` does: load_clustered_scene) and uploads, the GIL released; the
// context is left current in no thread.
std::shared_ptr<PyScene> open_scene(const LoadArgs& a, const std::string& source = "") {
  auto s = std::make_shared<PyScene>();
  s->options = a.scene;
  s->load_view = a.view;
  s->cache_dir = a.cache_dir;
  try {
    py::gil_scoped_release nogil;
    Scene scene = load_clustered_scene(a.scene);
    if (!source.empty()) scene.report.source = source;
    ViewOptions vo = a.view;
    s->frame = make_frame(std::move(scene), vo, a.cache_dir);
    s->frame->context->release_current();
  } catch (const InputError& e) {
    rethrow_load_error(e, a.scene.path);
  }
  warn(*s);
  return s;
}

// A fresh folder under the system's temporary folder, removed with the object.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "sylva-sample-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("sylva: cannot make a temporary folder");
    path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// sylva.sample: the plant `sylva sample KIND` writes, written to a temporary .glb and loaded
// from it (with the load's default seed, 1, as `sylva render` loads it), so the scene is the one
// the CLI renders from that file.
std::shared_ptr<PyScene> sample(const std::string& kind, uint64_t seed, int leaves, int blades,
                                const LoadArgs& args) {
  const TempDir dir;
  LoadArgs a = args;
  a.scene.path = (dir.path / (kind + ".glb")).string();
  std::string source = "sample " + kind + " --seed " + std::to_string(seed);
  {
    py::gil_scoped_release nogil;
    if (kind == "grass") {
      if (leaves != 0) throw InputError("--leaves", "applies to tree, bush and conifer");
      GrassOptions go;
      go.seed = seed;
      if (blades != 0) go.blades = blades;
      write_glb(make_grass(go), a.scene.path);
    } else {
      if (blades != 0) throw InputError("--blades", "applies to grass only");
      PlantOptions po;
      po.kind = parse_plant_kind(kind);
      po.seed = seed;
      po.leaves = leaves;
      write_glb(make_plant(po), a.scene.path);
    }
  }
  if (leaves != 0) source += " --leaves " + std::to_string(leaves);
  if (blades != 0) source += " --blades " + std::to_string(blades);
  return open_scene(a, source);
}

py::object info(const PyScene& s) {
  const std::string json = scene_info_json(s.frame->scene);
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<PyScene, std::shared_ptr<PyScene>>(
      m, "Scene",
      "A loaded scene, uploaded once, rendered many times (sylva.load, sylva.sample). Renders "
      "of one Scene run one at a time; the foliage preprocessing is cached per Scene.")
      .def("info", &info, "What the scene holds, as `sylva info --json` prints it (a dict)")
      .def_property_readonly(
          "cameras", [](const PyScene& s) -> py::object { return info(s)["cameras"]; },
          "The file's cameras (name, type, eye, ...): camera= takes a name or an index")
      .def_property_readonly(
          "source", [](const PyScene& s) { return s.frame->scene.report.source; },
          "The file it was loaded from, or the sample's description")
      .def("__repr__", [](const PyScene& s) {
        return "<sylva.Scene '" + s.frame->scene.report.source +
               "': " + std::to_string(s.frame->scene.drawn_triangle_count()) + " triangles>";
      });
  m.def(
      "load",
      [](const std::string& path, const std::string& foliage, int clusters, uint64_t seed,
         bool ground, const std::string& ground_color, bool lod, const py::object& cache_dir) {
        return open_scene(
            load_args(path, foliage, clusters, seed, ground, ground_color, lod, cache_dir));
      },
      "Loads a scene file (.glb, .gltf, .obj, .ply, .off, .stl) as `sylva render` does",
      py::arg("path"), py::kw_only(), py::arg("foliage") = "auto", py::arg("clusters") = 0,
      py::arg("seed") = 1, py::arg("ground") = false, py::arg("ground_color") = "#b4b4ac",
      py::arg("lod") = true, py::arg("cache_dir") = py::none());
  m.def(
      "sample",
      [](const std::string& kind, uint64_t seed, int leaves, int blades, int clusters, bool ground,
         const py::object& cache_dir) {
        return sample(kind, seed, leaves, blades,
                      load_args("", "auto", clusters, 1, ground, "#b4b4ac", true, cache_dir));
      },
      "A procedural plant (tree, bush, conifer) or grass patch, as `sylva sample KIND` writes "
      "it and `sylva render` loads it",
      py::arg("kind") = "tree", py::kw_only(), py::arg("seed") = 1, py::arg("leaves") = 0,
      py::arg("blades") = 0, py::arg("clusters") = 0, py::arg("ground") = false,
      py::arg("cache_dir") = py::none());
}

}  // namespace sylva::python

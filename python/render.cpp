// sylva.render, sylva.buffers and sylva.save (python/binding.h): the library's render_styled,
// render_buffers and writers, as `sylva render`, `sylva buffers` and -o call them.
#include <opencv2/imgproc.hpp>

#include "core/io/svg_writer.h"
#include "python/binding.h"
#include "styles/style_files.h"

namespace sylva::python {

namespace {

// A style name, or a preset file as str or os.PathLike.
std::string style_name(const py::object& style) {
  return py::module_::import("os").attr("fspath")(style).cast<std::string>();
}

// The scene's GL backend is chosen when it loads ($SYLVA_GL, else auto: EGL, then OSMesa);
// `gl` may name it (or auto), and names anything else as an error.
void check_gl(const PyScene& scene, const py::object& gl) {
  if (gl.is_none()) return;
  const GlChoice choice = parse_gl_choice(gl.cast<std::string>(), "gl");
  const GlBackend used = scene.frame->context->info().backend;
  if (choice.backend == GlBackend::Auto || choice.backend == used) return;
  throw InputError("gl", std::string("this scene renders with ") + gl_backend_name(used) +
                             ", chosen when it was loaded (set SYLVA_GL before sylva.load)");
}

// Row-major rows of a glm (column-major) matrix: rows[i][j] = m[j][i], so that
// p_view = view @ p_world for column vectors, as camera.json writes it.
py::array_t<float> matrix(const glm::mat4& m) {
  py::array_t<float> a({4, 4});
  auto r = a.mutable_unchecked<2>();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      r(i, j) = m[j][i];
  return a;
}

py::dict camera_dict(const Camera& c) {
  py::dict d;
  d["view"] = matrix(c.view);
  d["proj"] = matrix(c.proj);
  d["eye"] = py::make_tuple(c.eye.x, c.eye.y, c.eye.z);
  d["near"] = c.near_plane;
  d["far"] = c.far_plane;
  d["ortho"] = c.ortho;
  d["width"] = c.width;
  d["height"] = c.height;
  return d;
}

py::object render(PyScene& scene, const py::object& style, const py::object& params,
                  const std::string& format, const py::object& gl, const py::kwargs& view) {
  check_gl(scene, gl);
  if (format != "rgba" && format != "svg")
    throw InputError("format", "expected 'rgba' (an image) or 'svg', got '" + format + "'");
  const std::unique_ptr<Style> st = make_style(style_name(style), params);
  ViewOptions vo = view_options(view, scene.load_view);
  const bool svg = format == "svg";
  if (svg) require_line_style(*st, "format");
  StyledRender r = rendering(scene, [&] {
    const SheetScene sheet = frame_scene(scene, vo);
    return render_styled(sheet, *st, svg);
  });
  if (svg)
    return py::str(svg_document(*r.strokes, vector_page(*st, vo.background == "transparent", 0.0)));
  cv::cvtColor(r.image, r.image, cv::COLOR_BGRA2RGBA);
  return array_of(std::move(r.image));
}

py::dict buffers(PyScene& scene, const std::vector<std::string>& names, const py::object& style,
                 const py::object& normals, const py::object& params, const py::kwargs& view) {
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ",") + n;
  const TargetMask wanted = parse_buffer_list(list);
  const std::unique_ptr<Style> st = make_style(style_name(style), params);
  const NormalMode mode = normals.is_none()
                              ? st->normals()
                              : parse_normal_mode(normals.cast<std::string>(), "--normals");
  ViewOptions vo = view_options(view, scene.load_view);
  Camera camera;
  BufferImages images = rendering(scene, [&] {
    Frame& frame = *scene.frame;
    set_frame_view(frame, vo);
    frame.setup.request.flat_albedo = st->params().albedo == AlbedoSource::Flat;
    camera = frame.setup.camera;
    FoliageRun run;
    run.cache_dir = scene.cache_dir;
    return render_buffers(frame, *st, run, scene.options.seed, mode, wanted, {}, scene.memos.get());
  });
  py::dict out;
  for (auto& [target, mat] : images) {
    if (mat.type() == CV_8UC4) cv::cvtColor(mat, mat, cv::COLOR_BGRA2RGBA);
    out[target_name(target)] = array_of(std::move(mat));
  }
  out["camera"] = camera_dict(camera);
  return out;
}

void save(const py::array& image, const py::object& path, double dpi, int bit_depth) {
  const std::string p = py::module_::import("os").attr("fspath")(path).cast<std::string>();
  check_dpi(dpi, "dpi");
  if (bit_depth != 8 && bit_depth != 16)
    throw InputError("bit_depth", "must be 8 or 16, got " + std::to_string(bit_depth));
  const cv::Mat bgra = bgra_of(image);
  py::gil_scoped_release nogil;
  write_styled_image(p, bgra, dpi, bit_depth);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("render", &render,
        "Renders `scene` in `style` (a built-in name or a preset file) as `sylva render` does: "
        "an H x W x 4 uint8 RGBA array (sRGB, straight alpha), or the SVG text of a line style "
        "with format='svg'. View keywords: size, azimuth, elevation, distance, fov, ortho, "
        "camera, ssaa, background, ambient, lights; params: {'ink.detail': 6, ...}",
        py::arg("scene"), py::arg("style") = "standard", py::kw_only(),
        py::arg("params") = py::none(), py::arg("format") = "rgba", py::arg("gl") = py::none());
  m.def("buffers", &buffers,
        "The G-buffers `names` (color, normal, depth, position, id, ka, albedo, ao) as `sylva "
        "buffers` renders them: a dict of arrays (uint8 RGBA, float32, uint32 ids) and 'camera' "
        "(view and proj as 4x4 row-major matrices, eye, near, far, ortho, width, height)",
        py::arg("scene"),
        py::arg("names") = std::vector<std::string>{"color", "normal", "depth", "id"},
        py::kw_only(), py::arg("style") = "standard", py::arg("normals") = py::none(),
        py::arg("params") = py::none());
  m.def("save", &save,
        "Writes an RGBA (or RGB) uint8 image as .png, .tiff, .jpg or .exr (by the extension) "
        "through the library's writers, atomically; dpi > 0 goes into the file",
        py::arg("image"), py::arg("path"), py::kw_only(), py::arg("dpi") = 0.0,
        py::arg("bit_depth") = 8);
}

}  // namespace sylva::python

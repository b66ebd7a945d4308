// Python values to the library's options and back (python/binding.h).
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "python/binding.h"
#include "styles/sheet.h"

namespace sylva::python {

namespace {

// "WxH" from (w, h), an int N or a string as --size takes it.
std::string size_text(const py::handle& size) {
  if (py::isinstance<py::str>(size)) return size.cast<std::string>();
  if (py::isinstance<py::int_>(size)) return std::to_string(size.cast<long long>());
  const auto wh = size.cast<std::pair<long long, long long>>();
  return std::to_string(wh.first) + "x" + std::to_string(wh.second);
}

// A float keyword argument; ValueError("--option: ...") when it is not finite, as the CLI
// names its options.
float finite_float(const py::handle& value, const std::string& option) {
  const double v = value.cast<double>();
  if (!std::isfinite(v))
    throw InputError(option, "must be a finite number, got " + py::repr(value).cast<std::string>());
  return static_cast<float>(v);
}

std::string value_text(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v))
    return py::repr(v).cast<std::string>();
  throw py::type_error("params values must be numbers, bools or strings, got " +
                       py::repr(v).cast<std::string>());
}

void set_view_key(ViewOptions& o, const std::string& key, const py::handle& v) {
  if (key == "size")
    o.size = size_text(v);
  else if (key == "azimuth")
    o.orbit.azimuth_deg = finite_float(v, "--azimuth");
  else if (key == "elevation")
    o.orbit.elevation_deg = finite_float(v, "--elevation");
  else if (key == "distance")
    o.orbit.distance = finite_float(v, "--distance");
  else if (key == "fov")
    o.orbit.fov_deg = finite_float(v, "--fov");
  else if (key == "ambient")
    o.ambient = finite_float(v, "--ambient");
  else if (key == "ortho")
    o.orbit.ortho = v.cast<bool>();
  else if (key == "ssaa")
    o.ssaa = v.cast<int>();
  else if (key == "background")
    o.background = v.cast<std::string>();
  else if (key == "lights")
    o.lights = v.cast<std::vector<std::string>>();
  else if (key == "id")
    o.id_kind = v.cast<std::string>();
  else if (key == "camera")
    o.camera = v.is_none()                   ? ""
               : py::isinstance<py::int_>(v) ? std::to_string(v.cast<int>())
                                             : v.cast<std::string>();
  else
    throw py::type_error("unexpected keyword argument '" + key +
                         "' (view: size, azimuth, elevation, distance, fov, ortho, camera, "
                         "ssaa, background, ambient, lights, id)");
}

}  // namespace

ViewOptions view_options(const py::dict& view, const ViewOptions& base) {
  ViewOptions o = base;
  for (const auto& [key, value] : view) {
    const std::string name = key.cast<std::string>();
    if (value.is_none() && name != "camera") continue;
    try {
      set_view_key(o, name, value);
    } catch (const py::cast_error&) {
      throw py::type_error("keyword '" + name + "': unexpected type " +
                           py::repr(py::type::handle_of(value)).cast<std::string>());
    }
  }
  resolve_view_options(o);
  return o;
}

std::vector<std::string> assignments(const py::object& params) {
  std::vector<std::string> out;
  if (params.is_none()) return out;
  if (!py::isinstance<py::dict>(params))
    throw py::type_error("params must be a dict of 'section.key': value");
  for (const auto& [key, value] : params.cast<py::dict>()) {
    if (!py::isinstance<py::str>(key)) throw py::type_error("params keys must be strings");
    out.push_back(key.cast<std::string>() + "=" + value_text(value));
  }
  return out;
}

std::unique_ptr<Style> make_style(const std::string& name, const py::object& params) {
  return std::make_unique<Style>(name, assignments(params));
}

py::array array_of(cv::Mat mat) {
  const int depth = mat.depth();
  py::dtype dtype = depth == CV_8U    ? py::dtype::of<uint8_t>()
                    : depth == CV_32F ? py::dtype::of<float>()
                    : depth == CV_32S ? py::dtype::of<uint32_t>()
                                      : throw std::runtime_error("sylva: unexpected buffer type");
  auto* owned = new cv::Mat(std::move(mat));
  py::capsule owner(owned, [](void* p) { delete static_cast<cv::Mat*>(p); });
  const auto elem = static_cast<py::ssize_t>(owned->elemSize1());
  const auto step = static_cast<py::ssize_t>(owned->step[0]);
  const py::ssize_t channels = owned->channels();
  if (channels == 1)
    return py::array(dtype, {py::ssize_t(owned->rows), py::ssize_t(owned->cols)},
                     {step, elem * channels}, owned->data, owner);
  return py::array(dtype, {py::ssize_t(owned->rows), py::ssize_t(owned->cols), channels},
                   {step, elem * channels, elem}, owned->data, owner);
}

cv::Mat bgra_of(const py::array& image) {
  const auto a = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(image);
  if (!a || image.dtype().kind() != 'u' || image.itemsize() != 1 || a.ndim() != 3 ||
      (a.shape(2) != 3 && a.shape(2) != 4))
    throw InputError("image", "expected an H x W x 4 (RGBA) or H x W x 3 (RGB) uint8 array");
  const int channels = static_cast<int>(a.shape(2));
  const cv::Mat view(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), CV_8UC(channels),
                     const_cast<uint8_t*>(a.data()));
  cv::Mat bgra;
  cv::cvtColor(view, bgra, channels == 4 ? cv::COLOR_RGBA2BGRA : cv::COLOR_RGB2BGRA);
  return bgra;
}

void rethrow_load_error(const InputError& e, const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    PyErr_SetString(PyExc_FileNotFoundError, e.what());
    throw py::error_already_set();
  }
  throw e;
}

SheetScene frame_scene(PyScene& scene, ViewOptions& view) {
  set_frame_view(*scene.frame, view);
  FoliageRun run;
  run.cache_dir = scene.cache_dir;
  SheetScene sheet =
      make_sheet_scene(scene.frame->scene, scene.frame->setup, run, scene.options.seed);
  share_memos(sheet, scene.memos);
  return sheet;
}

}  // namespace sylva::python

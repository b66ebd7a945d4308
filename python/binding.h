// The Python module's shared parts (docs/python.md): the Scene object behind sylva.load and
// sylva.sample, the conversions between Python values and the library's options, numpy arrays
// over cv::Mat without a copy, and the rule every render follows (GIL released, one render of
// a scene at a time, Ctrl-C as KeyboardInterrupt). The module binds the library's entry points
// (styles/view.h, styles/frame.h, styles/turntable_frames.h, styles/style_files.h); it does not
// run the CLI.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"
#include "styles/frame.h"
#include "styles/style.h"
#include "styles/view.h"

namespace sylva::python {

namespace py = pybind11;

// A loaded scene with its GL context and uploaded geometry (one per Scene object) and what its
// renders share (FrameMemos: the preprocessing is paid once per settings, not per render).
struct PyScene {
  SceneOptions options;   // path (or the sample's description), foliage, clusters, seed
  ViewOptions load_view;  // ground, ground_color and lod: fixed when the scene is uploaded
  std::string cache_dir;  // the result cache folder; "" = none
  std::unique_ptr<Frame> frame;
  std::shared_ptr<FrameMemos> memos = std::make_shared<FrameMemos>();
  std::mutex mutex;  // one render at a time: the frame's GL context and rasterizer are one
};

// Keyword arguments of a view (size, azimuth, elevation, distance, fov, ortho, camera, ssaa,
// background, ambient, lights; `id` for buffers) over `base`. Unknown keys: TypeError, as for
// a function's keyword arguments; values are checked by resolve_view_options (ValueError).
ViewOptions view_options(const py::dict& view, const ViewOptions& base);

// {"ink.detail": 6, "ink.paper": "#f0e8d8"} as --set assignments "ink.detail=6": numbers as
// Python prints them (repr), bools as true/false, strings as they are. TypeError for a
// non-dict or a key that is not a string.
std::vector<std::string> assignments(const py::object& params);

// The style `name` (built-in or .toml path) with `params`; InputError (ValueError) for a bad
// name or value.
std::unique_ptr<Style> make_style(const std::string& name, const py::object& params);

// A numpy array over `mat` (moved to the heap, freed with the last view): H x W (one channel)
// or H x W x C, of uint8, float32 or uint32 (CV_32S ids, the same bits), strides from its step.
py::array array_of(cv::Mat mat);
// An H x W x 4 (RGBA) or H x W x 3 (RGB) uint8 array as a BGRA cv::Mat (a copy in OpenCV's
// channel order); ValueError for another shape or type.
cv::Mat bgra_of(const py::array& image);

// The file's errors as Python's: FileNotFoundError when `path` does not exist, else the
// InputError (ValueError) as it is.
[[noreturn]] void rethrow_load_error(const InputError& e, const std::string& path);

// Runs `work` with the GIL released, the scene locked, SIGINT turned into a stop between
// render passes (main thread) and the scene's GL context released after, so another thread
// may render it next. A stop raises KeyboardInterrupt (Interrupted, translated).
template <typename Work>
auto rendering(PyScene& scene, Work&& work) {
  py::gil_scoped_release nogil;
  const std::lock_guard lock(scene.mutex);
  const ScopedInterruptHandler sigint;
  struct Release {
    GlContext& context;
    ~Release() { context.release_current(); }
  } release{*scene.frame->context};
  try {
    auto result = work();
    check_interrupt();  // a Ctrl-C after the last pass still stops the script
    return result;
  } catch (const Interrupted&) {
    clear_interrupt();
    throw;
  }
}

// The frame's view set from `view` (view_options over the load view) and its sheet scene with
// the scene's memos; call inside rendering().
SheetScene frame_scene(PyScene& scene, ViewOptions& view);

void bind_scene(py::module_& m);
void bind_render(py::module_& m);
void bind_styles(py::module_& m);
void bind_turntable(py::module_& m);

}  // namespace sylva::python

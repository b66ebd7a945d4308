// sylva.turntable (python/binding.h): the frames of `sylva turntable` as an iterator of arrays
// (or SVG texts), each rendered when asked for (styles/turntable_frames.h).
#include <opencv2/imgproc.hpp>

#include "core/io/svg_writer.h"
#include "python/binding.h"
#include "styles/style_files.h"
#include "styles/turntable_frames.h"
#include "styles/video_out.h"

namespace sylva::python {

namespace {

class Turntable {
 public:
  Turntable(std::shared_ptr<PyScene> scene, std::unique_ptr<Style> style, ViewOptions view,
            const TurntablePath& path, int keyframe_every, bool svg)
      : m_scene(std::move(scene)),
        m_style(std::move(style)),
        m_view(std::move(view)),
        m_frames(path.frames),
        m_svg(svg) {
    rendering(*m_scene, [&] {
      m_sheet = frame_scene(*m_scene, m_view);
      m_renderer = std::make_unique<TurntableRenderer>(m_sheet, *m_style, path, keyframe_every);
      return 0;
    });
  }

  int size() const { return m_frames; }

  py::object next() {
    if (m_next >= m_frames) throw py::stop_iteration();
    const int frame = m_next++;
    TurntableFrame f = rendering(*m_scene, [&] { return m_renderer->render(frame, false, m_svg); });
    if (m_svg)
      return py::str(
          svg_document(*f.strokes, vector_page(*m_style, m_view.background == "transparent", 0.0)));
    cv::cvtColor(f.image, f.image, cv::COLOR_BGRA2RGBA);
    return array_of(std::move(f.image));
  }

 private:
  std::shared_ptr<PyScene> m_scene;  // kept alive while frames are asked for
  std::unique_ptr<Style> m_style;
  ViewOptions m_view;
  SheetScene m_sheet;
  std::unique_ptr<TurntableRenderer> m_renderer;
  int m_frames = 0, m_next = 0;
  bool m_svg = false;
};

std::unique_ptr<Turntable> turntable(const std::shared_ptr<PyScene>& scene, const py::object& style,
                                     int frames, float degrees, const std::string& axis, float zoom,
                                     int keyframe_every, const py::object& params,
                                     const std::string& format, const py::kwargs& view) {
  if (format != "rgba" && format != "svg")
    throw InputError("format", "expected 'rgba' (images) or 'svg', got '" + format + "'");
  TurntablePath path;
  path.frames = frames;
  path.degrees = degrees;
  path.axis = axis.size() == 1 ? axis[0] : '?';
  path.zoom = zoom;
  validate_turntable(path);
  auto st = make_style(py::module_::import("os").attr("fspath")(style).cast<std::string>(), params);
  if (format == "svg") require_line_style(*st, "format");
  ViewOptions base = scene->load_view;
  base.size = "512x512";  // as `sylva turntable`
  ViewOptions vo = view_options(view, base);
  return std::make_unique<Turntable>(scene, std::move(st), std::move(vo), path, keyframe_every,
                                     format == "svg");
}

// Frames (RGBA or RGB uint8 arrays of one size) into an MP4, as `sylva turntable -o x.mp4`
// writes them (alpha dropped); returns the frame count. Nothing is left behind on failure.
int save_video(const py::iterable& frames, const py::object& path, double fps) {
  if (!(fps > 0.0 && fps <= 1000.0)) throw InputError("fps", "must be in (0, 1000]");
  const std::string p = py::module_::import("os").attr("fspath")(path).cast<std::string>();
  std::unique_ptr<VideoOut> video;
  cv::Size size;
  int count = 0;
  for (const py::handle& frame : frames) {
    const cv::Mat bgra = bgra_of(frame.cast<py::array>());
    if (!video) {
      size = bgra.size();
      video = std::make_unique<VideoOut>(p, fps, size);
    }
    if (bgra.size() != size)
      throw InputError("frames", "every frame must have the first one's size");
    cv::Mat bgr;
    cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
    py::gil_scoped_release nogil;
    video->write(bgr);
    ++count;
  }
  if (!video) throw InputError("frames", "no frame to write");
  py::gil_scoped_release nogil;
  video->finish();
  return count;
}

}  // namespace

void bind_turntable(py::module_& m) {
  py::class_<Turntable>(m, "Turntable", "The frames of a turntable, rendered one per next()")
      .def("__iter__", [](Turntable& t) -> Turntable& { return t; })
      .def("__next__", &Turntable::next)
      .def("__len__", &Turntable::size);
  m.def("turntable", &turntable,
        "The frames of `sylva turntable` (the camera turned `degrees` over `frames` about "
        "`axis`) as an iterator of RGBA arrays, or SVG texts with format='svg'; view keywords "
        "as render's (size defaults to 512)",
        py::arg("scene"), py::arg("style") = "standard", py::kw_only(), py::arg("frames") = 120,
        py::arg("degrees") = 360.0f, py::arg("axis") = "y", py::arg("zoom") = 1.0f,
        py::arg("keyframe_every") = 1, py::arg("params") = py::none(), py::arg("format") = "rgba");
  m.def("save_video", &save_video,
        "Writes frames (RGBA or RGB uint8 arrays of one size, e.g. sylva.turntable's) as an MP4 "
        "through the library's writer (FFmpeg, in the codecs plugin), alpha dropped; returns "
        "the frame count",
        py::arg("frames"), py::arg("path"), py::kw_only(), py::arg("fps") = 24.0);
}

}  // namespace sylva::python

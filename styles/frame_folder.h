// Folders of turntable frames (frame-00000.png, ...): names, and whether a frame on disk is
// complete. What `turntable --resume` keeps and `sylva encode` reads.
#pragma once

#include <string>

namespace sylva {

// What a frame folder holds (turntable --frame-format): images, or a line style's strokes.
enum class FrameFormat { Png, Exr, Svg, Pdf };
// "png", "exr", "svg", "pdf": the format's name and its files' extension (without the dot).
const char* frame_format_name(FrameFormat format);
// The format named `name`; InputError(where, "must be png, exr, svg or pdf, not '...'").
FrameFormat parse_frame_format(const std::string& name, const std::string& where);
inline bool is_vector_format(FrameFormat f) {
  return f == FrameFormat::Svg || f == FrameFormat::Pdf;
}

// "frame-00012.png": the name of frame `frame` (0 .. 99999) in a frame folder.
std::string frame_file_name(int frame, FrameFormat format = FrameFormat::Png);

// "frame-NNNNN.EXT" → NNNNN; -1 for any other name.
int frame_index_of(const std::string& name, FrameFormat format = FrameFormat::Png);

// Empty when the frame file at `path` is complete; otherwise why not ("no such file", "cannot
// decode the image: <libpng's reason>", "truncated"). A PNG is decoded whole; an SVG must end
// with its closing tag, a PDF with %%EOF, an EXR must start with OpenEXR's magic number.
std::string frame_problem(const std::string& path, FrameFormat format);

// Removes the temporary files a killed writer left for frames [begin, end) in `dir`
// (".frame-00012.png.tmpXXXXXX", core/io/atomic_file.h); returns how many.
int remove_stale_frame_temporaries(const std::string& dir, int begin, int end, FrameFormat format);

}  // namespace sylva

// Helpers of the end-to-end CLI tests (tests/cli).
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace sylva::test {

// `sylva <args>` exits 2 with a single "sylva: error:" line that mentions `needle`.
void expect_input_error(const std::string& args, const std::string& needle);

// A scene written once by `sylva sample ARGS` and shared by every test program of the build
// (build/test-scenes/, keyed by ARGS and the sylva binary).
const std::string& sampled_scene(const std::string& tag, const std::string& args);

// The names in a folder, sorted.
std::vector<std::string> listing(const std::string& dir);

// ffmpeg's per-frame checksums of a video's decoded frames (a decoder nobody here wrote), one
// line per frame; a test failure when ffmpeg fails.
std::string decoded_frames(const std::string& video);

// A small sample tree (2000 leaves, seed 3), generated once per test program.
const std::string& small_tree();

// Channels of an image read by OpenImageIO (tests/tools/read_channels.py, a reader nobody here
// wrote): a comma-separated list of names, merged in that order; float and half channels as
// CV_32F, uint ones as CV_32S (the same bits); scratch files go to `dir`. An empty Mat (and a
// test failure) when the reader fails.
cv::Mat oiio_channels(const std::string& image, const std::string& names, const std::string& dir);

// A CSV as rows of column name -> field (quoted fields may hold commas and "" quotes); a test
// failure for a row with another number of fields than the header.
std::vector<std::map<std::string, std::string>> parse_csv(const std::string& text);

// A row's field as a number; a test failure (and 0) when the column is missing or empty.
double number(const std::map<std::string, std::string>& row, const std::string& column);

}  // namespace sylva::test

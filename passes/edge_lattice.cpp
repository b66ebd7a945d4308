#include "passes/edge_lattice.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace sylva {

static_assert(std::endian::native == std::endian::little, "MarkLattice packs byte pairs");

MarkLattice::MarkLattice(const EdgeMarks& marks)
    : m_width(std::max(0, 2 * marks.at.cols - 1)), m_height(std::max(0, 2 * marks.at.rows - 1)) {
  const int w = marks.at.cols, h = marks.at.rows;
  if (w == 0 || h == 0) {
    m_cells = cv::Mat::zeros(m_height + 2 * kPad, m_width + 2 * kPad + kTail, CV_8UC1);
    return;
  }
  // Every cell is written once: the lattice rows by the loop below, the border here and there
  // (no zero-fill of the whole grid first, which would double the memory traffic).
  m_cells.create(m_height + 2 * kPad, m_width + 2 * kPad + kTail, CV_8UC1);
  const size_t right = size_t(m_cells.cols - kPad - m_width);
  for (int j = 0; j < kPad; ++j) {
    std::memset(m_cells.ptr<uint8_t>(j), 0, size_t(m_cells.cols));
    std::memset(m_cells.ptr<uint8_t>(m_cells.rows - 1 - j), 0, size_t(m_cells.cols));
  }
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      // Fine row 2y: pixel centres at even i, between_x at odd i, as pairs of bytes (one
      // 16-bit store per pixel, which vectorises).
      uint8_t* even = m_cells.ptr<uint8_t>(2 * y + kPad) + kPad;
      const uint8_t* at = marks.at.ptr<uint8_t>(y);
      const uint8_t* bx = w > 1 ? marks.between_x.ptr<uint8_t>(y) : nullptr;
      std::memset(even - kPad, 0, kPad);
      for (int x = 0; x + 1 < w; ++x) {
        const uint16_t pair = uint16_t((at[x] != 0) | ((bx[x] != 0) << 8));
        std::memcpy(even + 2 * x, &pair, 2);
      }
      even[2 * (w - 1)] = at[w - 1] != 0;
      std::memset(even + m_width, 0, right);
      // Fine row 2y + 1: between_y at even i; odd i lies between four pixels, never a mark.
      if (y + 1 < h) {
        uint8_t* odd = m_cells.ptr<uint8_t>(2 * y + 1 + kPad) + kPad;
        const uint8_t* by = marks.between_y.ptr<uint8_t>(y);
        std::memset(odd - kPad, 0, kPad);
        for (int x = 0; x + 1 < w; ++x) {
          const uint16_t pair = uint16_t(by[x] != 0);  // second byte: i = 2x + 1, no mark
          std::memcpy(odd + 2 * x, &pair, 2);
        }
        odd[2 * (w - 1)] = by[w - 1] != 0;
        std::memset(odd + m_width, 0, right);
      }
    }
  });
  if (!marks.shift_x.empty()) {
    m_shift_x = marks.shift_x.ptr<float>(0);
    m_step_x = marks.shift_x.step1();
  }
  if (!marks.shift_y.empty()) {
    m_shift_y = marks.shift_y.ptr<float>(0);
    m_step_y = marks.shift_y.step1();
  }
}

}  // namespace sylva

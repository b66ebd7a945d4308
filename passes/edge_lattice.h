// The half-pixel lattice of the edges pass (passes/edges.h) as one byte grid: the marks of
// EdgeMarks (pixel centres, between horizontal and between vertical neighbours) interleaved
// at fine coordinates (i, j) = twice the pixel coordinates, pixel (x, y) at (2x, 2y). Marking
// clean-ups and line widening look at windows of neighbouring marks; on the interleaved grid
// such a lookup is one load instead of a branch on the parities of i and j, and a border of
// kPad empty cells keeps windows near the image border in bounds.
//
// Reads an EdgeMarks (its three mark images and the silhouette's sub-pixel shifts); writes
// nothing (a value that refers into them: the shifts are not copied, so the marks must
// outlive it).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "passes/edges.h"
#include "passes/pass_common.h"

namespace sylva {

class MarkLattice {
 public:
  // Empty cells around the lattice, in fine units: the widest window a caller reads (the
  // clean-up's 2.5 px around the outline).
  static constexpr int kPad = 5;
  // Further empty cells at the end of every row, so that bits() can load 16 cells from any i
  // up to width() - 1 + kPad.
  static constexpr int kTail = 15;

  explicit MarkLattice(const EdgeMarks& marks);

  int width() const { return m_width; }    // 2 W - 1
  int height() const { return m_height; }  // 2 H - 1

  // Fine row j, indexable from -kPad to width() - 1 + kPad + kTail (1 = a mark, 0 = none);
  // j from -kPad to height() - 1 + kPad.
  const uint8_t* row(int j) const { return m_cells.ptr<uint8_t>(j + kPad) + kPad; }
  bool operator()(int i, int j) const { return row(j)[i] != 0; }

  // Bit k (0..15): whether cell (i + k, j) holds a mark, for i in [-kPad, width() - 1 + kPad]
  // (callers mask the bits of their window). One 16-byte load, so a window costs no branch per
  // cell, and its marks come out in order of i (lowest bit first).
  unsigned bits(int i, int j) const {
    const uint8_t* cells = row(j) + i;
#if defined(__SSE2__)
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(cells));
    return ~unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128()))) & 0xFFFFu;
#else
    unsigned b = 0;
    for (int k = 0; k < 16; ++k)
      b |= unsigned(cells[k] != 0) << k;
    return b;
#endif
  }

  // Where the mark at (i, j) lies, with its sub-pixel shift (EdgeMarks::shift_x/_y), in fine
  // units relative to (i, j): (0, 0) on pixel centres and for marks without a shift.
  cv::Point2d shift(int i, int j) const {
    if (i % 2 == 1 && m_shift_x) return {2.0 * m_shift_x[(j / 2) * m_step_x + (i - 1) / 2], 0.0};
    if (j % 2 == 1 && m_shift_y) return {0.0, 2.0 * m_shift_y[((j - 1) / 2) * m_step_y + i / 2]};
    return {0.0, 0.0};
  }

 private:
  int m_width = 0, m_height = 0;
  cv::Mat m_cells;
  const float* m_shift_x = nullptr;
  const float* m_shift_y = nullptr;
  size_t m_step_x = 0, m_step_y = 0;  // in floats
};

}  // namespace sylva

#include "core/gl/ao_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace sylva {

namespace {

constexpr int kMaxGridCells = 64;  // per side
static_assert(kAoCrownReach == 8.0f, "the raster shader's crowns_visibility uses 8 radii");

// std430 layout of the shader's AoShell.
struct ShellRecord {
  glm::vec4 centre;  // w: volume scale
  glm::vec4 anchor;
  glm::vec4 inverse[3];
  glm::vec4 transpose[3];
};

// GL_MAX_SHADER_STORAGE_BLOCK_SIZE is at least 2^27 bytes (llvmpipe's); a GPU may allow more.
template <class T>
void fill(GLuint buffer, const std::vector<T>& data, const char* what) {
  // An empty buffer still gets a few bytes: a bound block must have storage.
  const size_t bytes = std::max<size_t>(16, data.size() * sizeof(T));
  GLint limit = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
  if (limit > 0 && bytes > size_t(limit))
    throw std::runtime_error("AO of many plants: the " + std::string(what) + " take " +
                             std::to_string(bytes >> 20) + " MiB, over this GL's " +
                             std::to_string(limit >> 20) + " MiB shader storage block limit");
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_STREAM_DRAW);
  if (!data.empty())
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
}

void shells_of(const AoShading& ao, std::vector<ShellRecord>& shells,
               std::vector<glm::uvec4>& plants) {
  for (const AoShading::PlantShells& p : ao.plant_shells) {
    uint32_t alpha_bits = 0;
    std::memcpy(&alpha_bits, &p.alpha_rho, 4);
    plants.emplace_back(uint32_t(shells.size()), uint32_t(p.centres.size()), alpha_bits, 0u);
    for (size_t i = 0; i < p.centres.size(); ++i) {
      ShellRecord r{};
      r.centre = glm::vec4(p.centres[i], p.volume_scale[i]);
      r.anchor = glm::vec4(p.anchors[i], 0.0f);
      for (int c = 0; c < 3; ++c) {
        r.inverse[c] = glm::vec4(p.inverse[i][c], 0.0f);
        r.transpose[c] = glm::vec4(p.transpose[i][c], 0.0f);
      }
      shells.push_back(r);
    }
  }
}

}  // namespace

void AoBuffers::upload(const AoShading& ao) {
  if (!m_buffers[0]) glGenBuffers(GLsizei(m_buffers.size()), m_buffers.data());
  std::vector<ShellRecord> shells;
  std::vector<glm::uvec4> plants;
  shells_of(ao, shells, plants);
  // The grid over the crowns' reach.
  std::vector<glm::vec4> crowns;
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (const glm::vec4& c : ao.crowns) {
    if (!(c.w > 0.0f) || !std::isfinite(c.w)) continue;
    crowns.push_back(c);
    const float reach = kAoCrownReach * c.w;
    lo = glm::min(lo, glm::vec2(c.x, c.z) - reach);
    hi = glm::max(hi, glm::vec2(c.x, c.z) + reach);
  }
  std::vector<uint32_t> grid;
  m_grid = glm::vec4(0.0f);
  m_cells = glm::ivec2(0);
  if (!crowns.empty()) {
    const float cell = std::max(std::max(hi.x - lo.x, hi.y - lo.y) / kMaxGridCells, 1e-6f);
    m_cells = glm::min(glm::ivec2(glm::ceil((hi - lo) / cell)), glm::ivec2(kMaxGridCells));
    m_cells = glm::max(m_cells, glm::ivec2(1));
    m_grid = glm::vec4(lo.x, lo.y, cell, 0.0f);
    std::vector<std::vector<uint32_t>> lists(size_t(m_cells.x * m_cells.y));
    for (size_t i = 0; i < crowns.size(); ++i) {
      const float reach = kAoCrownReach * crowns[i].w;
      const glm::vec2 c(crowns[i].x, crowns[i].z);
      const glm::ivec2 a =
          glm::clamp(glm::ivec2(glm::floor((c - reach - lo) / cell)), glm::ivec2(0), m_cells - 1);
      const glm::ivec2 b =
          glm::clamp(glm::ivec2(glm::floor((c + reach - lo) / cell)), glm::ivec2(0), m_cells - 1);
      for (int z = a.y; z <= b.y; ++z)
        for (int x = a.x; x <= b.x; ++x)
          lists[size_t(z * m_cells.x + x)].push_back(uint32_t(i));
    }
    grid.resize(2 * lists.size());
    for (size_t k = 0; k < lists.size(); ++k) {
      grid[2 * k] = uint32_t(grid.size());
      grid[2 * k + 1] = uint32_t(lists[k].size());
      grid.insert(grid.end(), lists[k].begin(), lists[k].end());
    }
  }
  fill(m_buffers[0], shells, "shells");
  fill(m_buffers[1], plants, "plants' shell ranges");
  fill(m_buffers[2], crowns, "crowns");
  fill(m_buffers[3], grid, "crown grid's lists");
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

void AoBuffers::bind(const RasterProgram& p) const {
  for (size_t i = 0; i < m_buffers.size(); ++i)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(i), m_buffers[i]);
  glUniform4fv(p.ao_grid, 1, &m_grid[0]);
  glUniform2i(p.ao_grid_cells, m_cells.x, m_cells.y);
}

void AoBuffers::release() {
  if (m_buffers[0]) glDeleteBuffers(GLsizei(m_buffers.size()), m_buffers.data());
  m_buffers = {};
}

}  // namespace sylva

#include "core/gl/gpu_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/gl/shaders.h"

namespace sylva {

namespace {

// libOSMesa exports GL 4.5 but not its direct-state-access entry points, so objects are
// edited through bindings.
template <typename T>
GLuint make_buffer(GLenum target, const std::vector<T>& data) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(target, buffer);
  glBufferStorage(target, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(), 0);
  return buffer;
}

// The mip chain of an sRGB RGBA texture, as glGenerateMipmap makes it for GL_SRGB8_ALPHA8
// (colour averaged in linear light, alpha as is, each level a box filter of the one above,
// floor(size / 2) per side). Made here because llvmpipe compiles a blit shader the first time
// glGenerateMipmap runs, a tenth of a second of every command that draws a textured scene.
// Returns levels 1 to levels - 1, 8-bit RGBA.
std::vector<cv::Mat> srgb_mip_chain(const Texture& tex, int levels) {
  static const std::array<float, 256> decode = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i)
      t[size_t(i)] = srgb_to_linear(float(i) / 255.0f);
    return t;
  }();
  constexpr int kEncodeSteps = 65535;  // exact to the 8-bit level even in the darks
  static const std::vector<uint8_t> encode = [] {
    std::vector<uint8_t> t(kEncodeSteps + 1);
    for (int i = 0; i <= kEncodeSteps; ++i)
      t[size_t(i)] = uint8_t(std::lround(linear_to_srgb(float(i) / kEncodeSteps) * 255.0f));
    return t;
  }();
  const cv::Mat rgba(tex.height, tex.width, CV_8UC4, const_cast<uint8_t*>(tex.rgba.data()));
  cv::Mat linear(rgba.size(), CV_32FC4);
  for (int y = 0; y < rgba.rows; ++y) {
    const cv::Vec4b* in = rgba.ptr<cv::Vec4b>(y);
    cv::Vec4f* out = linear.ptr<cv::Vec4f>(y);
    for (int x = 0; x < rgba.cols; ++x)
      out[x] = {decode[in[x][0]], decode[in[x][1]], decode[in[x][2]], in[x][3] / 255.0f};
  }
  std::vector<cv::Mat> chain;
  for (int level = 1; level < levels; ++level) {
    const cv::Size size(std::max(1, linear.cols / 2), std::max(1, linear.rows / 2));
    cv::Mat smaller;
    cv::resize(linear, smaller, size, 0, 0, cv::INTER_AREA);
    cv::Mat bytes(size, CV_8UC4);
    for (int y = 0; y < size.height; ++y) {
      const cv::Vec4f* in = smaller.ptr<cv::Vec4f>(y);
      cv::Vec4b* out = bytes.ptr<cv::Vec4b>(y);
      for (int x = 0; x < size.width; ++x) {
        for (int c = 0; c < 3; ++c)
          out[x][c] = encode[size_t(std::clamp(in[x][c], 0.0f, 1.0f) * kEncodeSteps + 0.5f)];
        out[x][3] = uint8_t(std::clamp(in[x][3], 0.0f, 1.0f) * 255.0f + 0.5f);
      }
    }
    chain.push_back(bytes);
    linear = smaller;
  }
  return chain;
}

void check_array(size_t size, size_t expected, const Mesh& mesh, const char* what) {
  if (size != 0 && size != expected) {
    throw InputError("mesh '" + mesh.name + "'", std::string(what) + " has " +
                                                     std::to_string(size) + " entries, expected " +
                                                     std::to_string(expected));
  }
}

}  // namespace

// A vertex belongs to one connected component, so the ids of any triangle using it are
// the vertex's ids; the last triangle wins.
GpuMesh upload_mesh(const Mesh& mesh, uint32_t object_id) {
  const size_t nv = mesh.positions.size();
  const size_t nt = mesh.triangle_count();
  check_array(mesh.uvs.size(), nv, mesh, "uvs");
  check_array(mesh.colors.size(), nv, mesh, "colors");
  check_array(mesh.primitive_ids.size(), nt, mesh, "primitive_ids");
  check_array(mesh.cluster_ids.size(), nt, mesh, "cluster_ids");
  check_array(mesh.roles.size(), nt, mesh, "roles");

  std::vector<uint32_t> ids(nv * 2, 0);
  std::vector<uint8_t> roles(nv, static_cast<uint8_t>(Role::Other));
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t prim = mesh.primitive_ids.empty() ? 0 : mesh.primitive_ids[t];
    const uint32_t cluster = mesh.cluster_ids.empty() ? 0 : mesh.cluster_ids[t];
    const auto role = static_cast<uint8_t>(mesh.roles.empty() ? Role::Other : mesh.roles[t]);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + k];
      if (v >= nv) throw InputError("mesh '" + mesh.name + "'", "vertex index out of range");
      ids[2 * v] = prim;
      ids[2 * v + 1] = cluster;
      roles[v] = role;
    }
  }

  GpuMesh g;
  g.material = mesh.material;
  g.object_id = object_id;
  g.index_count = static_cast<GLsizei>(nt * 3);
  g.vertex_count = nv;
  glGenVertexArrays(1, &g.vao);
  glBindVertexArray(g.vao);
  auto attach = [&](GLuint buffer, GLuint location, GLint size, GLenum type, bool integer) {
    g.buffers.push_back(buffer);
    if (integer) {
      glVertexAttribIPointer(location, size, type, 0, nullptr);
    } else {
      glVertexAttribPointer(location, size, type, GL_FALSE, 0, nullptr);
    }
    glEnableVertexAttribArray(location);
  };
  attach(make_buffer(GL_ARRAY_BUFFER, mesh.positions), kAttribPosition, 3, GL_FLOAT, false);
  if (!mesh.uvs.empty()) {
    attach(make_buffer(GL_ARRAY_BUFFER, mesh.uvs), kAttribUv, 2, GL_FLOAT, false);
  }
  if (!mesh.colors.empty()) {
    attach(make_buffer(GL_ARRAY_BUFFER, mesh.colors), kAttribColor, 4, GL_FLOAT, false);
  }
  attach(make_buffer(GL_ARRAY_BUFFER, ids), kAttribIds, 2, GL_UNSIGNED_INT, true);
  attach(make_buffer(GL_ARRAY_BUFFER, roles), kAttribRole, 1, GL_UNSIGNED_BYTE, true);
  // The element-array binding is VAO state: bound while the VAO is.
  g.buffers.push_back(make_buffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  g.oriented_foliage = mesh.outward_normals;
  try {
    replace_shading(g, mesh.normals, mesh.ka, mesh.name);
  } catch (...) {
    release_mesh(g);
    throw;
  }
  return g;
}

void replace_shading(GpuMesh& g, const std::vector<glm::vec3>& normals,
                     const std::vector<float>& ka, const std::string& name) {
  if (!normals.empty() && normals.size() != g.vertex_count)
    throw InputError("mesh '" + name + "'", "normals has " + std::to_string(normals.size()) +
                                                " entries, expected " +
                                                std::to_string(g.vertex_count));
  if (!ka.empty() && ka.size() != g.vertex_count)
    throw InputError("mesh '" + name + "'", "ka has " + std::to_string(ka.size()) +
                                                " entries, expected " +
                                                std::to_string(g.vertex_count));
  glBindVertexArray(g.vao);
  auto set = [&](GLuint& buffer, GLuint location, GLint size, const auto& data) {
    if (buffer) glDeleteBuffers(1, &buffer);
    buffer = 0;
    if (data.empty()) {
      glDisableVertexAttribArray(location);  // reads the constant set before each draw
      return;
    }
    buffer = make_buffer(GL_ARRAY_BUFFER, data);
    glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(location);
  };
  set(g.normal_buffer, kAttribNormal, 3, normals);
  set(g.ka_buffer, kAttribKa, 1, ka);
  g.has_normals = !normals.empty();
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

GLuint upload_texture(const Texture& tex) {
  if (tex.width < 1 || tex.height < 1 ||
      tex.rgba.size() != static_cast<size_t>(tex.width) * tex.height * 4) {
    throw InputError("texture '" + tex.name + "'", "pixel data does not match its size");
  }
  int levels = 1;
  while ((std::max(tex.width, tex.height) >> levels) > 0)
    ++levels;
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glTexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, tex.width, tex.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Rows go in top first: GL's t = 0 is then the image top, which is glTF's v = 0.
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, tex.width, tex.height, GL_RGBA, GL_UNSIGNED_BYTE,
                  tex.rgba.data());
  const std::vector<cv::Mat> chain = srgb_mip_chain(tex, levels);
  for (size_t i = 0; i < chain.size(); ++i)
    glTexSubImage2D(GL_TEXTURE_2D, GLint(i + 1), 0, 0, chain[i].cols, chain[i].rows, GL_RGBA,
                    GL_UNSIGNED_BYTE, chain[i].data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glBindTexture(GL_TEXTURE_2D, 0);
  return id;
}

void release_mesh(GpuMesh& mesh) {
  glDeleteVertexArrays(1, &mesh.vao);
  glDeleteBuffers(static_cast<GLsizei>(mesh.buffers.size()), mesh.buffers.data());
  for (GLuint* b : {&mesh.normal_buffer, &mesh.ka_buffer})
    if (*b) glDeleteBuffers(1, b), *b = 0;
  mesh.vao = 0;
  mesh.buffers.clear();
}

glm::vec3 texture_mean(const Texture& t) {
  glm::dvec3 sum(0.0), all(0.0);
  size_t n = 0;
  const size_t count = size_t(t.width) * size_t(t.height);
  for (size_t i = 0; i < count && 4 * i + 3 < t.rgba.size(); ++i) {
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) {
      const double v = t.rgba[4 * i + k] / 255.0;
      c[k] = srgb_to_linear(float(v));
    }
    all += c;
    if (t.rgba[4 * i + 3] >= 128) sum += c, ++n;
  }
  if (n > 0) return glm::vec3(sum / double(n));
  return count > 0 ? glm::vec3(all / double(count)) : glm::vec3(1.0f);
}

GLuint make_target_texture(GLenum internal_format, int width, int height) {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  return id;
}

// Meshes without a material: grey, and double-sided because untextured plant meshes
// (OBJ/PLY leaves) rarely have consistent winding.
Material default_material() {
  Material m;
  m.name = "default";
  m.base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  m.double_sided = true;
  return m;
}

}  // namespace sylva

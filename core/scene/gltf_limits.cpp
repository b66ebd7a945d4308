#include "core/scene/gltf_limits.h"

#include "core/error.h"

namespace sylva {

namespace {

using Json = nlohmann::json;

void check_count(const std::string& path, const std::string& what, size_t n, size_t max) {
  if (n > max)
    throw InputError(path, "too many " + what + ": " + std::to_string(n) + " (at most " +
                               std::to_string(max) + ")");
}

// Counts as the SAX parser goes: a frame per open object or array, with the key it sits under.
class LimitCounter : public nlohmann::json_sax<Json> {
 public:
  explicit LimitCounter(std::string path) : m_path(std::move(path)) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    m_key = k;
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    throw InputError(m_path, "invalid JSON: " + std::string(e.what()));
  }

 private:
  struct Frame {
    bool array;
    std::string key;  // the key this value sits under in its parent object
    size_t count = 0;
  };
  bool value() {
    if (!m_stack.empty() && m_stack.back().array) ++m_stack.back().count;
    return true;
  }
  bool open(bool array) {
    value();
    if (m_stack.size() >= GltfLimits::kMaxDepth)
      throw InputError(m_path, "invalid glTF: JSON nested deeper than " +
                                   std::to_string(GltfLimits::kMaxDepth) + " levels");
    m_stack.push_back({array, m_stack.empty() || m_stack.back().array ? "" : m_key});
    return true;
  }
  bool close() {
    const Frame f = m_stack.back();
    m_stack.pop_back();
    if (f.array && m_stack.size() == 1) check_top_level(f.key, f.count);
    if (f.array && m_stack.size() == 3 && f.key == "primitives" && m_stack[1].key == "meshes")
      check_count(m_path, "primitives", m_primitives += f.count, GltfLimits::kMaxPrimitives);
    return true;
  }
  void check_top_level(const std::string& key, size_t n) const {
    if (key == "nodes") check_count(m_path, key, n, GltfLimits::kMaxNodes);
    if (key == "meshes") check_count(m_path, key, n, GltfLimits::kMaxMeshes);
    if (key == "accessors" || key == "bufferViews")
      check_count(m_path, key, n, GltfLimits::kMaxAccessors);
    for (const char* k : {"materials", "textures", "images", "samplers", "buffers", "cameras",
                          "scenes", "skins", "animations"})
      if (key == k) check_count(m_path, key, n, GltfLimits::kMaxItems);
  }

  std::string m_path, m_key;
  std::vector<Frame> m_stack;
  size_t m_primitives = 0;
};

void check_accessor_counts(const std::string& path, const Json& gltf) {
  const auto accessors = gltf.find("accessors");
  if (accessors == gltf.end() || !accessors->is_array()) return;
  for (size_t i = 0; i < accessors->size(); ++i) {
    const Json& a = (*accessors)[i];
    if (!a.is_object()) continue;
    const auto count = a.find("count");
    if (count == a.end() || !count->is_number()) continue;
    const double n = count->get<double>();
    if (!(n >= 0 && n <= double(GltfLimits::kMaxAccessorElements)))
      throw InputError(path, "accessor " + std::to_string(i) + ": count " + count->dump() +
                                 " is out of range [0, " +
                                 std::to_string(GltfLimits::kMaxAccessorElements) + "]");
  }
}

}  // namespace

void check_gltf_json(const std::string& path, const std::string& text) {
  LimitCounter counter(path);
  Json::sax_parse(text, &counter);
}

void check_gltf_limits(const std::string& path, const Json& gltf) {
  check_accessor_counts(path, gltf);
}

}  // namespace sylva

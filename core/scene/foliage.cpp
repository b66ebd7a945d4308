#include "core/scene/foliage.h"

#include <array>
#include <cctype>
#include <set>
#include <string_view>

#include "core/error.h"

namespace sylva {
namespace {

std::string lower(std::string s) {
  for (char& c : s)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool contains_any(const std::string& name, std::initializer_list<std::string_view> words) {
  const std::string l = lower(name);
  for (std::string_view w : words)
    if (l.find(w) != std::string::npos) return true;
  return false;
}

const std::string& material_name(const Scene& scene, const Mesh& mesh) {
  static const std::string none;
  return mesh.material >= 0 && mesh.material < int(scene.materials.size())
             ? scene.materials[size_t(mesh.material)].name
             : none;
}

bool named(const Scene& scene, const Mesh& mesh, std::initializer_list<std::string_view> words) {
  return contains_any(mesh.name, words) || contains_any(material_name(scene, mesh), words);
}

Role non_foliage_role(const Scene& scene, const Mesh& mesh) {
  if (named(scene, mesh, {"grass", "lawn"})) return Role::Grass;
  if (named(scene, mesh, {"bark", "trunk", "branch", "wood", "stem"})) return Role::Wood;
  if (named(scene, mesh, {"ground", "terrain", "soil"})) return Role::Ground;
  return Role::Other;
}

// One line, at most a handful of names: `sylva info` prints it as is.
std::string name_list(const std::set<std::string>& names) {
  std::string out;
  size_t shown = 0;
  for (const std::string& n : names) {
    if (shown == 8) {
      out += ", and " + std::to_string(names.size() - shown) + " more";
      break;
    }
    if (shown) out += ", ";
    out += n.empty() ? std::string("(unnamed)") : n;
    ++shown;
  }
  return out;
}

std::string reason(const std::set<std::string>& materials, const std::set<std::string>& meshes) {
  std::string out;
  if (!materials.empty()) out += "materials: " + name_list(materials);
  if (!meshes.empty()) {
    if (!out.empty()) out += "; ";
    out += "meshes: " + name_list(meshes);
  }
  return out.empty() ? "no foliage" : out;
}

}  // namespace

bool glob_match(const std::string& pattern, const std::string& text) {
  // Iterative matcher with single-star backtracking: linear in practice, never recursive.
  const std::string p = lower(pattern), t = lower(text);
  size_t pi = 0, ti = 0, star = std::string::npos, mark = 0;
  while (ti < t.size()) {
    if (pi < p.size() && (p[pi] == '?' || p[pi] == t[ti])) {
      ++pi;
      ++ti;
    } else if (pi < p.size() && p[pi] == '*') {
      star = pi++;
      mark = ti;
    } else if (star != std::string::npos) {
      pi = star + 1;
      ti = ++mark;
    } else {
      return false;
    }
  }
  while (pi < p.size() && p[pi] == '*')
    ++pi;
  return pi == p.size();
}

void classify_roles(Scene& scene, const std::string& foliage_option) {
  const std::string option = lower(foliage_option);
  const size_t n = scene.meshes.size();
  std::vector<char> foliage(n, 0);
  std::vector<char> from_file(n, 0);
  std::set<std::string> hit_materials, hit_meshes;
  auto mark = [&](size_t m, bool by_material) {
    foliage[m] = 1;
    const Mesh& mesh = scene.meshes[m];
    if (by_material)
      hit_materials.insert(material_name(scene, mesh));
    else
      hit_meshes.insert(mesh.name);
  };
  std::string rule;

  if (option == "none") {
    rule = "--foliage none";
  } else if (option == "all") {
    rule = "--foliage all";
    for (size_t m = 0; m < n; ++m)
      mark(m, false);
  } else if (option != "auto") {
    rule = "--foliage '" + foliage_option + "'";
    for (size_t m = 0; m < n; ++m) {
      const Mesh& mesh = scene.meshes[m];
      if (glob_match(foliage_option, material_name(scene, mesh)))
        mark(m, true);
      else if (glob_match(foliage_option, mesh.name))
        mark(m, false);
    }
    if (hit_materials.empty() && hit_meshes.empty()) {
      std::set<std::string> names;
      for (const Material& mat : scene.materials)
        names.insert(mat.name);
      for (const Mesh& mesh : scene.meshes)
        names.insert(mesh.name);
      throw InputError("--foliage",
                       "pattern '" + foliage_option +
                           "' matches no material or mesh; names are: " + name_list(names));
    }
  } else {
    // Roles written by `sylva` itself (glTF extras) are the most reliable source.
    size_t file_meshes = 0;
    for (size_t m = 0; m < n; ++m) {
      const Mesh& mesh = scene.meshes[m];
      from_file[m] = !mesh.roles.empty() && mesh.roles.size() == mesh.triangle_count();
      file_meshes += from_file[m];
    }
    for (size_t m = 0; m < n; ++m) {
      const Mesh& mesh = scene.meshes[m];
      if (from_file[m]) continue;
      if (contains_any(material_name(scene, mesh), {"leaf", "leaves", "foliage", "needle"}))
        mark(m, true);
      else if (contains_any(mesh.name, {"leaf", "leaves", "foliage", "needle"}))
        mark(m, false);
    }
    rule = "name match";
    if (hit_materials.empty() && hit_meshes.empty()) {
      rule = "alpha MASK";
      for (size_t m = 0; m < n; ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (from_file[m] || mesh.material < 0 || mesh.material >= int(scene.materials.size()))
          continue;
        if (scene.materials[size_t(mesh.material)].alpha_mode == AlphaMode::Mask) mark(m, true);
      }
      if (hit_materials.empty()) rule = "no foliage found";
    }
    if (file_meshes == n)
      rule = "sylva_role extras";
    else if (file_meshes > 0)
      rule += " + sylva_role extras (" + std::to_string(file_meshes) + " meshes)";
  }

  size_t foliage_triangles = 0;
  for (size_t m = 0; m < n; ++m) {
    Mesh& mesh = scene.meshes[m];
    if (!from_file[m]) {
      const Role role = foliage[m] ? Role::Foliage : non_foliage_role(scene, mesh);
      mesh.roles.assign(mesh.triangle_count(), role);
    }
    for (Role r : mesh.roles)
      foliage_triangles += r == Role::Foliage;
  }
  scene.report.foliage_rule = rule;
  std::string why = reason(hit_materials, hit_meshes);
  if (rule == "sylva_role extras" || rule == "--foliage none" ||
      hit_materials.size() + hit_meshes.size() == 0)
    why = std::to_string(foliage_triangles) + " foliage triangles";
  else
    why += " (" + std::to_string(foliage_triangles) + " foliage triangles)";
  if (rule == "alpha MASK") why = "alpha-MASK " + why;
  scene.report.foliage_reason = why;
}

}  // namespace sylva

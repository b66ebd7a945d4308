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

namespace {

// Meshes marked as foliage, the meshes whose roles come from the file, and the names that
// matched (for the report).
struct FoliageMarks {
  std::vector<char> foliage;
  std::vector<char> from_file;
  std::set<std::string> hit_materials, hit_meshes;

  explicit FoliageMarks(size_t meshes) : foliage(meshes, 0), from_file(meshes, 0) {}
  void mark(const Scene& scene, size_t m, bool by_material) {
    foliage[m] = 1;
    const Mesh& mesh = scene.meshes[m];
    if (by_material)
      hit_materials.insert(material_name(scene, mesh));
    else
      hit_meshes.insert(mesh.name);
  }
  bool none() const { return hit_materials.empty() && hit_meshes.empty(); }
};

// --foliage all: every mesh, by its name.
std::string mark_all(const Scene& scene, FoliageMarks& marks) {
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    marks.mark(scene, m, false);
  return "--foliage all";
}

// --foliage PATTERN: meshes whose material name, else mesh name, matches the glob; throws
// listing the names when none does.
std::string mark_by_pattern(const Scene& scene, const std::string& pattern, FoliageMarks& marks) {
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (glob_match(pattern, material_name(scene, mesh)))
      marks.mark(scene, m, true);
    else if (glob_match(pattern, mesh.name))
      marks.mark(scene, m, false);
  }
  if (marks.none()) {
    std::set<std::string> names;
    for (const Material& mat : scene.materials)
      names.insert(mat.name);
    for (const Mesh& mesh : scene.meshes)
      names.insert(mesh.name);
    throw InputError(
        "--foliage",
        "pattern '" + pattern + "' matches no material or mesh; names are: " + name_list(names));
  }
  return "--foliage '" + pattern + "'";
}

// Flags the meshes that carry a role per triangle (glTF extras written by `sylva` itself, the
// most reliable source); returns how many do.
size_t find_file_roles(const Scene& scene, FoliageMarks& marks) {
  size_t file_meshes = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    marks.from_file[m] = !mesh.roles.empty() && mesh.roles.size() == mesh.triangle_count();
    file_meshes += marks.from_file[m];
  }
  return file_meshes;
}

// Meshes without file roles whose material, else mesh name, contains a leaf word.
void mark_by_leaf_names(const Scene& scene, FoliageMarks& marks) {
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (marks.from_file[m]) continue;
    if (contains_any(material_name(scene, mesh), {"leaf", "leaves", "foliage", "needle"}))
      marks.mark(scene, m, true);
    else if (contains_any(mesh.name, {"leaf", "leaves", "foliage", "needle"}))
      marks.mark(scene, m, false);
  }
}

// Meshes without file roles whose material is alpha-MASKed (cut-out leaf cards).
void mark_by_alpha_mask(const Scene& scene, FoliageMarks& marks) {
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (marks.from_file[m] || mesh.material < 0 || mesh.material >= int(scene.materials.size()))
      continue;
    if (scene.materials[size_t(mesh.material)].alpha_mode == AlphaMode::Mask)
      marks.mark(scene, m, true);
  }
}

// --foliage auto: roles from the file, then leaf names, else alpha-MASK materials; returns the
// rule that decided.
std::string mark_auto(const Scene& scene, FoliageMarks& marks) {
  const size_t n = scene.meshes.size();
  const size_t file_meshes = find_file_roles(scene, marks);
  mark_by_leaf_names(scene, marks);
  std::string rule = "name match";
  if (marks.none()) {
    rule = "alpha MASK";
    mark_by_alpha_mask(scene, marks);
    if (marks.hit_materials.empty()) rule = "no foliage found";
  }
  if (file_meshes == n)
    rule = "sylva_role extras";
  else if (file_meshes > 0)
    rule += " + sylva_role extras (" + std::to_string(file_meshes) + " meshes)";
  return rule;
}

// Gives every mesh without file roles one role (foliage if marked, else from its names);
// returns the scene's foliage triangle count.
size_t assign_roles(Scene& scene, const FoliageMarks& marks) {
  size_t foliage_triangles = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    Mesh& mesh = scene.meshes[m];
    if (!marks.from_file[m]) {
      const Role role = marks.foliage[m] ? Role::Foliage : non_foliage_role(scene, mesh);
      mesh.roles.assign(mesh.triangle_count(), role);
    }
    for (Role r : mesh.roles)
      foliage_triangles += r == Role::Foliage;
  }
  return foliage_triangles;
}

// The report's one line on why these triangles are foliage.
std::string foliage_reason(const std::string& rule, const FoliageMarks& marks,
                           size_t foliage_triangles) {
  std::string why = reason(marks.hit_materials, marks.hit_meshes);
  if (rule == "sylva_role extras" || rule == "--foliage none" ||
      marks.hit_materials.size() + marks.hit_meshes.size() == 0)
    why = std::to_string(foliage_triangles) + " foliage triangles";
  else
    why += " (" + std::to_string(foliage_triangles) + " foliage triangles)";
  if (rule == "alpha MASK") why = "alpha-MASK " + why;
  return why;
}

}  // namespace

void classify_roles(Scene& scene, const std::string& foliage_option) {
  const std::string option = lower(foliage_option);
  FoliageMarks marks(scene.meshes.size());
  std::string rule;
  if (option == "none")
    rule = "--foliage none";
  else if (option == "all")
    rule = mark_all(scene, marks);
  else if (option != "auto")
    rule = mark_by_pattern(scene, foliage_option, marks);
  else
    rule = mark_auto(scene, marks);
  const size_t foliage_triangles = assign_roles(scene, marks);
  scene.report.foliage_rule = rule;
  scene.report.foliage_reason = foliage_reason(rule, marks, foliage_triangles);
}

}  // namespace sylva

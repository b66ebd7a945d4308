// sylva.styles and sylva.style (python/binding.h): what `sylva styles [NAME]` prints, as dicts.
#include "python/binding.h"
#include "styles/presets.h"

namespace sylva::python {

namespace {

const char* type_name(ParamType t) {
  switch (t) {
    case ParamType::Float:
      return "float";
    case ParamType::Int:
      return "int";
    case ParamType::Bool:
      return "bool";
    case ParamType::Color:
      return "color";
    case ParamType::Choice:
      return "choice";
    case ParamType::Text:
      return "text";
  }
  return "text";
}

py::dict param_dict(const Style& s, const ParamSpec& p) {
  py::dict d;
  d["value"] = s.set().value_text(p.key);
  d["default"] = p.default_text;
  d["allowed"] = allowed_text(p);
  d["meaning"] = p.doc;
  d["unit"] = p.unit;
  d["type"] = type_name(p.type);
  if (p.type == ParamType::Float || p.type == ParamType::Int)
    d["range"] = py::make_tuple(p.min, p.max);
  if (p.type == ParamType::Choice) d["choices"] = p.choices;
  return d;
}

py::dict styles() {
  py::dict out;
  for (const std::string& n : builtin_preset_names()) {
    const Style s(n);
    py::dict d;
    d["builder"] = s.info().builder;
    d["description"] = s.info().description;
    out[py::str(n)] = d;
  }
  return out;
}

py::dict style(const py::object& name) {
  const Style s(py::module_::import("os").attr("fspath")(name).cast<std::string>());
  py::dict d;
  d["name"] = s.info().name;
  d["source"] = s.info().source;
  d["description"] = s.info().description;
  d["builder"] = s.info().builder;
  d["chain"] = s.info().chain;
  d["lines"] = s.has_strokes();
  py::dict params;
  for (const ParamSpec& p : s.set().specs())
    params[py::str(p.key)] = param_dict(s, p);
  d["params"] = params;
  return d;
}

}  // namespace

void bind_styles(py::module_& m) {
  m.def("styles", &styles,
        "The built-in style presets: {name: {'builder': ..., 'description': ...}}, as `sylva "
        "styles` lists them");
  m.def("style", &style,
        "One preset (a built-in name or a .toml file) as `sylva styles NAME` prints it: name, "
        "source, description, builder, chain, lines (has SVG output) and params: {key: {value, "
        "default, allowed, meaning, unit, type, range or choices}}",
        py::arg("name"));
}

}  // namespace sylva::python

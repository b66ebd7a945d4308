// The render graph (DESIGN.md §3): passes declare the resources they read and write, the
// caller presents the outputs it wants, compile() culls every pass and resource nobody
// needs, execute() runs the rest in order and frees each resource after its last reader.
// A pass asks PassContext::wanted() which of its outputs are live, so a multi-output pass
// (the raster pass) produces only those. Passes must be added in dependency order (a pass
// reads only what earlier passes write); resources hold any copyable value (std::any).
// A scope (GraphScope) prefixes the names a builder gives, so one graph can hold several
// copies of the same passes, e.g. one style chain per cell of a contact sheet.
#pragma once

#include <any>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"

namespace sylva {

class RenderGraph;

class PassContext {
 public:
  bool wanted(int resource) const;
  template <class T>
  const T& read(int resource) const {
    const std::any& v = value(resource);
    const T* p = std::any_cast<T>(&v);
    SYLVA_CHECK(p != nullptr, "render graph: resource has another type");
    return *p;
  }
  void write(int resource, std::any value);

 private:
  friend class RenderGraph;
  PassContext(RenderGraph& graph, int pass) : m_graph(graph), m_pass(pass) {}
  const std::any& value(int resource) const;
  RenderGraph& m_graph;
  int m_pass;
};

class RenderGraph {
 public:
  using Run = std::function<void(PassContext&)>;

  // Declares a resource, or returns the existing one with this name (scope prefix included).
  int resource(const std::string& name);
  // The pass is named scope() + name.
  int add_pass(const std::string& name, std::vector<int> reads, std::vector<int> writes, Run run);
  void present(int resource);

  void compile();
  // after_pass (optional) is called with each live pass's full name once it has run, e.g.
  // to report progress over live_passes().
  void execute(const std::function<void(const std::string&)>& after_pass = {});

  bool compiled() const { return m_compiled; }
  // "" or "a/" or "a/b/": what resource() and add_pass() put in front of names. The lookups
  // below (find_resource, has_pass, pass_live, resource_name) use full names.
  const std::string& scope() const { return m_scope; }
  bool is_live(int resource) const;
  bool pass_live(const std::string& name) const;
  bool has_pass(const std::string& name) const;
  int find_resource(const std::string& name) const;  // -1 if absent
  const std::string& resource_name(int resource) const;
  std::vector<std::string> live_passes() const;

  template <class T>
  const T& get(int resource) const {
    const T* p = std::any_cast<T>(&m_resources.at(resource).value);
    SYLVA_CHECK(p != nullptr, "render graph: '" + resource_name(resource) + "' not produced");
    return *p;
  }

  // Graphviz: passes as boxes, resources as ellipses, culled ones grey and dashed.
  std::string to_dot() const;

  // Called by execute() with every live resource's full name and value right after the pass
  // writing it ran (before inputs are released), e.g. for tests that check each pass's output.
  using Observer = std::function<void(const std::string& resource, const std::any& value)>;
  void set_observer(Observer observer) { m_observer = std::move(observer); }

 private:
  friend class PassContext;
  struct Resource {
    std::string name;
    int writer = -1;
    std::vector<int> readers;
    bool presented = false;
    bool live = false;
    int pending_reads = 0;
    std::any value;
  };
  struct Pass {
    std::string name;
    std::vector<int> reads, writes;
    Run run;
    bool live = false;
  };
  std::vector<Resource> m_resources;
  std::vector<Pass> m_passes;
  bool m_compiled = false;
  std::string m_scope;
  Observer m_observer;
  friend class GraphScope;
};

// While alive, names in `graph` get "name/" appended to the enclosing scope. name must be
// non-empty and free of '/'.
class GraphScope {
 public:
  GraphScope(RenderGraph& graph, const std::string& name);
  ~GraphScope();
  GraphScope(const GraphScope&) = delete;
  GraphScope& operator=(const GraphScope&) = delete;

 private:
  RenderGraph& m_graph;
  std::string m_previous;
};

}  // namespace sylva

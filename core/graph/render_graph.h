// The render graph (DESIGN.md §3): passes declare the resources they read and write, the
// caller presents the outputs it wants, compile() culls every pass and resource nobody
// needs, execute() runs the rest in order and frees each resource after its last reader.
// A pass asks PassContext::wanted() which of its outputs are live, so a multi-output pass
// (the raster pass) produces only those. Passes must be added in dependency order (a pass
// reads only what earlier passes write). A resource is declared with the type of its value
// (resource<T>() gives a Handle<T>), and add_pass checks that every handle it is given names a
// resource of that type, so a pass that reads or writes the wrong type fails where the graph is
// built, not when it runs; PassContext::read and write take the value's type from the handle.
// A scope (GraphScope) prefixes the names a builder gives, so one graph can hold several
// copies of the same passes, e.g. one style chain per cell of a contact sheet.
#pragma once

#include <any>
#include <functional>
#include <string>
#include <type_traits>
#include <typeindex>
#include <typeinfo>
#include <vector>

#include "core/error.h"

namespace cv {
class Mat;
}

namespace sylva {

class RenderGraph;

// A resource of a render graph holding a T; a default handle (id -1) names none.
template <class T>
struct Handle {
  int id = -1;
  bool valid() const { return id >= 0; }
  bool operator==(const Handle&) const = default;
};

// An image (cv::Mat) in a render graph: a G-buffer target or an image pass's output.
using ImageHandle = Handle<cv::Mat>;

// Any handle with its type, as a pass's reads and writes are listed.
struct ResourceRef {
  int id;
  std::type_index type;
  template <class T>
  ResourceRef(Handle<T> h) : id(h.id), type(typeid(T)) {}  // NOLINT: implicit on purpose
};

class PassContext {
 public:
  bool wanted(ResourceRef resource) const;
  template <class T>
  const T& read(Handle<T> resource) const {
    const T* p = std::any_cast<T>(&value(resource.id));
    SYLVA_CHECK(p != nullptr, "render graph: a handle of another type");  // add_pass checks it
    return *p;
  }
  template <class T>
  void write(Handle<T> resource, std::type_identity_t<T> value) {
    store(resource.id, std::any(std::move(value)));
  }

 private:
  friend class RenderGraph;
  PassContext(RenderGraph& graph, int pass) : m_graph(graph), m_pass(pass) {}
  const std::any& value(int resource) const;
  void store(int resource, std::any value);
  RenderGraph& m_graph;
  int m_pass;
};

class RenderGraph {
 public:
  using Run = std::function<void(PassContext&)>;

  // Declares a resource holding a T, or returns the existing one with this name (scope prefix
  // included); the same name declared with another type is a programming error.
  template <class T>
  Handle<T> resource(const std::string& name) {
    return Handle<T>{declare(name, typeid(T))};
  }
  // Where a pass may run. Main: on the calling thread (a pass that draws with the GL context,
  // or changes anything but its outputs). Any: on a worker thread, beside other passes whose
  // results it does not need; such a pass reads only its inputs and what nothing changes while
  // the graph runs (the scene), and locks what it shares (a memo): an image pass, say. So a
  // frame's independent passes share the cores.
  enum class Threads { Main, Any };
  // The pass is named scope() + name. Every handle must be valid and of its resource's type.
  int add_pass(const std::string& name, std::vector<ResourceRef> reads,
               std::vector<ResourceRef> writes, Run run, Threads threads = Threads::Main);
  void present(ResourceRef resource);

  void compile();
  // after_pass (optional) is called with each live pass's full name once it has run, e.g.
  // to report progress over live_passes(). A pass runs once every pass writing what it reads
  // has run: the Threads::Main passes one at a time on the calling thread, up to two
  // Threads::Any passes beside them, in an order that can differ from the order they were
  // added in. The values are those of running the passes one by one in order. A pass's
  // exception is thrown here once the passes running beside it have ended. after_pass and the
  // observer are called one at a time, on the thread that ran the pass (a worker's, for a
  // Threads::Any pass, which then goes on with the next ready one).
  void execute(const std::function<void(const std::string&)>& after_pass = {});

  bool compiled() const { return m_compiled; }
  // "" or "a/" or "a/b/": what resource() and add_pass() put in front of names. The lookups
  // below (find_resource, has_pass, pass_live, resource_name) use full names.
  const std::string& scope() const { return m_scope; }
  bool is_live(ResourceRef resource) const;
  bool pass_live(const std::string& name) const;
  bool has_pass(const std::string& name) const;
  // The resource with this full name if it holds a T, else an invalid handle.
  template <class T>
  Handle<T> find_resource(const std::string& name) const {
    const int id = find_id(name);
    return Handle<T>{id >= 0 && m_resources[id].type == typeid(T) ? id : -1};
  }
  const std::string& resource_name(ResourceRef resource) const;
  std::vector<std::string> live_passes() const;

  template <class T>
  const T& get(Handle<T> resource) const {
    const T* p = std::any_cast<T>(&m_resources.at(checked(resource)).value);
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
  int declare(const std::string& local_name, std::type_index type);
  int find_id(const std::string& name) const;  // -1 if absent
  int checked(ResourceRef resource) const;     // its id, once it names a resource of its type
  std::vector<int> ids(const std::vector<ResourceRef>& refs) const;
  struct Resource {
    std::string name;
    std::type_index type = typeid(void);
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
    Threads threads = Threads::Main;
    bool live = false;
  };
  struct Schedule;
  class Runner;
  Schedule schedule() const;
  void run_pass(int pass);
  // What execute() does once `pass` has run: checks its outputs, shows them to the observer,
  // frees the inputs it read last, and tells after_pass.
  void finish_pass(int pass, const std::function<void(const std::string&)>& after_pass);
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

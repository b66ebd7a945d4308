#include "core/graph/render_graph.h"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <future>
#include <mutex>
#include <set>
#include <sstream>

#include "core/interrupt.h"

namespace sylva {

bool PassContext::wanted(ResourceRef resource) const {
  return m_graph.is_live(resource);
}

const std::any& PassContext::value(int resource) const {
  const auto& reads = m_graph.m_passes[m_pass].reads;
  SYLVA_CHECK(std::find(reads.begin(), reads.end(), resource) != reads.end(),
              "pass '" + m_graph.m_passes[m_pass].name + "' reads undeclared '" +
                  m_graph.m_resources.at(resource).name + "'");
  const std::any& v = m_graph.m_resources[resource].value;
  SYLVA_CHECK(v.has_value(), "render graph: '" + m_graph.m_resources[resource].name + "' is empty");
  return v;
}

void PassContext::store(int resource, std::any value) {
  SYLVA_CHECK(m_graph.m_resources.at(resource).writer == m_pass,
              "pass '" + m_graph.m_passes[m_pass].name + "' writes undeclared '" +
                  m_graph.m_resources[resource].name + "'");
  if (m_graph.m_resources[resource].live) m_graph.m_resources[resource].value = std::move(value);
}

GraphScope::GraphScope(RenderGraph& graph, const std::string& name)
    : m_graph(graph), m_previous(graph.m_scope) {
  SYLVA_CHECK(!name.empty() && name.find('/') == std::string::npos,
              "render graph: bad scope name '" + name + "'");
  m_graph.m_scope += name + "/";
}

GraphScope::~GraphScope() {
  m_graph.m_scope = m_previous;
}

int RenderGraph::declare(const std::string& local_name, std::type_index type) {
  const std::string name = m_scope + local_name;
  const int found = find_id(name);
  if (found >= 0) {
    SYLVA_CHECK(m_resources[found].type == type, "render graph: '" + name + "' declared as " +
                                                     m_resources[found].type.name() + ", now as " +
                                                     type.name());
    return found;
  }
  Resource r;
  r.name = name;
  r.type = type;
  m_resources.push_back(std::move(r));
  m_compiled = false;
  return static_cast<int>(m_resources.size()) - 1;
}

int RenderGraph::find_id(const std::string& name) const {
  for (size_t i = 0; i < m_resources.size(); ++i)
    if (m_resources[i].name == name) return static_cast<int>(i);
  return -1;
}

int RenderGraph::checked(ResourceRef resource) const {
  SYLVA_CHECK(resource.id >= 0 && size_t(resource.id) < m_resources.size(),
              "render graph: a handle that names no resource");
  const Resource& r = m_resources[resource.id];
  SYLVA_CHECK(r.type == resource.type, "render graph: '" + r.name + "' holds " + r.type.name() +
                                           ", not " + resource.type.name());
  return resource.id;
}

const std::string& RenderGraph::resource_name(ResourceRef resource) const {
  return m_resources[checked(resource)].name;
}

// The handles' ids, each checked against its resource's type.
std::vector<int> RenderGraph::ids(const std::vector<ResourceRef>& refs) const {
  std::vector<int> out;
  out.reserve(refs.size());
  for (const ResourceRef& r : refs)
    out.push_back(checked(r));
  return out;
}

int RenderGraph::add_pass(const std::string& local_name, std::vector<ResourceRef> read_refs,
                          std::vector<ResourceRef> write_refs, Run run, Threads threads) {
  const std::string name = m_scope + local_name;
  SYLVA_CHECK(!has_pass(name), "render graph: duplicate pass '" + name + "'");
  std::vector<int> reads = ids(read_refs), writes = ids(write_refs);
  int id = static_cast<int>(m_passes.size());
  for (int r : reads) {
    SYLVA_CHECK(m_resources.at(r).writer >= 0, "pass '" + name + "' reads '" + m_resources[r].name +
                                                   "' before anything writes it");
    m_resources[r].readers.push_back(id);
  }
  for (int w : writes) {
    SYLVA_CHECK(m_resources.at(w).writer < 0,
                "resource '" + m_resources[w].name + "' written by two passes");
    m_resources[w].writer = id;
  }
  m_passes.push_back(Pass{name, std::move(reads), std::move(writes), std::move(run), threads});
  m_compiled = false;
  return id;
}

void RenderGraph::present(ResourceRef ref) {
  const int resource = checked(ref);
  SYLVA_CHECK(m_resources[resource].writer >= 0,
              "presented resource '" + m_resources[resource].name + "' has no writer");
  m_resources[resource].presented = true;
  m_compiled = false;
}

void RenderGraph::compile() {
  for (Resource& r : m_resources) {
    r.live = r.presented;
    r.pending_reads = 0;
  }
  // Passes come in dependency order, so one sweep from the back reaches every producer.
  for (int p = static_cast<int>(m_passes.size()) - 1; p >= 0; --p) {
    Pass& pass = m_passes[p];
    pass.live = std::any_of(pass.writes.begin(), pass.writes.end(),
                            [&](int w) { return m_resources[w].live; });
    if (!pass.live) continue;
    for (int r : pass.reads)
      m_resources[r].live = true;
  }
  for (const Pass& pass : m_passes)
    if (pass.live)
      for (int r : pass.reads)
        ++m_resources[r].pending_reads;
  m_compiled = true;
}

void RenderGraph::run_pass(int pass) {
  PassContext ctx(*this, pass);
  m_passes[size_t(pass)].run(ctx);
}

void RenderGraph::finish_pass(int p, const std::function<void(const std::string&)>& after_pass) {
  const Pass& pass = m_passes[size_t(p)];
  for (int w : pass.writes) {
    SYLVA_CHECK(!m_resources[w].live || m_resources[w].value.has_value(),
                "pass '" + pass.name + "' did not write '" + m_resources[w].name + "'");
    if (m_observer && m_resources[w].live) m_observer(m_resources[w].name, m_resources[w].value);
  }
  // Release inputs after their last reader, unless they are outputs.
  for (int r : pass.reads) {
    Resource& res = m_resources[r];
    if (--res.pending_reads == 0 && !res.presented) res.value.reset();
  }
  if (after_pass) after_pass(pass.name);
}

namespace {

// Threads::Any passes running at once: a frame's image passes are each parallel inside, so two
// fill the cores where one alone leaves them idle between its parallel loops.
constexpr size_t kMostInFlight = 2;

struct InFlight {
  int pass;
  std::future<void> done;
};

// The passes in flight that have ended, in the order they did.
class Landings {
 public:
  void land(int pass) {
    {
      const std::lock_guard<std::mutex> lock(m_mutex);
      m_ended.push_back(pass);
    }
    m_ended_one.notify_one();
  }
  int wait() {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_ended_one.wait(lock, [this] { return !m_ended.empty(); });
    const int pass = m_ended.front();
    m_ended.pop_front();
    return pass;
  }

 private:
  std::mutex m_mutex;
  std::condition_variable m_ended_one;
  std::deque<int> m_ended;
};

// Tells `landings` that `pass` ended, however it ends.
struct Landed {
  Landings& landings;
  int pass;
  ~Landed() { landings.land(pass); }
};

}  // namespace

// Which live passes can run: how many unfinished passes write what each one reads, and the
// passes that read each one's outputs.
struct RenderGraph::Schedule {
  std::vector<int> waiting;
  std::vector<std::vector<int>> feeds;
  std::set<int> ready;
  size_t left = 0;  // live passes not finished
  void finished(int pass) {
    for (int q : feeds[size_t(pass)])
      if (--waiting[size_t(q)] == 0) ready.insert(q);
    --left;
  }
};

RenderGraph::Schedule RenderGraph::schedule() const {
  Schedule s;
  s.waiting.assign(m_passes.size(), 0);
  s.feeds.resize(m_passes.size());
  for (size_t p = 0; p < m_passes.size(); ++p) {
    if (!m_passes[p].live) continue;
    ++s.left;
    std::set<int> writers;
    for (int r : m_passes[p].reads)
      writers.insert(m_resources[r].writer);
    for (int w : writers)
      s.feeds[size_t(w)].push_back(int(p));
    s.waiting[p] = int(writers.size());
    if (writers.empty()) s.ready.insert(int(p));
  }
  return s;
}

void RenderGraph::execute(const std::function<void(const std::string&)>& after_pass) {
  if (!m_compiled) compile();
  Schedule s = schedule();
  auto finished = [&](int p) {
    finish_pass(p, after_pass);
    s.finished(p);
  };
  Landings landings;  // outlives `flying`, whose futures wait for their passes when destroyed
  std::vector<InFlight> flying;
  while (s.left > 0) {
    check_interrupt();  // a long render stops between passes after SIGINT (core/interrupt.h)
    // The first ready pass that can start: one for any thread while fewer than kMostInFlight
    // are in flight, else one for the calling thread at once (beside the passes in flight, which
    // only read what it cannot change). Passes in flight go first, so the work that does not
    // wait for a calling-thread pass (the raster) runs while it does.
    auto next = std::find_if(s.ready.begin(), s.ready.end(), [&](int p) {
      return m_passes[size_t(p)].threads == Threads::Any && flying.size() < kMostInFlight;
    });
    if (next == s.ready.end())
      next = std::find_if(s.ready.begin(), s.ready.end(),
                          [&](int p) { return m_passes[size_t(p)].threads == Threads::Main; });
    if (next != s.ready.end()) {
      const int pass = *next;
      s.ready.erase(next);
      if (m_passes[size_t(pass)].threads == Threads::Any) {
        flying.push_back({pass, std::async(std::launch::async, [this, pass, &landings] {
                            const Landed landed{landings, pass};
                            run_pass(pass);
                          })});
      } else {
        run_pass(pass);
        finished(pass);
      }
      continue;
    }
    SYLVA_CHECK(!flying.empty(), "render graph: no pass can run");
    // The first pass in flight to end (its exception, if any, thrown here).
    const int ended = landings.wait();
    const auto it = std::find_if(flying.begin(), flying.end(),
                                 [ended](const InFlight& f) { return f.pass == ended; });
    InFlight landed = std::move(*it);
    flying.erase(it);
    landed.done.get();
    finished(ended);
  }
}

bool RenderGraph::is_live(ResourceRef resource) const {
  SYLVA_CHECK(m_compiled, "render graph: compile() before asking what is live");
  return m_resources[checked(resource)].live;
}

bool RenderGraph::has_pass(const std::string& name) const {
  return std::any_of(m_passes.begin(), m_passes.end(),
                     [&](const Pass& p) { return p.name == name; });
}

bool RenderGraph::pass_live(const std::string& name) const {
  SYLVA_CHECK(m_compiled, "render graph: compile() before asking what is live");
  for (const Pass& p : m_passes)
    if (p.name == name) return p.live;
  return false;
}

std::vector<std::string> RenderGraph::live_passes() const {
  std::vector<std::string> out;
  for (const Pass& p : m_passes)
    if (p.live) out.push_back(p.name);
  return out;
}

std::string RenderGraph::to_dot() const {
  std::ostringstream s;
  auto style = [](bool live) { return live ? "" : ", style=dashed, color=grey, fontcolor=grey"; };
  s << "digraph sylva {\n  rankdir=LR;\n";
  for (size_t p = 0; p < m_passes.size(); ++p)
    s << "  p" << p << " [shape=box, label=\"" << m_passes[p].name << "\""
      << style(m_passes[p].live) << "];\n";
  for (size_t r = 0; r < m_resources.size(); ++r) {
    const Resource& res = m_resources[r];
    s << "  r" << r << " [shape=ellipse, label=\"" << res.name << "\""
      << (res.presented ? ", peripheries=2" : "") << style(res.live) << "];\n";
  }
  for (size_t p = 0; p < m_passes.size(); ++p) {
    for (int r : m_passes[p].reads)
      s << "  r" << r << " -> p" << p << ";\n";
    for (int w : m_passes[p].writes)
      s << "  p" << p << " -> r" << w << ";\n";
  }
  s << "}\n";
  return s.str();
}

}  // namespace sylva

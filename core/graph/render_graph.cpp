#include "core/graph/render_graph.h"

#include <algorithm>
#include <condition_variable>
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

// One execute(): the schedule and what is in flight, shared by the calling thread and the
// workers under one lock. A worker that ends a pass finishes it and goes on with the next ready
// pass for any thread itself, so a pass waiting for it starts at once, on the core that is
// already running, rather than when the calling thread next wakes (a busy core can keep it
// waiting for milliseconds), and passes for any thread go on while the calling thread runs one
// of its own (the raster).
class RenderGraph::Runner {
 public:
  Runner(RenderGraph& graph, const std::function<void(const std::string&)>& after_pass)
      : m_graph(graph), m_after_pass(after_pass), m_schedule(graph.schedule()) {}

  void run() {
    std::unique_lock<std::mutex> lock(m_mutex);
    bool stuck = false;  // passes left, none running and none ready
    while (m_schedule.left > 0 && !m_error) {
      launch_ready();
      const int pass = take(Threads::Main);
      if (pass >= 0) {
        lock.unlock();
        std::exception_ptr error = attempt(pass);
        lock.lock();
        end(pass, error);
        continue;
      }
      if (m_flying == 0) {
        stuck = true;
        break;
      }
      m_changed.wait(lock);
    }
    m_changed.wait(lock, [this] { return m_flying == 0; });
    lock.unlock();
    m_workers.clear();  // their threads have ended their work
    if (m_error) std::rethrow_exception(m_error);
    SYLVA_CHECK(!stuck, "render graph: no pass can run");
  }

 private:
  // The first ready pass for `threads`, taken from the ready set; -1 when there is none.
  int take(Threads threads) {
    const auto it = std::find_if(m_schedule.ready.begin(), m_schedule.ready.end(), [&](int p) {
      return m_graph.m_passes[size_t(p)].threads == threads;
    });
    if (it == m_schedule.ready.end()) return -1;
    const int pass = *it;
    m_schedule.ready.erase(it);
    return pass;
  }
  // Starts workers on ready passes for any thread while fewer than kMostInFlight are in flight.
  void launch_ready() {
    while (m_flying < kMostInFlight && !m_error) {
      const int pass = take(Threads::Any);
      if (pass < 0) return;
      ++m_flying;
      try {
        m_workers.push_back(std::async(std::launch::async, [this, pass] { work(pass); }));
      } catch (...) {  // no thread for it
        --m_flying;
        m_error = std::current_exception();
      }
    }
  }
  // Runs `pass`; its exception, or an interrupt before it (core/interrupt.h), as the result.
  std::exception_ptr attempt(int pass) {
    try {
      check_interrupt();  // a long render stops between passes after SIGINT
      m_graph.run_pass(pass);
      return nullptr;
    } catch (...) {
      return std::current_exception();
    }
  }
  // Under the lock, once `pass` has run: finished, or the graph's first error kept.
  void end(int pass, std::exception_ptr error) {
    if (!error) {
      try {
        m_graph.finish_pass(pass, m_after_pass);
        m_schedule.finished(pass);
      } catch (...) {
        error = std::current_exception();
      }
    }
    if (error && !m_error) m_error = error;
    m_changed.notify_all();
  }
  // A worker: `pass`, then the next ready pass for any thread, until none is or one failed.
  void work(int pass) {
    while (pass >= 0) {
      const std::exception_ptr error = attempt(pass);
      const std::lock_guard<std::mutex> lock(m_mutex);
      end(pass, error);
      pass = m_error ? -1 : take(Threads::Any);
      if (pass < 0) --m_flying;
      launch_ready();
    }
  }

  RenderGraph& m_graph;
  const std::function<void(const std::string&)>& m_after_pass;
  Schedule m_schedule;
  std::mutex m_mutex;
  std::condition_variable m_changed;  // a pass ended
  size_t m_flying = 0;                // workers with a pass
  std::exception_ptr m_error;         // the first pass's exception
  std::vector<std::future<void>> m_workers;
};

void RenderGraph::execute(const std::function<void(const std::string&)>& after_pass) {
  if (!m_compiled) compile();
  Runner(*this, after_pass).run();
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

#include "core/graph/render_graph.h"

#include <algorithm>
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
                          std::vector<ResourceRef> write_refs, Run run) {
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
  m_passes.push_back(Pass{name, std::move(reads), std::move(writes), std::move(run)});
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

void RenderGraph::execute(const std::function<void(const std::string&)>& after_pass) {
  if (!m_compiled) compile();
  for (size_t p = 0; p < m_passes.size(); ++p) {
    Pass& pass = m_passes[p];
    if (!pass.live) continue;
    check_interrupt();  // a long render stops between passes after SIGINT (core/interrupt.h)
    PassContext ctx(*this, static_cast<int>(p));
    pass.run(ctx);
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

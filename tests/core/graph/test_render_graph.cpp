// The render graph culls passes and resources nobody presents, runs the rest in order,
// tells multi-output passes which outputs are wanted, frees inputs after their last use, and
// shows an observer what each pass wrote; a SIGINT stops it between passes.
#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include "core/graph/render_graph.h"
#include "core/interrupt.h"

namespace sylva {
namespace {

// raster -> {color, normal, id}; edges reads normal+id; toon reads color.
struct Fixture {
  RenderGraph g;
  Handle<int> color, normal, id, edges_out, toon_out;
  std::string log;
  std::string raster_made;
  Fixture() {
    color = g.resource<int>("color");
    normal = g.resource<int>("normal");
    id = g.resource<int>("id");
    edges_out = g.resource<int>("edges");
    toon_out = g.resource<int>("toon");
    g.add_pass("raster", {}, {color, normal, id}, [this](PassContext& c) {
      log += "raster;";
      for (Handle<int> r : {color, normal, id})
        if (c.wanted(r)) {
          raster_made += g.resource_name(r) + ",";
          c.write(r, 1);
        }
    });
    g.add_pass("edges", {normal, id}, {edges_out}, [this](PassContext& c) {
      log += "edges;";
      c.write(edges_out, c.read<int>(normal) + c.read<int>(id));
    });
    g.add_pass("toon", {color}, {toon_out}, [this](PassContext& c) {
      log += "toon;";
      c.write(toon_out, c.read<int>(color) * 10);
    });
  }
};

TEST(RenderGraph, CullsWhatNobodyPresents) {
  Fixture f;
  f.g.present(f.toon_out);
  f.g.compile();
  EXPECT_TRUE(f.g.pass_live("raster"));
  EXPECT_TRUE(f.g.pass_live("toon"));
  EXPECT_FALSE(f.g.pass_live("edges"));
  EXPECT_FALSE(f.g.is_live(f.id));
  EXPECT_FALSE(f.g.is_live(f.normal));
  f.g.execute();
  EXPECT_EQ(f.log, "raster;toon;");
  EXPECT_EQ(f.raster_made, "color,");  // the ID and normal targets are never produced
  EXPECT_EQ(f.g.get<int>(f.toon_out), 10);
}

TEST(RenderGraph, MultipleOutputsKeepEverythingTheyNeed) {
  Fixture f;
  f.g.present(f.toon_out);
  f.g.present(f.edges_out);
  f.g.execute();
  EXPECT_EQ(f.log, "raster;edges;toon;");
  EXPECT_EQ(f.raster_made, "color,normal,id,");
  EXPECT_EQ(f.g.get<int>(f.edges_out), 2);
}

TEST(RenderGraph, NothingPresentedRunsNothing) {
  Fixture f;
  f.g.execute();
  EXPECT_EQ(f.log, "");
  EXPECT_TRUE(f.g.live_passes().empty());
}

TEST(RenderGraph, IntermediatesAreReleasedAfterLastReader) {
  Fixture f;
  f.g.present(f.edges_out);
  f.g.execute();
  EXPECT_DEATH_IF_SUPPORTED((void)f.g.get<int>(f.normal), "not produced");
}

// The observer sees every live resource as it is written, intermediates included (which the
// graph then releases), and nothing of culled passes.
TEST(RenderGraph, ObserverSeesEveryLiveResourceAsItIsWritten) {
  Fixture f;
  std::string seen;
  f.g.set_observer([&](const std::string& name, const std::any& value) {
    seen += name + "=" + std::to_string(std::any_cast<int>(value)) + ";";
  });
  f.g.present(f.edges_out);
  f.g.execute();
  EXPECT_EQ(seen, "normal=1;id=1;edges=2;");
}

TEST(RenderGraph, DotExportMarksCulledNodes) {
  Fixture f;
  f.g.present(f.toon_out);
  f.g.compile();
  std::string dot = f.g.to_dot();
  EXPECT_NE(dot.find("digraph"), std::string::npos);
  EXPECT_NE(dot.find("label=\"edges\", style=dashed"), std::string::npos);
  EXPECT_NE(dot.find("label=\"toon\"]"), std::string::npos);
  EXPECT_NE(dot.find("peripheries=2"), std::string::npos);
}

// Two copies of the same builder in one graph (a contact sheet): scopes keep their names
// apart, both read the shared input, and only the presented copy runs.
TEST(RenderGraph, ScopesSeparateCopiesOfABuilder) {
  RenderGraph g;
  const auto in = g.resource<int>("in");
  g.add_pass("source", {}, {in}, [in](PassContext& c) { c.write(in, 2); });
  auto builder = [&](int factor) {
    const auto out = g.resource<int>("out");
    g.add_pass("scale", {in}, {out},
               [in, out, factor](PassContext& c) { c.write(out, c.read<int>(in) * factor); });
    return out;
  };
  Handle<int> a, b;
  {
    GraphScope scope(g, "a");
    a = builder(3);
    EXPECT_EQ(g.scope(), "a/");
    {
      GraphScope inner(g, "x");
      EXPECT_EQ(g.scope(), "a/x/");
    }
  }
  {
    GraphScope scope(g, "b");
    b = builder(5);
  }
  EXPECT_EQ(g.scope(), "");
  EXPECT_NE(a, b);
  EXPECT_EQ(g.resource_name(a), "a/out");
  EXPECT_EQ(g.find_resource<int>("b/out"), b);
  EXPECT_FALSE(g.find_resource<float>("b/out").valid());  // another type finds nothing
  EXPECT_EQ(g.resource<int>("in"), in);  // outside a scope the name is the plain one
  g.present(b);
  g.compile();
  EXPECT_FALSE(g.pass_live("a/scale"));
  EXPECT_TRUE(g.pass_live("b/scale"));
  std::string ran;
  g.execute([&](const std::string& pass) { ran += pass + ";"; });
  EXPECT_EQ(ran, "source;b/scale;");
  EXPECT_EQ(g.live_passes().size(), 2u);
  EXPECT_EQ(g.get<int>(b), 10);
}

TEST(RenderGraph, ReadingBeforeWritingIsAProgrammingError) {
  RenderGraph g;
  const auto a = g.resource<int>("a");
  EXPECT_DEATH_IF_SUPPORTED(g.add_pass("p", {a}, {}, [](PassContext&) {}), "before anything");
}

// A resource has one type: declaring its name again with another type, or handing add_pass a
// handle whose type is not the resource's, stops where the graph is built, before any pass
// runs; a default handle names nothing.
TEST(RenderGraph, HandlesOfTheWrongTypeAreRefusedWhereThePassIsAdded) {
  RenderGraph g;
  const auto a = g.resource<int>("a");
  g.add_pass("source", {}, {a}, [a](PassContext& c) { c.write(a, 7); });
  EXPECT_DEATH_IF_SUPPORTED((void)g.resource<float>("a"), "declared as");
  const Handle<float> forged{a.id};
  const auto out = g.resource<float>("out");
  EXPECT_DEATH_IF_SUPPORTED(g.add_pass("p", {forged}, {out}, [](PassContext&) {}), "holds");
  EXPECT_DEATH_IF_SUPPORTED(g.add_pass("q", {Handle<int>{}}, {out}, [](PassContext&) {}),
                            "names no resource");
  EXPECT_DEATH_IF_SUPPORTED(g.present(forged), "holds");
  g.add_pass("half", {a}, {out},
             [a, out](PassContext& c) { c.write(out, static_cast<float>(c.read(a)) / 2.0f); });
  g.present(out);
  g.execute();
  EXPECT_FLOAT_EQ(g.get(out), 3.5f);
}

// A SIGINT during a pass (under ScopedInterruptHandler, as the Python module renders) stops the
// graph before its next pass; the flag, once cleared, lets the next render run.
TEST(RenderGraph, AnInterruptStopsBetweenPasses) {
  Fixture f;
  f.g.present(f.toon_out);
  f.g.present(f.edges_out);
  f.g.compile();
  {
    const ScopedInterruptHandler sigint;
    EXPECT_THROW(f.g.execute([](const std::string& pass) {
      if (pass == "raster") std::raise(SIGINT);
    }),
                 Interrupted);
    EXPECT_EQ(f.log, "raster;");
    EXPECT_EQ(interrupt_signal(), SIGINT);
    clear_interrupt();
  }
  EXPECT_EQ(interrupt_signal(), 0);
  EXPECT_NO_THROW(check_interrupt());
}

}  // namespace
}  // namespace sylva

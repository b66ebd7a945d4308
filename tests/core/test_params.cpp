// ParamSet (core/params.h): a choice bound to an enum is parsed when set and prints its name;
// every set remembers where the value came from; check_values checks fields a program filled
// in directly with the setters' own messages; allowed_text states each type's values.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/params.h"

namespace sylva {
namespace {

enum class Shape { Round, Square, Star };

struct Fields {
  Shape shape = Shape::Square;
  float width = 2.0f;
  int count = 3;
  std::string mode = "a";
  std::string size = "auto";
};

void bind(ParamSet& set, Fields& f) {
  set.add_choice("t.shape", f.shape,
                 {{"round", Shape::Round}, {"square", Shape::Square}, {"star", Shape::Star}},
                 "the shape");
  set.add_float("t.width", f.width, 0.5, 8, "px", "the width");
  set.add_int("t.count", f.count, 1, 10, "", "how many");
  set.add_choice("t.mode", f.mode, {"a", "b"}, "a string choice");
  set.add_text(
      "t.size", f.size,
      [](const std::string& text, const std::string& where) {
        if (text != "auto" && text != "big") throw InputError(where, "auto or big");
      },
      "auto or big", "a text");
}

TEST(Params, EnumChoiceParsesWhenSetAndPrintsItsName) {
  Fields f;
  ParamSet set;
  bind(set, f);
  EXPECT_EQ(set.spec("t.shape", "test").default_text, "square");
  EXPECT_EQ(set.spec("t.shape", "test").choices,
            (std::vector<std::string>{"round", "square", "star"}));
  set.set_text("t.shape", "star", "test");
  EXPECT_EQ(f.shape, Shape::Star);
  EXPECT_EQ(set.value_text("t.shape"), "star");
  f.shape = Shape::Round;  // a program sets the field; the set reads it back
  EXPECT_EQ(set.value_text("t.shape"), "round");
  try {
    set.set_from_string("t.shape", "oval", "--set");
    ADD_FAILURE() << "oval accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--set");
    EXPECT_EQ(e.reason(), "t.shape = \"oval\" is not one of round, square, star");
  }
  EXPECT_EQ(f.shape, Shape::Round);  // a refused value leaves the field as it was
}

TEST(Params, SourceIsWhereTheValueWasLastSet) {
  Fields f;
  ParamSet set;
  bind(set, f);
  EXPECT_EQ(set.source("t.width"), "");  // the bound default
  set.set_number("t.width", 4, "style.toml");
  EXPECT_EQ(set.source("t.width"), "style.toml");
  set.set({"t.width", "5", "--width"});
  EXPECT_EQ(set.source("t.width"), "--width");
  EXPECT_FLOAT_EQ(f.width, 5.0f);
  EXPECT_THROW(set.set({"t.width", "9", "--set"}), InputError);
  EXPECT_EQ(set.source("t.width"), "--width");  // a refused value changes nothing
  set.set_text("t.shape", "round", "--set");
  EXPECT_EQ(set.source("t.shape"), "--set");
  EXPECT_EQ(set.source("t.count"), "");
}

TEST(Params, CheckValuesUsesTheSettersMessages) {
  Fields f;
  ParamSet set;
  bind(set, f);
  EXPECT_NO_THROW(set.check_values("fields"));
  // What check_values says of the set's fields once they hold `changed`.
  auto message = [&](const Fields& changed) {
    f = changed;
    try {
      set.check_values("fields");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Fields wide, nan, none, star, mode, huge, big;
  wide.width = 9.0f;
  EXPECT_EQ(message(wide), "fields: t.width = 9 is outside [0.5, 8] px");
  nan.width = std::nanf("");
  EXPECT_EQ(message(nan), "fields: t.width = nan is outside [0.5, 8] px");
  none.count = 0;
  EXPECT_EQ(message(none), "fields: t.count = 0 is outside [1, 10]");
  star.shape = static_cast<Shape>(7);
  EXPECT_EQ(message(star), "fields: t.shape holds a value that is not one of round, square, star");
  mode.mode.assign(1, 'c');
  EXPECT_EQ(message(mode), "fields: t.mode holds a value that is not one of a, b");
  huge.size.assign("huge");
  EXPECT_EQ(message(huge), "fields: t.size: auto or big");
  big.size.assign("big");
  EXPECT_EQ(message(big), "accepted");
}

TEST(Params, AllowedTextStatesEachType) {
  Fields f;
  bool on = false;
  glm::vec3 colour(0.0f);
  ParamSet set;
  bind(set, f);
  set.add_bool("t.on", on, "a flag");
  set.add_color("t.colour", colour, "a colour");
  EXPECT_EQ(allowed_text(set.spec("t.width", "test")), "[0.5, 8] px");
  EXPECT_EQ(allowed_text(set.spec("t.count", "test")), "[1, 10]");
  EXPECT_EQ(allowed_text(set.spec("t.shape", "test")), "round | square | star");
  EXPECT_EQ(allowed_text(set.spec("t.size", "test")), "auto or big");
  EXPECT_EQ(allowed_text(set.spec("t.on", "test")), "true | false");
  EXPECT_EQ(allowed_text(set.spec("t.colour", "test")), "\"#RRGGBB\"");
}

}  // namespace
}  // namespace sylva

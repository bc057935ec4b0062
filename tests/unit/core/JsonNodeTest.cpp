// JsonNode: the path-aware JSON reader behind every Sylva file format (scenes, folding projects, blade
// models, tree species, tile sets, wind settings): one dialect of paths (JSON Pointer) and messages.
#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

namespace sylva {
namespace {

template <typename F> std::string messageOf(F&& body) {
  try {
    body();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(JsonNode, ReadsValuesAndNamesTheJsonPointerInErrors) {
  const nlohmann::json doc =
      nlohmann::json::parse(R"({"a": {"b": [1, 2.5, "x"], "n": -3, "s": "", "t": true, "u/v": 0}})");
  const JsonNode root(doc, "f.json");
  const JsonNode a = root["a"];
  EXPECT_EQ(a.path(), "/a");
  EXPECT_EQ(a["u/v"].path(), "/a/u~1v");
  EXPECT_TRUE(a.has("b"));
  EXPECT_FALSE(a.has("zz"));
  EXPECT_EQ(a["b"].array(1, 3), 3u);
  EXPECT_DOUBLE_EQ(a["b"][1].number(), 2.5);
  EXPECT_EQ(a["n"].integer(-5, 5), -3);
  EXPECT_TRUE(a["t"].boolean());
  EXPECT_EQ(a["s"].string(true), "");

  EXPECT_EQ(messageOf([&] { root.array(0, 1); }), "f.json: /: expected an array, got object");
  EXPECT_EQ(messageOf([&] { a["zz"].number(); }), "f.json: /a/zz: missing field");
  EXPECT_EQ(messageOf([&] { a["b"][2].number(); }), "f.json: /a/b/2: expected a number, got string");
  EXPECT_EQ(messageOf([&] { a["b"][1].integer(0, 9); }), "f.json: /a/b/1: expected a whole number, got 2.5");
  EXPECT_EQ(messageOf([&] { a["n"].integer(0, 9); }), "f.json: /a/n: -3 is less than 0");
  EXPECT_EQ(messageOf([&] { a["b"][1].number(0, 2); }), "f.json: /a/b/1: 2.5 is more than 2");
  EXPECT_EQ(messageOf([&] { a["b"][std::size_t{0}].numberAbove(1, 2); }),
            "f.json: /a/b/0: 1 must be more than 1");
  EXPECT_EQ(messageOf([&] { a["n"].nonNegative(); }), "f.json: /a/n: -3 is less than 0");
  EXPECT_EQ(messageOf([&] { a["n"].unsignedInteger(); }), "f.json: /a/n: -3 is less than 0");
  EXPECT_EQ(messageOf([&] { a["b"].array(4, 9); }), "f.json: /a/b: expected at least 4 entries, got 3");
  EXPECT_EQ(messageOf([&] { a["b"].array(0, 2); }), "f.json: /a/b: 3 entries is more than 2");
  EXPECT_EQ(messageOf([&] { a["b"].arrayOf(2, "two"); }), "f.json: /a/b: expected 2 entries (two), got 3");
  EXPECT_EQ(messageOf([&] { a["s"].string(); }), "f.json: /a/s: must not be empty");
  EXPECT_EQ(messageOf([&] { a["b"][2].string(false, 0); }), "f.json: /a/b/2: 1 characters is more than 0");
  EXPECT_EQ(messageOf([&] { a["n"].boolean(); }), "f.json: /a/n: expected true or false, got number");
  EXPECT_EQ(messageOf([&] { a["b"][2].choice({"y", "z"}); }), "f.json: /a/b/2: 'x' is not one of: y, z");
}

TEST(JsonNode, UnknownFieldsNameTheClosestKnownOne) {
  const nlohmann::json doc = nlohmann::json::parse(R"({"densty": 1})");
  const JsonNode root(doc, "f.json");
  EXPECT_EQ(messageOf([&] {
              root.object({"density", "count"});
            }),
            "f.json: /densty: unknown field (did you mean 'density'?)");
  EXPECT_EQ(messageOf([&] { root.object({"banana"}); }), "f.json: /densty: unknown field");
  EXPECT_EQ(messageOf([&] { root.object({"densty"}); }), "");
  EXPECT_EQ(closestKey("elevaton", {"azimuth", "elevation", "intensity"}), "elevation");
  EXPECT_EQ(closestKey("zzzzzzzz", {"azimuth", "elevation", "intensity"}), "");
  EXPECT_EQ(closestKey("x", {}), "");
}

TEST(JsonNode, MessagesStayOnOneLine) {
  const nlohmann::json doc = nlohmann::json::parse(R"({"a\nb": 1})");
  EXPECT_EQ(messageOf([&] { JsonNode(doc, "f.json").object({}); }), "f.json: /a\\u000ab: unknown field");
}

TEST(JsonNode, StrictParsingRefusesDuplicateKeysAndNamesLineAndColumn) {
  EXPECT_EQ(parseJsonStrict(R"({"a": [1, {"b": 2}]})", "f.json")["a"][1]["b"], 2);
  EXPECT_EQ(messageOf([] { parseJsonStrict(R"({"a": [0, {"b": 1, "b": 2}]})", "f.json"); }),
            "f.json: /a/1/b: duplicate field");
  EXPECT_EQ(
      messageOf([] { parseJsonStrict("{\n  \"a\": ]\n}", "f.json"); }).rfind("f.json:2:8: invalid JSON: ", 0),
      0u);
}

// The class: a number JSON cannot hold (NaN, Infinity from other writers; 1e999 overflows a double) fails to
// parse, and the message names the field it was for, not only a line and column.
TEST(JsonNode, ParseErrorsNameTheFieldTheParserStoppedIn) {
  const auto message = [](const std::string& text) {
    return messageOf([&] { parseJsonStrict(text, "f.json"); });
  };
  EXPECT_THAT(message(R"({"profiles": [{"id": "p", "period_s": 1e999}]})"),
              ::testing::AllOf(::testing::HasSubstr("number overflow"),
                               ::testing::HasSubstr("(in /profiles/0/period_s)")));
  EXPECT_THAT(message(R"({"a": {"b": [1, 2, NaN]}})"),
              ::testing::AllOf(::testing::HasSubstr("JSON has no NaN or Infinity"),
                               ::testing::HasSubstr("(in /a/b/2)")));
  EXPECT_THAT(message(R"({"x": -Infinity})"),
              ::testing::AllOf(::testing::HasSubstr("no NaN or Infinity"), ::testing::HasSubstr("(in /x)")));
  EXPECT_THAT(message(R"([{"a": 1}, {"b": nan}])"), ::testing::HasSubstr("(in /1/b)"));
  // A plain syntax error keeps its line and column, with the field where there is one.
  EXPECT_THAT(message("{\n  \"a\": ]\n}"), ::testing::HasSubstr("(in /a)"));
  EXPECT_THAT(message("{"), ::testing::Not(::testing::HasSubstr("(in ")));
  EXPECT_THAT(message(R"({"a": nul})"), ::testing::Not(::testing::HasSubstr("NaN")));
}

} // namespace
} // namespace sylva

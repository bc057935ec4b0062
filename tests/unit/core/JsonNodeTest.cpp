// JsonNode: the path-aware JSON reader behind every Sylva file format (folding projects, blade models).
#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>

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

TEST(JsonNode, ReadsValuesAndNamesThePathInErrors) {
  const nlohmann::json doc =
      nlohmann::json::parse(R"({"a": {"b": [1, 2.5, "x"], "n": -3, "s": "", "t": true}})");
  const JsonNode root(doc, "f.json", "");
  const JsonNode a = root["a"];
  EXPECT_EQ(a.path(), "a");
  EXPECT_TRUE(a.has("b"));
  EXPECT_FALSE(a.has("zz"));
  EXPECT_EQ(a["b"].array(1, 3), 3u);
  EXPECT_DOUBLE_EQ(a["b"][1].number(), 2.5);
  EXPECT_EQ(a["n"].integer(-5, 5), -3);
  EXPECT_TRUE(a["t"].boolean());
  EXPECT_EQ(a["s"].string(true), "");

  EXPECT_EQ(messageOf([&] { a["zz"].number(); }), "f.json: a.zz: missing field");
  EXPECT_EQ(messageOf([&] { a["b"][2].number(); }), "f.json: a.b[2]: expected a number");
  EXPECT_EQ(messageOf([&] { a["b"][1].integer(0, 9); }), "f.json: a.b[1]: expected an integer");
  EXPECT_NE(messageOf([&] { a["n"].integer(0, 9); }).find("a.n"), std::string::npos);
  EXPECT_NE(messageOf([&] { a["n"].nonNegative(); }).find("expected a finite number ≥ 0"), std::string::npos);
  EXPECT_NE(messageOf([&] { a["b"].array(4, 9); }).find("a.b"), std::string::npos);
  EXPECT_NE(messageOf([&] { a["b"].arrayOf(2, "two"); }).find("two"), std::string::npos);
  EXPECT_NE(messageOf([&] { a["s"].string(); }).find("a.s"), std::string::npos);
  EXPECT_EQ(messageOf([&] { a.object({"b", "n", "s"}); }), "f.json: a.t: unknown field 't'");
  EXPECT_EQ(messageOf([&] { a.object({"b", "n", "s", "t"}); }), "");
  EXPECT_NE(messageOf([&] { a["b"][2].choice({"y", "z"}); }).find("'x' is not one of"), std::string::npos);
}

} // namespace
} // namespace sylva

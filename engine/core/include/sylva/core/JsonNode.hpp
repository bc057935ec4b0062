#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

namespace sylva {

/**
 * A JSON value with the file it came from and its JSON path, for strict parsing of Sylva's data files
 * (folding projects, blade models). Every check throws sylva::Error with one line reading
 * `<where>: <path>: <reason>`, e.g. `grass.json: blades[0].lods[1].widths[3]: expected a finite number ≥ 0`;
 * the root's path reads `(top level)`. Paths join keys with '.' and indices as `[i]`:
 * `zones[0].shape.pts[2]`.
 *
 * A JsonNode refers to its value without copying it: the JSON document must outlive every node made from it.
 * Domain readers (vectors, polygons, …) are free functions over a JsonNode in their own module.
 */
class JsonNode {
public:
  /** `value` at JSON path `path` ("" for the root) of the document named `where` (usually a file name). */
  JsonNode(const nlohmann::json& value, std::string where, std::string path);

  /** The JSON value itself, for checks this class does not offer. */
  const nlohmann::json& value() const { return mValue; }
  /** The JSON path, e.g. `zones[0].shape`; "" for the root. */
  const std::string& path() const { return mPath; }

  /** Throws sylva::Error `<where>: <path>: <reason>` (`(top level)` for the root's path). */
  [[noreturn]] void error(const std::string& reason) const;

  /** Whether this is an object holding `key`; false for any other value. */
  bool has(const char* key) const;

  /**
   * Requires an object whose keys are all in `allowed`; returns this node. Errors: `expected a JSON object`;
   * for a key not allowed, at that key's path, `unknown field '<key>'`.
   */
  const JsonNode& object(std::initializer_list<const char*> allowed) const;

  /**
   * The field `key`, whose path is this path plus `.key`. Error, at the field's path: `missing field` (also
   * when this is not an object; call object() first for the better message).
   */
  JsonNode operator[](const char* key) const;

  /**
   * Entry `index` of an array, whose path is this path plus `[index]`. The caller checks the size first
   * (array() or arrayOf()); an index out of range throws nlohmann::json's out_of_range, not sylva::Error.
   */
  JsonNode operator[](std::size_t index) const;

  /**
   * Requires an array of `minCount` … `maxCount` entries; returns its size. Errors: `expected an array`,
   * `expected at least <min> entries, got <n>`, `at most <max> entries allowed, got <n>`.
   */
  std::size_t array(std::size_t minCount, std::size_t maxCount) const;

  /**
   * Requires an array of exactly `count` entries; `what` says where the count comes from (e.g. "'knots'").
   * Errors: `expected an array`, `expected <count> entries (<what>), got <n>`.
   */
  void arrayOf(std::size_t count, const char* what) const;

  /** A finite number (integer or not). Errors: `expected a number`, `expected a finite number`. */
  double number() const;

  /**
   * A finite number in [lo, hi] (inclusive). Errors: those of number(), then `<v> is out of range [<lo>,
   * <hi>]`.
   */
  double number(double lo, double hi) const;

  /** A finite number ≥ 0. Error (for any other value, including a non-number): `expected a finite number ≥
   * 0`. */
  double nonNegative() const;

  /**
   * A whole number in [lo, hi] (1.0 counts as 1). Errors: `expected an integer` (also for a non-number or a
   * non-finite number), then `<v> is out of range [<lo>, <hi>]`.
   */
  int integer(int lo, int hi) const;

  /** A string, empty only when `allowEmpty`. Errors: `expected a string`, `must not be empty`. */
  std::string string(bool allowEmpty = false) const;

  /** true or false (not 0 or 1). Error: `expected true or false`. */
  bool boolean() const;

  /**
   * A non-empty string equal to one of `names`; returns it. Errors: those of string(), then `'<s>' is not one
   * of: <name>, <name>, …`.
   */
  std::string choice(std::initializer_list<const char*> names) const;

private:
  std::string join(const std::string& key) const;

  const nlohmann::json& mValue;
  std::string mWhere;
  std::string mPath;
};

} // namespace sylva

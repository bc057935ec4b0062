#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace sylva {

/**
 * A JSON value with the file it came from and its JSON Pointer (RFC 6901), for strict parsing of every Sylva
 * data file (scenes, folding projects, blade models, tree species, tile sets, wind settings): one dialect,
 * one set of messages. Every check throws sylva::Error with one line reading `<where>: <pointer>: <reason>`,
 * e.g. `grass.json: /blades/0/lods/1/widths/3: -1 is less than 0`; the root reads `/`. Control characters in
 * keys and values are written as `\u00XX`, so a message never spans lines. An unknown key names the closest
 * known one when it is plausibly a typo: `meadow.json: /grass/0/densty: unknown field (did you mean
 * 'density'?)`.
 *
 * A JsonNode refers to its value without copying it: the JSON document must outlive every node made from it.
 * Domain readers (vectors, polygons, …) are free functions over a JsonNode in their own module.
 */
class JsonNode {
public:
  /** `value` at JSON Pointer `pointer` ("" for the root) of the document named `where` (usually a file). */
  JsonNode(const nlohmann::json& value, std::string where, std::string pointer = "");

  /** The JSON value itself, for checks this class does not offer. */
  const nlohmann::json& value() const { return mValue; }
  /** The JSON Pointer of this value, e.g. `/zones/0/shape`; "" for the root. */
  const std::string& path() const { return mPath; }
  /** The document's name, as given (usually the file). */
  const std::string& where() const { return mWhere; }

  /** Throws sylva::Error `<where>: <pointer>: <reason>` (`/` for the root), on one line. */
  [[noreturn]] void error(const std::string& reason) const;

  /** Whether this is an object holding `key`; false for any other value. */
  bool has(const char* key) const;

  /**
   * Requires an object whose keys are all in `allowed`; returns this node. Errors: `expected an object, got
   * TYPE`; at an unknown key's pointer, `unknown field`, with ` (did you mean 'KEY'?)` when one is close.
   */
  const JsonNode& object(std::initializer_list<const char*> allowed) const;

  /** The field `key`. Error, at the field's pointer: `missing field` (also when this is not an object). */
  JsonNode operator[](const char* key) const;
  /** The field `key` of an object that holds it (keys read from the document itself, any text). */
  JsonNode child(std::string_view key) const;

  /**
   * Entry `index` of an array. The caller checks the size first (array() or arrayOf()); an index out of range
   * throws nlohmann::json's out_of_range, not sylva::Error.
   */
  JsonNode operator[](std::size_t index) const;

  /**
   * Requires an array of `minCount` … `maxCount` entries; returns its size. Errors: `expected an array, got
   * <type>`, `expected at least <min> entries, got <n>`, `<n> entries is more than <max>`.
   */
  std::size_t array(std::size_t minCount, std::size_t maxCount) const;

  /**
   * Requires an array of exactly `count` entries; `what` says where the count comes from (e.g. "'knots'").
   * Errors: `expected an array, got <type>`, `expected <count> entries (<what>), got <n>`.
   */
  void arrayOf(std::size_t count, const char* what) const;

  /** A finite number (integer or not). Errors: `expected a number, got <type>`, `expected a finite number`.
   */
  double number() const;
  /** A finite number in [lo, hi]. Errors: those of number(), then `<v> is less than <lo>` / `is more than`.
   */
  double number(double lo, double hi) const;
  /** A number in (lo, hi]: `lo` itself is refused with `<v> must be more than <lo>`. */
  double numberAbove(double lo, double hi) const;
  /** number(lo, hi) as a float. */
  float real(double lo, double hi) const { return static_cast<float>(number(lo, hi)); }
  /** numberAbove(lo, hi) as a float. */
  float realAbove(double lo, double hi) const { return static_cast<float>(numberAbove(lo, hi)); }
  /** A finite number ≥ 0 (no upper bound). */
  double nonNegative() const;

  /**
   * A whole number in [lo, hi] (1.0 counts as 1). Errors: those of number(), `expected a whole number, got
   * <v>`, then `<v> is less than <lo>` / `is more than <hi>`.
   */
  int integer(long long lo, long long hi) const;
  /** A whole number in [0, 2^64) (seeds). Errors: `<v> is less than 0`, `expected a whole number in ...`. */
  std::uint64_t unsignedInteger() const;

  /**
   * A string, empty only when `allowEmpty`, at most `maxLength` bytes. Errors: `expected a string, got
   * <type>`, `must not be empty`, `<n> characters is more than <max>`.
   */
  std::string string(bool allowEmpty = false, std::size_t maxLength = 1u << 20) const;

  /** true or false (not 0 or 1). Error: `expected true or false, got <type>`. */
  bool boolean() const;

  /**
   * A non-empty string equal to one of `names`; returns it. Errors: those of string(), then `'S' is not one
   * of: NAME, NAME, …`.
   */
  std::string choice(std::initializer_list<const char*> names) const;

private:
  const nlohmann::json& mValue;
  std::string mWhere;
  std::string mPath;
};

/** JSON Pointer escaping of one reference token (RFC 6901): '~' → "~0", '/' → "~1". */
std::string jsonPointerToken(std::string_view token);

/** The closest of `candidates` to `key` by edit distance, or "" when none is plausibly a typo of it. */
std::string closestKey(std::string_view key, const std::vector<std::string>& candidates);

/**
 * Parses a JSON document, refusing duplicate keys in an object (nlohmann keeps the last one silently, hiding
 * a typo made by copy and paste). Errors, on one line: `<where>:<line>:<col>: invalid JSON: <reason>`,
 * `<where>: <pointer>: duplicate field`.
 */
nlohmann::json parseJsonStrict(std::string_view text, const std::string& where);

/** Formats a number for messages: integers without a fraction, others in shortest round-trip form. */
std::string showNumber(double v);

} // namespace sylva

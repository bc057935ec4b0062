#include <sylva/core/JsonNode.hpp>

#include <sylva/core/Error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace sylva {

namespace {

/** `text` with control characters written as \uXXXX, so an error message stays on one line. */
std::string oneLine(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/** The text's 1-based line and column of the 1-based byte offset `byte` (nlohmann's parse_error::byte). */
std::pair<std::size_t, std::size_t> lineColumn(std::string_view text, std::size_t byte) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

/** nlohmann's message without its "[json.exception…] parse error at line L, column C: " prefix. */
std::string parseReason(const std::string& what) {
  std::string reason = what;
  const auto tag = reason.find("] ");
  if (tag != std::string::npos) {
    reason = reason.substr(tag + 2);
  }
  const auto colon = reason.find(": ");
  if (reason.rfind("parse error", 0) == 0 && colon != std::string::npos) {
    reason = reason.substr(colon + 2);
  }
  std::replace(reason.begin(), reason.end(), '\n', ' ');
  return reason;
}

} // namespace

std::string jsonPointerToken(std::string_view token) {
  std::string out;
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string closestKey(std::string_view key, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t bestDistance = std::numeric_limits<std::size_t>::max();
  for (const std::string& c : candidates) {
    const std::size_t d = editDistance(key, c);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  // A typo: at most a third of the longer name differs (and at least one edit is allowed for short names).
  const std::size_t longer = std::max(key.size(), best.size());
  const std::size_t allowed = std::max<std::size_t>(2, longer / 3);
  return bestDistance <= allowed ? best : std::string();
}

std::string showNumber(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e15) {
    return fmt::format("{}", static_cast<long long>(v));
  }
  return fmt::format("{}", v);
}

JsonNode::JsonNode(const nlohmann::json& value, std::string where, std::string pointer)
    : mValue(value), mWhere(std::move(where)), mPath(std::move(pointer)) {}

void JsonNode::error(const std::string& reason) const {
  fail("{}", oneLine(fmt::format("{}: {}: {}", mWhere, mPath.empty() ? "/" : mPath, reason)));
}

bool JsonNode::has(const char* key) const {
  return mValue.is_object() && mValue.contains(key);
}

const JsonNode& JsonNode::object(std::initializer_list<const char*> allowed) const {
  if (!mValue.is_object()) {
    error(fmt::format("expected an object, got {}", mValue.type_name()));
  }
  const std::vector<std::string> known(allowed.begin(), allowed.end());
  for (const auto& item : mValue.items()) {
    const std::string& key = item.key();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      const std::string suggestion = closestKey(key, known);
      child(key).error(suggestion.empty() ? std::string("unknown field")
                                          : fmt::format("unknown field (did you mean '{}'?)", suggestion));
    }
  }
  return *this;
}

JsonNode JsonNode::operator[](const char* key) const {
  if (!has(key)) {
    JsonNode(mValue, mWhere, mPath + "/" + jsonPointerToken(key)).error("missing field");
  }
  return child(key);
}

JsonNode JsonNode::child(std::string_view key) const {
  return JsonNode(mValue.at(std::string(key)), mWhere, mPath + "/" + jsonPointerToken(key));
}

JsonNode JsonNode::operator[](std::size_t index) const {
  return JsonNode(mValue.at(index), mWhere, mPath + "/" + std::to_string(index));
}

std::size_t JsonNode::array(std::size_t minCount, std::size_t maxCount) const {
  if (!mValue.is_array()) {
    error(fmt::format("expected an array, got {}", mValue.type_name()));
  }
  const std::size_t n = mValue.size();
  if (n < minCount) {
    error(fmt::format("expected at least {} entries, got {}", minCount, n));
  }
  if (n > maxCount) {
    error(fmt::format("{} entries is more than {}", n, maxCount));
  }
  return n;
}

void JsonNode::arrayOf(std::size_t count, const char* what) const {
  if (!mValue.is_array()) {
    error(fmt::format("expected an array, got {}", mValue.type_name()));
  }
  if (mValue.size() != count) {
    error(fmt::format("expected {} entries ({}), got {}", count, what, mValue.size()));
  }
}

double JsonNode::number() const {
  if (!mValue.is_number()) {
    error(fmt::format("expected a number, got {}", mValue.type_name()));
  }
  const double v = mValue.get<double>();
  if (!std::isfinite(v)) {
    error("expected a finite number");
  }
  return v;
}

double JsonNode::number(double lo, double hi) const {
  const double v = number();
  if (v < lo) {
    error(fmt::format("{} is less than {}", showNumber(v), showNumber(lo)));
  }
  if (v > hi) {
    error(fmt::format("{} is more than {}", showNumber(v), showNumber(hi)));
  }
  return v;
}

double JsonNode::numberAbove(double lo, double hi) const {
  const double v = number(lo, hi);
  if (v <= lo) {
    error(fmt::format("{} must be more than {}", showNumber(v), showNumber(lo)));
  }
  return v;
}

double JsonNode::nonNegative() const {
  return number(0.0, std::numeric_limits<double>::max());
}

int JsonNode::integer(long long lo, long long hi) const {
  const double v = number();
  if (v != std::floor(v)) {
    error(fmt::format("expected a whole number, got {}", showNumber(v)));
  }
  if (v < static_cast<double>(lo)) {
    error(fmt::format("{} is less than {}", showNumber(v), lo));
  }
  if (v > static_cast<double>(hi)) {
    error(fmt::format("{} is more than {}", showNumber(v), hi));
  }
  return static_cast<int>(v);
}

std::uint64_t JsonNode::unsignedInteger() const {
  if (mValue.is_number_unsigned()) {
    return mValue.get<std::uint64_t>();
  }
  if (mValue.is_number_integer()) {
    error(fmt::format("{} is less than 0", mValue.get<std::int64_t>()));
  }
  error(fmt::format("expected a whole number in [0, 2^64), got {}", mValue.type_name()));
}

std::string JsonNode::string(bool allowEmpty, std::size_t maxLength) const {
  if (!mValue.is_string()) {
    error(fmt::format("expected a string, got {}", mValue.type_name()));
  }
  std::string s = mValue.get<std::string>();
  if (s.empty() && !allowEmpty) {
    error("must not be empty");
  }
  if (s.size() > maxLength) {
    error(fmt::format("{} characters is more than {}", s.size(), maxLength));
  }
  return s;
}

bool JsonNode::boolean() const {
  if (!mValue.is_boolean()) {
    error(fmt::format("expected true or false, got {}", mValue.type_name()));
  }
  return mValue.get<bool>();
}

std::string JsonNode::choice(std::initializer_list<const char*> names) const {
  const std::string s = string();
  std::string list;
  for (const char* name : names) {
    if (s == name) {
      return s;
    }
    list += list.empty() ? std::string(name) : ", " + std::string(name);
  }
  error(fmt::format("'{}' is not one of: {}", s, list));
}

nlohmann::json parseJsonStrict(std::string_view text, const std::string& where) {
  struct Level {
    bool isObject = false;
    std::set<std::string> keys;
    std::string key;      ///< object: the current key
    long long index = -1; ///< array: the current index
  };
  std::vector<Level> stack;
  auto pathOf = [&stack](const std::string* lastKey) {
    std::string p;
    for (std::size_t i = 0; i < stack.size(); ++i) {
      const Level& l = stack[i];
      if (l.isObject) {
        p.append("/").append(jsonPointerToken(i + 1 == stack.size() && lastKey ? *lastKey : l.key));
      } else {
        p.append("/").append(std::to_string(l.index));
      }
    }
    return p;
  };
  // Inside an array, every value or container start begins a new element.
  auto nextElement = [&stack] {
    if (!stack.empty() && !stack.back().isObject) {
      ++stack.back().index;
    }
  };
  nlohmann::json::parser_callback_t callback = [&](int /*depth*/, nlohmann::json::parse_event_t event,
                                                   nlohmann::json& parsed) {
    switch (event) {
    case nlohmann::json::parse_event_t::object_start:
      nextElement();
      stack.push_back(Level{true, {}, {}, -1});
      break;
    case nlohmann::json::parse_event_t::array_start:
      nextElement();
      stack.push_back(Level{false, {}, {}, -1});
      break;
    case nlohmann::json::parse_event_t::object_end:
    case nlohmann::json::parse_event_t::array_end:
      if (!stack.empty()) {
        stack.pop_back();
      }
      break;
    case nlohmann::json::parse_event_t::key: {
      const std::string key = parsed.get<std::string>();
      if (!stack.empty()) {
        if (!stack.back().keys.insert(key).second) {
          fail("{}", oneLine(fmt::format("{}: {}: duplicate field", where, pathOf(&key))));
        }
        stack.back().key = key;
      }
      break;
    }
    case nlohmann::json::parse_event_t::value:
      nextElement();
      break;
    }
    return true;
  };
  // Where the parser stopped: the key last read in an object, the element after the last complete one in an
  // array (a scalar that fails to parse emits no event; a container counts itself when it starts).
  auto stoppedIn = [&stack] {
    std::string path;
    for (std::size_t i = 0; i < stack.size(); ++i) {
      const Level& l = stack[i];
      if (l.isObject && l.key.empty()) {
        break;
      }
      const bool last = i + 1 == stack.size();
      path.append("/").append(l.isObject ? jsonPointerToken(l.key)
                                         : std::to_string(last ? l.index + 1 : std::max(0LL, l.index)));
    }
    return path.empty() ? std::string() : fmt::format(" (in {})", path);
  };
  try {
    return nlohmann::json::parse(text.begin(), text.end(), callback);
  } catch (const nlohmann::json::parse_error& e) {
    const auto [line, column] = lineColumn(text, e.byte);
    std::string reason = parseReason(e.what());
    // NaN, Infinity, -Infinity, nan, inf: what other writers print for non-finite numbers. The last token
    // the parser read is at the end of its "last read: '…'".
    if (const std::size_t read = reason.rfind("last read: '"); read != std::string::npos) {
      std::string token = reason.substr(read + 12);
      if (!token.empty() && token.back() == '\'') {
        token.pop_back();
      }
      if (const std::size_t cut = token.find_last_of(" \t\n:,[{"); cut != std::string::npos) {
        token.erase(0, cut + 1);
      }
      if (!token.empty() && token.front() == '-') {
        token.erase(0, 1);
      }
      if (token.starts_with("N") || token.starts_with("I") || token.starts_with("na") ||
          token.starts_with("in")) {
        reason += " (JSON has no NaN or Infinity: give a finite number)";
      }
    }
    fail("{}",
         oneLine(fmt::format("{}:{}:{}: invalid JSON: {}{}", where, line, column, reason, stoppedIn())));
  } catch (const nlohmann::json::exception& e) {
    fail("{}", oneLine(fmt::format("{}: invalid JSON: {}{}", where, parseReason(e.what()), stoppedIn())));
  }
}

} // namespace sylva

#include <sylva/core/JsonNode.hpp>

#include <sylva/core/Error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace sylva {

JsonNode::JsonNode(const nlohmann::json& value, std::string where, std::string path)
    : mValue(value), mWhere(std::move(where)), mPath(std::move(path)) {}

void JsonNode::error(const std::string& reason) const {
  fail("{}: {}: {}", mWhere, mPath.empty() ? std::string("(top level)") : mPath, reason);
}

bool JsonNode::has(const char* key) const {
  return mValue.is_object() && mValue.contains(key);
}

const JsonNode& JsonNode::object(std::initializer_list<const char*> allowed) const {
  if (!mValue.is_object()) {
    error("expected a JSON object");
  }
  for (const auto& item : mValue.items()) {
    const std::string& key = item.key();
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* name) { return key == name; })) {
      JsonNode(item.value(), mWhere, join(key)).error(fmt::format("unknown field '{}'", key));
    }
  }
  return *this;
}

JsonNode JsonNode::operator[](const char* key) const {
  if (!has(key)) {
    JsonNode(mValue, mWhere, join(key)).error("missing field");
  }
  return JsonNode(mValue.at(key), mWhere, join(key));
}

JsonNode JsonNode::operator[](std::size_t index) const {
  return JsonNode(mValue.at(index), mWhere, fmt::format("{}[{}]", mPath, index));
}

std::size_t JsonNode::array(std::size_t minCount, std::size_t maxCount) const {
  if (!mValue.is_array()) {
    error("expected an array");
  }
  if (mValue.size() < minCount) {
    error(fmt::format("expected at least {} entries, got {}", minCount, mValue.size()));
  }
  if (mValue.size() > maxCount) {
    error(fmt::format("at most {} entries allowed, got {}", maxCount, mValue.size()));
  }
  return mValue.size();
}

void JsonNode::arrayOf(std::size_t count, const char* what) const {
  if (!mValue.is_array()) {
    error("expected an array");
  }
  if (mValue.size() != count) {
    error(fmt::format("expected {} entries ({}), got {}", count, what, mValue.size()));
  }
}

double JsonNode::number() const {
  if (!mValue.is_number()) {
    error("expected a number");
  }
  const double v = mValue.get<double>();
  if (!std::isfinite(v)) {
    error("expected a finite number");
  }
  return v;
}

double JsonNode::number(double lo, double hi) const {
  const double v = number();
  if (v < lo || v > hi) {
    error(fmt::format("{} is out of range [{}, {}]", v, lo, hi));
  }
  return v;
}

double JsonNode::nonNegative() const {
  if (!mValue.is_number() || !std::isfinite(mValue.get<double>()) || mValue.get<double>() < 0.0) {
    error("expected a finite number ≥ 0");
  }
  return mValue.get<double>();
}

int JsonNode::integer(int lo, int hi) const {
  if (!mValue.is_number()) {
    error("expected an integer");
  }
  const double v = mValue.get<double>();
  if (!std::isfinite(v) || v != std::floor(v)) {
    error("expected an integer");
  }
  if (v < lo || v > hi) {
    error(fmt::format("{} is out of range [{}, {}]", v, lo, hi));
  }
  return static_cast<int>(v);
}

std::string JsonNode::string(bool allowEmpty) const {
  if (!mValue.is_string()) {
    error("expected a string");
  }
  std::string s = mValue.get<std::string>();
  if (s.empty() && !allowEmpty) {
    error("must not be empty");
  }
  return s;
}

bool JsonNode::boolean() const {
  if (!mValue.is_boolean()) {
    error("expected true or false");
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

std::string JsonNode::join(const std::string& key) const {
  return mPath.empty() ? key : mPath + "." + key;
}

} // namespace sylva

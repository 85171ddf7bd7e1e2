// Template part of config.h (type conversion with clear messages).
#pragma once

#include <cmath>
#include <type_traits>

namespace cosim::config {

namespace detail {
template <class T>
const char* type_name() {
  if constexpr (std::is_same_v<T, bool>) return "true or false";
  else if constexpr (std::is_integral_v<T>) return "an integer";
  else if constexpr (std::is_floating_point_v<T>) return "a number";
  else return "a string";
}

template <class T>
bool convert(const YAML::Node& n, T& out) {
  if (!n.IsScalar()) return false;
  if constexpr (std::is_same_v<T, bool>) {
    const std::string& s = n.Scalar();
    if (s == "true" || s == "yes" || s == "on") {
      out = true;
      return true;
    }
    if (s == "false" || s == "no" || s == "off") {
      out = false;
      return true;
    }
    return false;
  } else if constexpr (std::is_integral_v<T>) {
    const std::string& s = n.Scalar();
    try {
      std::size_t pos = 0;
      long long v = std::stoll(s, &pos);
      if (pos != s.size()) return false;
      out = static_cast<T>(v);
      return true;
    } catch (...) { return false; }
  } else if constexpr (std::is_floating_point_v<T>) {
    const std::string& s = n.Scalar();
    try {
      std::size_t pos = 0;
      double v = std::stod(s, &pos);
      if (pos != s.size() || !std::isfinite(v)) return false;  // nan and inf are not numbers a scene can mean
      out = static_cast<T>(v);
      return true;
    } catch (...) { return false; }
  } else {
    out = n.Scalar();
    return true;
  }
}
}  // namespace detail

template <class T>
T Node::get(const std::string& key, const T& fallback, Check<T> check) {
  used_.insert(key);
  YAML::Node n = at(key);
  if (!n || n.IsNull()) return fallback;
  T v{};
  if (!detail::convert(n, v)) fail(key, std::string(detail::type_name<T>()) + ", got " + describe(n));
  if (check) {
    std::string expected = check(v);
    if (!expected.empty()) fail(key, expected + ", got " + describe(n));
  }
  return v;
}

template <class T>
T Node::require(const std::string& key, Check<T> check) {
  used_.insert(key);
  YAML::Node n = at(key);
  if (!n || n.IsNull())
    fail(key, std::string("a value (") + detail::type_name<T>() + "), but the key is missing" + typo_of_missing(key));
  return get<T>(key, T{}, check);
}

template <class T>
T Node::as(Check<T> check) const {
  T v{};
  if (!detail::convert(node_, v)) fail("", std::string(detail::type_name<T>()) + ", got " + describe(node_));
  if (check) {
    std::string expected = check(v);
    if (!expected.empty()) fail("", expected + ", got " + describe(node_));
  }
  return v;
}

}  // namespace cosim::config

// Minimal streaming JSON writer (Boost 1.74 has no Boost.JSON). Deterministic output:
// keys appear in insertion order, doubles with round-trip precision.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

namespace dcshell {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& os, int indent = 2) : os_(os), indent_(indent) {}
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(const std::string& k);
  JsonWriter& value(const std::string& v);
  JsonWriter& value(const char* v) { return value(std::string(v)); }
  JsonWriter& value(double v);  ///< NaN/inf are written as null
  JsonWriter& value(std::int64_t v);
  /// Any other integer type.
  template <class I, class = std::enable_if_t<std::is_integral_v<I> && !std::is_same_v<I, bool> &&
                                              !std::is_same_v<I, std::int64_t>>>
  JsonWriter& value(I v) { return value(static_cast<std::int64_t>(v)); }
  JsonWriter& value(bool v);
  JsonWriter& null();
  template <class T>
  JsonWriter& field(const std::string& k, const T& v) { key(k); return value(v); }
  JsonWriter& value(const std::vector<double>& v);

 private:
  void before_value();
  void newline();
  std::ostream& os_;
  int indent_;
  struct Level { bool is_object; bool empty; };
  std::vector<Level> stack_;
  bool after_key_ = false;
};

std::string json_escape(const std::string& s);

}  // namespace dcshell

// Checked reading of the scene file's JSON (private to the scene loader, model/scene_io*.cpp).
// Every failure throws InputError(file, json_path, "expected X, found Y") with a JSON path in
// the style `$.draws[2].indices[5]`.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace rastercmp::scene_json {

using Json = nlohmann::json;

// Text → JSON, with the checks the JSON library leaves out: an empty file, a UTF-16/32 byte
// order mark, NUL bytes, malformed UTF-8 and duplicate keys. Syntax errors get the path `$`
// and the line, column and byte offset.
Json parse_text(std::string_view text, const std::string& file);

// A short description of a JSON value for the "found ..." half of a message.
std::string describe(const Json& value);

// `$.a` + "b" → `$.a.b` (or `$.a["b c"]` when the key is not an identifier); `$.a` + 2 → `$.a[2]`.
std::string key_path(const std::string& parent, std::string_view key);
std::string index_path(const std::string& parent, size_t index);

// One value of the document with its JSON path. Cheap to copy; refers to the document.
class Node {
 public:
  Node(const Json& value, std::string path, const std::string& file)
      : value_(&value), path_(std::move(path)), file_(&file) {}

  const Json& json() const { return *value_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }

  // Throws InputError(file, path, "expected <what>, found <describe(value)>").
  [[noreturn]] void fail(std::string_view what) const;
  // Throws InputError(file, path, message) with the message as given.
  [[noreturn]] void fail_message(std::string message) const;

  // Checks the value is an object whose keys are all in `allowed`; `what` names the object.
  void expect_object(std::string_view what, std::initializer_list<std::string_view> allowed) const;
  std::optional<Node> find(std::string_view key) const;
  Node element(size_t index) const;
  // Checks the value is an array of min..max elements and returns its size.
  size_t expect_array(size_t min_size, size_t max_size, std::string_view what) const;

  bool as_bool() const;
  // A string without control characters (one line).
  std::string as_line(std::string_view what) const;
  int64_t as_integer(int64_t min_value, int64_t max_value, std::string_view what) const;
  // A finite number in min..max (inclusive).
  double as_number(double min_value, double max_value, std::string_view what) const;
  // A finite number that a float can hold, rounded to float.
  float as_float(std::string_view what) const;

  // One of `names` (each the to_string of the matching enum value).
  template <class Enum>
  Enum as_enum(std::initializer_list<Enum> values) const {
    const size_t index = enum_index(values.size(), [&](size_t i) { return to_string(values.begin()[i]); });
    return values.begin()[index];
  }
  template <class Enum, size_t N>
  Enum as_enum(const std::array<Enum, N>& values) const {
    return values[enum_index(N, [&](size_t i) { return to_string(values[i]); })];
  }

 private:
  template <class NameOf>
  size_t enum_index(size_t count, NameOf name_of) const {
    std::string choices;
    for (size_t i = 0; i < count; ++i) {
      if (json().is_string() && json().get_ref<const std::string&>() == name_of(i)) return i;
      choices += (i == 0 ? "\"" : ", \"") + std::string(name_of(i)) + "\"";
    }
    fail("one of " + choices);
  }

  const Json* value_;
  std::string path_;
  const std::string* file_;
};

}  // namespace rastercmp::scene_json

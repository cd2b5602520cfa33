#include "model/scene_json.hpp"

#include <cfloat>
#include <cmath>

#include <fmt/format.h>

#include "model/errors.hpp"

namespace rastercmp::scene_json {

namespace {

constexpr size_t kMaxShownStringLength = 40;

bool is_identifier(std::string_view key) {
  if (key.empty() || (key[0] >= '0' && key[0] <= '9')) return false;
  for (const char c : key) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

// A key or string for a message: quoted, and past kMaxShownStringLength bytes cut, with its size
// (a megabyte key is not echoed whole).
std::string shown_string(std::string_view text) {
  if (text.size() <= kMaxShownStringLength) return Json(std::string(text)).dump();
  size_t cut = kMaxShownStringLength;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // keep UTF-8 whole
  return Json(std::string(text.substr(0, cut))).dump() + fmt::format("... ({} bytes)", text.size());
}

std::string join_keys(std::initializer_list<std::string_view> keys) {
  std::string joined;
  for (const std::string_view key : keys) joined += (joined.empty() ? "" : ", ") + std::string(key);
  return joined;
}

}  // namespace

std::string describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case Json::value_t::string: return "the string " + shown_string(value.get_ref<const std::string&>());
    case Json::value_t::array:
      if (value.empty()) return "an empty array";
      return fmt::format("an array of {} element{}", value.size(), value.size() == 1 ? "" : "s");
    case Json::value_t::object:
      if (value.empty()) return "an empty object";
      return fmt::format("an object with {} key{}", value.size(), value.size() == 1 ? "" : "s");
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return value.dump();
    default: return "a value of type " + std::string(value.type_name());
  }
}

std::string key_path(const std::string& parent, std::string_view key) {
  if (is_identifier(key) && key.size() <= kMaxShownStringLength) return parent + "." + std::string(key);
  return parent + "[" + shown_string(key) + "]";
}

std::string index_path(const std::string& parent, size_t index) { return fmt::format("{}[{}]", parent, index); }

void Node::fail(std::string_view what) const {
  throw InputError(file(), path_, fmt::format("expected {}, found {}", what, describe(json())));
}

void Node::fail_message(std::string message) const { throw InputError(file(), path_, std::move(message)); }

void Node::expect_object(std::string_view what, std::initializer_list<std::string_view> allowed) const {
  if (!json().is_object()) fail(what);
  for (const auto& [key, value] : json().items()) {
    bool known = false;
    for (const std::string_view name : allowed) known = known || key == name;
    if (!known) {
      throw InputError(
          file(), key_path(path_, key),
          fmt::format("expected one of the keys {}, found the unknown key {}", join_keys(allowed), shown_string(key)));
    }
  }
}

std::optional<Node> Node::find(std::string_view key) const {
  const auto it = json().find(key);
  if (it == json().end()) return std::nullopt;
  return Node(*it, key_path(path_, key), file());
}

Node Node::element(size_t index) const { return Node(json()[index], index_path(path_, index), file()); }

size_t Node::expect_array(size_t min_size, size_t max_size, std::string_view what) const {
  if (!json().is_array() || json().size() < min_size || json().size() > max_size) fail(what);
  return json().size();
}

bool Node::as_bool() const {
  if (!json().is_boolean()) fail("true or false");
  return json().get<bool>();
}

std::string Node::as_line(std::string_view what) const {
  if (!json().is_string()) fail(what);
  const std::string& text = json().get_ref<const std::string&>();
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    // C0 and DEL, and C1 (U+0080..U+009F, in UTF-8 0xC2 0x80..0x9F; the text is valid UTF-8).
    const bool c1 = c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) <= 0x9F;
    if (c < 0x20 || c == 0x7F || c1) fail(fmt::format("{} without control characters", what));
  }
  return text;
}

int64_t Node::as_integer(int64_t min_value, int64_t max_value, std::string_view what) const {
  if (json().is_number_unsigned()) {
    const uint64_t value = json().get<uint64_t>();
    if (value > uint64_t(max_value) || (min_value > 0 && value < uint64_t(min_value))) fail(what);
    return int64_t(value);
  }
  if (!json().is_number_integer()) fail(what);
  const int64_t value = json().get<int64_t>();
  if (value < min_value || value > max_value) fail(what);
  return value;
}

double Node::as_number(double min_value, double max_value, std::string_view what) const {
  if (!json().is_number()) fail(what);
  const double value = json().get<double>();
  if (!std::isfinite(value) || value < min_value || value > max_value) fail(what);
  return value;
}

float Node::as_float(std::string_view what) const { return float(as_number(-FLT_MAX, FLT_MAX, what)); }

}  // namespace rastercmp::scene_json

// Scene text → JSON document: encoding checks, syntax errors with their position, duplicate keys.
#include <set>
#include <vector>

#include <fmt/format.h>

#include "model/errors.hpp"
#include "model/scene_json.hpp"

namespace rastercmp::scene_json {

namespace {

std::string position_of(std::string_view text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++column;  // columns count characters, not UTF-8 continuation bytes
    }
  }
  return fmt::format("line {}, column {} (byte offset {})", line, column, offset);
}

// Length of the UTF-8 sequence starting at text[i], or 0 when it is malformed
// (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF).
size_t utf8_sequence_length(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0u; };
  const auto continuation = [&](size_t k) { return (byte(k) & 0xC0) == 0x80; };
  const unsigned lead = byte(0);
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) return continuation(1) ? 2 : 0;
  if (lead >= 0xE0 && lead <= 0xEF) {
    const unsigned second = byte(1);
    const bool ok = (lead == 0xE0 ? second >= 0xA0 : true) && (lead == 0xED ? second < 0xA0 : true);
    return ok && continuation(1) && continuation(2) ? 3 : 0;
  }
  if (lead >= 0xF0 && lead <= 0xF4) {
    const unsigned second = byte(1);
    const bool ok = (lead == 0xF0 ? second >= 0x90 : true) && (lead == 0xF4 ? second < 0x90 : true);
    return ok && continuation(1) && continuation(2) && continuation(3) ? 4 : 0;
  }
  return 0;
}

void check_encoding(std::string_view text, const std::string& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    throw InputError(file, "$",
                     text.empty() ? "expected a JSON object (the scene), found an empty file"
                                  : "expected a JSON object (the scene), found only white space");
  }
  if (text.starts_with("\xFF\xFE") || text.starts_with("\xFE\xFF")) {
    throw InputError(file, "$", "expected UTF-8 text, found a UTF-16 or UTF-32 byte order mark");
  }
  for (size_t i = 0; i < text.size();) {
    if (text[i] == '\0') {
      throw InputError(
          file, "$",
          "expected UTF-8 JSON text, found a NUL byte at " + position_of(text, i) + " (binary data, or UTF-16 text?)");
    }
    const size_t length = utf8_sequence_length(text, i);
    if (length == 0) {
      throw InputError(file, "$",
                       fmt::format("expected UTF-8 text, found the invalid UTF-8 byte 0x{:02X} at {}",
                                   static_cast<unsigned char>(text[i]), position_of(text, i)));
    }
    i += length;
  }
}

// Follows the parser through the document to know the path of the value being read,
// and rejects a key that appears twice in one object (the JSON library keeps the last).
class PathTracker {
 public:
  explicit PathTracker(const std::string& file) : file_(file) {}

  bool on_event(Json::parse_event_t event, const Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        count_element();
        frames_.push_back(Frame{event == Json::parse_event_t::array_start, 0, {}, {}});
        break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end: frames_.pop_back(); break;
      case Json::parse_event_t::key: on_key(parsed.get<std::string>()); break;
      case Json::parse_event_t::value: count_element(); break;
    }
    return true;
  }

  // Path of the value the parser is reading now: inside the innermost array, the element
  // after the last one counted; everywhere else, the element or key being read.
  std::string current_path() const {
    std::string path = "$";
    for (size_t i = 0; i < frames_.size(); ++i) {
      const Frame& frame = frames_[i];
      const bool innermost = i + 1 == frames_.size();
      path = frame.is_array ? index_path(path, innermost ? frame.elements : frame.elements - 1)
                            : key_path(path, frame.key);
    }
    return path;
  }

 private:
  struct Frame {
    bool is_array;
    size_t elements;  // arrays: elements seen so far
    std::string key;  // objects: the last key
    std::set<std::string> keys;
  };

  void count_element() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().elements;
  }

  void on_key(const std::string& key) {
    Frame& frame = frames_.back();
    frame.key = key;
    if (!frame.keys.insert(key).second) {
      throw InputError(file_, path_of_last(), "expected each key once in an object, found this key a second time");
    }
  }

  // Path of the key read last (every enclosing array: the element being read).
  std::string path_of_last() const {
    std::string path = "$";
    for (const Frame& frame : frames_) {
      path = frame.is_array ? index_path(path, frame.elements - 1) : key_path(path, frame.key);
    }
    return path;
  }

  const std::string& file_;
  std::vector<Frame> frames_;
};

std::string library_detail(const std::string& what) {
  const size_t bracket = what.find("] ");
  std::string detail = bracket == std::string::npos ? what : what.substr(bracket + 2);
  const size_t column = detail.find("column ");
  const size_t colon = column == std::string::npos ? std::string::npos : detail.find(": ", column);
  return colon == std::string::npos ? detail : detail.substr(colon + 2);
}

}  // namespace

Json parse_text(std::string_view text, const std::string& file) {
  check_encoding(text, file);
  PathTracker tracker(file);
  try {
    return Json::parse(text.begin(), text.end(), [&tracker](int, Json::parse_event_t event, Json& parsed) {
      return tracker.on_event(event, parsed);
    });
  } catch (const Json::parse_error& error) {
    const size_t offset = error.byte == 0 ? 0 : error.byte - 1;
    const bool at_end = error.byte > text.size();  // the parser read past the last byte
    throw InputError(file, "$",
                     fmt::format("expected valid JSON, found a syntax error at {}: {}{}", position_of(text, offset),
                                 library_detail(error.what()), at_end ? " (the file ends early: truncated?)" : ""));
  } catch (const Json::out_of_range& error) {
    throw InputError(file, tracker.current_path(),
                     "expected a number a double can hold, found " + library_detail(error.what()));
  }
}

}  // namespace rastercmp::scene_json

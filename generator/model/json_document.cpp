// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/json_document.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <sstream>

#include "model/model_error.hpp"

namespace kanegen::model {

using nlohmann::json;

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ModelError(path, "file", std::string("cannot open it (") + std::strerror(errno) + ")",
                     "check the path");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ModelError(path, "file", "cannot read it", "check the file");
  return text.str();
}

std::string pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

namespace {

std::string line_and_column(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// Tracks where the parser is (for the pointer of a duplicate key) and the
/// keys seen in each open object.
class DuplicateKeyFinder {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        open_.push_back({event == json::parse_event_t::array_start, 0, {}, {}});
        break;
      case json::parse_event_t::key: {
        Frame& f = open_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second && !duplicate_) duplicate_ = current_pointer();
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        open_.pop_back();
        element_done();
        break;
      case json::parse_event_t::value:
        element_done();
        break;
    }
    return true;
  }

  const std::optional<std::string>& duplicate() const { return duplicate_; }

 private:
  struct Frame {
    bool is_array;
    std::size_t index;
    std::string key;
    std::set<std::string> keys;
  };

  void element_done() {
    if (!open_.empty() && open_.back().is_array) ++open_.back().index;
  }

  std::string current_pointer() const {
    std::string out;
    for (const Frame& f : open_) out += "/" + (f.is_array ? std::to_string(f.index) : pointer_token(f.key));
    return out;
  }

  std::vector<Frame> open_;
  std::optional<std::string> duplicate_;
};

}  // namespace

json parse_json_document(const std::string& text, const std::string& file) {
  DuplicateKeyFinder finder;
  json document;
  try {
    document = json::parse(text, std::ref(finder));
  } catch (const json::parse_error& e) {
    // nlohmann's message: "[json.exception.parse_error.101] parse error at line L, column C: <detail>".
    std::string detail = e.what();
    const auto column_at = detail.find("column ");
    const auto colon = column_at == std::string::npos ? std::string::npos : detail.find(": ", column_at);
    if (colon != std::string::npos) detail = detail.substr(colon + 2);
    // "; " separates the problem from the fix in our messages.
    for (auto at = detail.find("; "); at != std::string::npos; at = detail.find("; ", at))
      detail.replace(at, 2, ", ");
    // e.byte is 1-based and points at the offending character.
    throw ModelError(file, line_and_column(text, e.byte == 0 ? 0 : e.byte - 1), "malformed JSON: " + detail,
                     "fix the JSON syntax (a missing or extra comma, quote or bracket is the usual cause)");
  } catch (const json::out_of_range& e) {
    // A number too large for a double ("1e999"): nlohmann gives no position,
    // so look for the number's text.
    std::string detail = e.what();
    const auto quote = detail.find('\'');
    const std::string number =
        quote == std::string::npos ? std::string() : detail.substr(quote + 1, detail.rfind('\'') - quote - 1);
    const auto at = number.empty() ? std::string::npos : text.find(number);
    throw ModelError(file, at == std::string::npos ? std::string("/") : line_and_column(text, at),
                     "number " + number + " is too large for a double (not finite)", "use a finite value");
  }
  if (finder.duplicate()) {
    const std::string& place = *finder.duplicate();
    const std::string key = place.substr(place.rfind('/') + 1);
    throw ModelError(file, place, "key '" + key + "' appears twice in the same object",
                     "keep only one of them (JSON readers would silently drop one)");
  }
  return document;
}

}  // namespace kanegen::model

#include "json_path.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <unordered_set>

namespace pge {
namespace {

constexpr std::string_view kWhitespace = " \t\r\n";
constexpr std::string_view kStructural = "{}[]:,";

bool is_space(char c) { return kWhitespace.find(c) != std::string_view::npos; }
bool is_structural(char c) { return kStructural.find(c) != std::string_view::npos; }

std::size_t skip_space(std::string_view text, std::size_t i) {
  while (i < text.size() && is_space(text[i])) ++i;
  return i;
}

// One token: a structural character, a string literal (to its closing quote, or to the end of a
// truncated text) or any other run of characters (numbers, literals, and garbage such as NaN).
std::size_t token_end(std::string_view text, std::size_t i) {
  if (is_structural(text[i])) return i + 1;
  if (text[i] == '"') {
    for (++i; i < text.size(); ++i) {
      if (text[i] == '\\')
        ++i;
      else if (text[i] == '"')
        return i + 1;
    }
    return text.size();
  }
  while (i < text.size() && !is_space(text[i]) && !is_structural(text[i]) && text[i] != '"') ++i;
  return i;
}

struct Frame {
  bool object = false;
  bool has_step = false;  // a key was read (object) or an element started (array)
  std::unordered_set<std::string> keys;
};

}  // namespace

JsonPath operator+(JsonPath path, std::string key) {
  path.push_back({std::move(key), -1});
  return path;
}

JsonPath operator+(JsonPath path, int index) {
  path.push_back({"", index});
  return path;
}

std::string dotted(const JsonPath& path, std::size_t from) {
  std::string out;
  for (std::size_t i = from; i < path.size(); ++i) {
    if (path[i].index >= 0) {
      out += '[' + std::to_string(path[i].index) + ']';
    } else {
      if (!out.empty()) out += '.';
      out += path[i].key;
    }
  }
  return out;
}

JsonPath parse_dotted(std::string_view text) {
  JsonPath path;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '.') {
      ++i;
    } else if (text[i] == '[') {
      const std::size_t close = text.find(']', i);
      if (close == std::string_view::npos) break;
      path = path + std::stoi(std::string(text.substr(i + 1, close - i - 1)));
      i = close + 1;
    } else {
      const std::size_t stop = std::min(text.find_first_of(".[", i), text.size());
      path = path + std::string(text.substr(i, stop - i));
      i = stop;
    }
  }
  return path;
}

TextPosition text_position(std::string_view text, std::size_t offset) {
  TextPosition pos{1, 1};
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++pos.line;
      pos.column = 1;
    } else {
      ++pos.column;
    }
  }
  return pos;
}

std::string string_literal(std::string_view text, std::size_t begin) {
  if (begin >= text.size() || text[begin] != '"') return {};
  const std::string_view literal = text.substr(begin, token_end(text, begin) - begin);
  // Keys and ids rarely hold escapes; only then is the real parser worth calling.
  if (literal.size() >= 2 && literal.back() == '"' && literal.find('\\') == std::string_view::npos)
    return std::string(literal.substr(1, literal.size() - 2));
  const auto decoded = nlohmann::json::parse(literal, nullptr, false);
  return decoded.is_string() ? decoded.get<std::string>() : std::string();
}

JsonPath walk_json(std::string_view text, std::size_t limit, const JsonVisitor& visit) {
  std::vector<Frame> frames;
  JsonPath path;  // one step per frame with has_step set
  bool expect_key = false;

  auto visit_value = [&](std::size_t begin, std::size_t end) {
    return visit(JsonToken{false, false, begin, end}, path);
  };

  for (std::size_t i = skip_space(text, 0); i < text.size() && i < limit; i = skip_space(text, i)) {
    const std::size_t end = token_end(text, i);
    const char c = text[i];
    if (c == '{' || c == '[') {
      if (!visit_value(i, i + 1)) break;
      frames.push_back({c == '{', c == '[', {}});
      // In place, not `path = path + 0`: a copy per bracket made deep texts quadratic.
      if (c == '[') path.push_back({"", 0});
      expect_key = c == '{';
    } else if (c == '}' || c == ']') {
      if (!frames.empty()) {
        if (frames.back().has_step) path.pop_back();
        frames.pop_back();
      }
      expect_key = false;
    } else if (c == ',') {
      if (frames.empty()) {
        // A stray comma at the top level: nothing to track.
      } else if (!frames.back().object) {
        ++path.back().index;
      } else {
        // Between keys: the value just read is finished, the next key is not yet known.
        if (frames.back().has_step) path.pop_back();
        frames.back().has_step = false;
        expect_key = true;
      }
    } else if (c == ':') {
      expect_key = false;
    } else if (expect_key && c == '"' && !frames.empty() && frames.back().object) {
      Frame& frame = frames.back();
      if (frame.has_step) path.pop_back();
      std::string key = string_literal(text, i);
      const bool duplicate = !frame.keys.insert(key).second;
      path.push_back({std::move(key), -1});
      frame.has_step = true;
      expect_key = false;
      if (!visit(JsonToken{true, duplicate, i, end}, path)) break;
    } else {
      if (!visit_value(i, end)) break;
    }
    i = end;
  }
  return path;
}

std::size_t value_end(std::string_view text, std::size_t begin) {
  int depth = 0;
  for (std::size_t i = skip_space(text, begin); i < text.size(); i = skip_space(text, i)) {
    const char c = text[i];
    if (c == '{' || c == '[') ++depth;
    if (c == '}' || c == ']') --depth;
    i = token_end(text, i);
    if (depth <= 0) return i;
  }
  return text.size();
}

std::size_t nesting_too_deep(std::string_view text, int max_depth) {
  int depth = 0;
  for (std::size_t i = skip_space(text, 0); i < text.size();
       i = skip_space(text, token_end(text, i))) {
    if (text[i] == '{' || text[i] == '[') {
      if (++depth > max_depth) return i;
    } else if (text[i] == '}' || text[i] == ']') {
      // A stray closing bracket is the parser's to report; never let it hide deeper nesting.
      depth = std::max(depth - 1, 0);
    }
  }
  return std::string_view::npos;
}

std::size_t find_value(std::string_view text, const JsonPath& path) {
  std::size_t found = std::string_view::npos;
  walk_json(text, text.size(), [&](const JsonToken& token, const JsonPath& at) {
    if (!token.is_key && at == path) found = token.begin;
    return true;
  });
  return found;
}

}  // namespace pge

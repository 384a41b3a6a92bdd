// Positions in JSON text: which key path a byte offset lies in, and where a path's value starts.
//
// nlohmann::json reports a syntax error only as a byte offset, and its parsed values carry no
// positions at all. To name the body and field of every error, and the line of a bad value, we
// re-scan the text with this tiny tokenizer. It never validates: it must keep going through the
// malformed text that made the real parser fail.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace pge {

// One step of a path: an object key, or an array index when `index >= 0`.
struct PathStep {
  std::string key;
  int index = -1;
  bool operator==(const PathStep&) const = default;
};
using JsonPath = std::vector<PathStep>;

JsonPath operator+(JsonPath path, std::string key);
JsonPath operator+(JsonPath path, int index);

// Dotted form, e.g. "bodies[3].circle.radius"; keys are written as they are.
std::string dotted(const JsonPath& path, std::size_t from = 0);
// The inverse of `dotted` for paths whose keys contain no '.' or '['.
JsonPath parse_dotted(std::string_view text);

struct TextPosition {
  int line = 0;    // 1-based
  int column = 0;  // 1-based, in bytes
};
TextPosition text_position(std::string_view text, std::size_t offset);

// A key or value token met by `walk_json`. For objects and arrays `begin` is the bracket.
struct JsonToken {
  bool is_key = false;
  bool duplicate_key = false;  // the key already occurred in the same object
  std::size_t begin = 0;
  std::size_t end = 0;
};
// Called with every token and its path (for a key, the path ending in that key); return false to
// stop the walk.
using JsonVisitor = std::function<bool(const JsonToken&, const JsonPath&)>;

// Walks the tokens that begin before `limit` and returns the path in effect at `limit`: the
// path of the value being read there.
JsonPath walk_json(std::string_view text, std::size_t limit, const JsonVisitor& visit);

// The offset just past the value starting at `begin` (brackets matched, strings skipped).
std::size_t value_end(std::string_view text, std::size_t begin);

// The offset of the first '[' or '{' (outside strings) that opens more than `max_depth` nested
// levels; npos if none does. Linear on any text: the reader calls it before the parser, because
// nlohmann's serializer (describing a value in a message) recurses once per level and overflowed
// the stack at 100,000, and the path of an error that deep made a message of 300 KB.
std::size_t nesting_too_deep(std::string_view text, int max_depth);

// Where the value at `path` starts (the last one, as the parser keeps the last duplicate key);
// npos if absent.
std::size_t find_value(std::string_view text, const JsonPath& path);

// The decoded string literal starting at `begin`; empty if it is not a valid string literal.
std::string string_literal(std::string_view text, std::size_t begin);

}  // namespace pge

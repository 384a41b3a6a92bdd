// Diagnostics for JSON text shared by the scene and trace readers (json_text.hpp).
#include "json_text.hpp"

#include "pge/scene_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>

namespace pge {

std::string describe(const nlohmann::json& value) {
  return excerpt(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

// The whole run of non-separator characters around `offset`, e.g. "NaN" or "-Infinity".
std::string_view word_at(std::string_view text, std::size_t offset) {
  auto is_word = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  };
  std::size_t begin = std::min(offset, text.size());
  while (begin > 0 && is_word(text[begin - 1])) --begin;
  std::size_t end = begin;
  while (end < text.size() && is_word(text[end])) ++end;
  return text.substr(begin, end - begin);
}

bool is_nan_or_infinity(std::string_view word) {
  if (!word.empty() && (word[0] == '-' || word[0] == '+')) word.remove_prefix(1);
  std::string lower(word);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower == "nan" || lower == "inf" || lower == "infinity";
}

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix;
// the position is reported our way. The token it quotes ("last read: '...'") is cut: for an
// unclosed string it is the whole rest of the file.
std::string syntax_reason(const nlohmann::json::parse_error& error) {
  std::string_view what = error.what();
  if (const std::size_t start = what.find("syntax error"); start != std::string_view::npos)
    what.remove_prefix(start);
  constexpr std::string_view kLastRead = "last read: '";
  const std::size_t token = what.find(kLastRead);
  if (token == std::string_view::npos || what.back() != '\'') return std::string(what);
  const std::size_t begin = token + kLastRead.size();
  // What follows the token is nlohmann's own "; expected ..." or the closing quote alone.
  std::size_t end = what.rfind("'; expected ");
  if (end == std::string_view::npos || end < begin) end = what.size() - 1;
  return std::string(what.substr(0, begin)) + excerpt(what.substr(begin, end - begin)) +
         std::string(what.substr(end));
}

// A number literal that no double can hold: the parser rejects overflow without saying where,
// and silently turns a tiny non-zero number into 0. Empty if the literal is fine.
std::string number_problem(std::string_view literal) {
  double value = 0;
  const auto result = std::from_chars(literal.data(), literal.data() + literal.size(), value);
  if (result.ec != std::errc::result_out_of_range) return {};
  const bool tiny =
      literal.find("e-") != std::string_view::npos || literal.find("E-") != std::string_view::npos;
  return fmt::format(
      "number {} is out of range for a double ({})", excerpt(literal),
      tiny ? "it would read as 0; write 0 if that is meant" : "it would overflow to infinity");
}


std::optional<TokenProblem> token_problem(std::string_view text) {
  JsonToken bad;
  std::string reason;
  walk_json(text, text.size(), [&](const JsonToken& token, const JsonPath& path) {
    if (token.is_key && token.duplicate_key)
      reason = fmt::format("duplicate key \"{}\"", excerpt(path.back().key));
    else if (!token.is_key &&
             (text[token.begin] == '-' || std::isdigit(static_cast<unsigned char>(text[token.begin]))))
      reason = number_problem(text.substr(token.begin, token.end - token.begin));
    bad = token;
    return reason.empty();
  });
  if (reason.empty()) return std::nullopt;
  return TokenProblem{bad.is_key ? bad.end : bad.begin, reason};
}

}  // namespace pge

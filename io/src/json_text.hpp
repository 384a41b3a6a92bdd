// Diagnostics for JSON text that the scene and trace readers share: what nlohmann's parser
// rejects or accepts silently, said in one readable line.
#pragma once

#include "json_path.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace pge {

// A value as it would be written, cut to kMaxQuoted bytes (scene_io.hpp's excerpt).
std::string describe(const nlohmann::json& value);
// The whole run of non-separator characters around `offset`, e.g. "NaN" or "-Infinity".
std::string_view word_at(std::string_view text, std::size_t offset);
bool is_nan_or_infinity(std::string_view word);
// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix;
// the position is reported our way. The token it quotes ("last read: '...'") is cut: for an
// unclosed string it is the whole rest of the file.
std::string syntax_reason(const nlohmann::json::parse_error& error);
// A number literal that no double can hold: the parser rejects overflow without saying where,
// and silently turns a tiny non-zero number into 0. Empty if the literal is fine.
std::string number_problem(std::string_view literal);

// What the parser accepts silently but a file must not: the first duplicate key (the parser
// keeps the last, hiding the first) or number no double can hold, with where it is (a key's
// error belongs to the key's path, which is the path at its end: `offset` is there).
struct TokenProblem {
  std::size_t offset = 0;
  std::string reason;
};
std::optional<TokenProblem> token_problem(std::string_view text);

}  // namespace pge

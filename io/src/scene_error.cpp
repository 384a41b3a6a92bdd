#include "pge/scene_io.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace pge {
namespace {

// JSON string syntax: quotes and control characters in ids and keys stay visible and the
// message stays on one line; a long id or field (a huge key, a path 64 levels deep) is cut.
// The accessors keep the whole value.
std::string quoted(const std::string& s) {
  return nlohmann::json(excerpt(s)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string error_message(const SceneErrorPlace& place, const std::string& reason) {
  std::string message = place.file;
  if (place.line > 0) message += fmt::format(":{}:{}", place.line, place.column);
  message += ": ";
  if (place.body_index >= 0) {
    message += place.body_id.empty()
                   ? fmt::format("body bodies[{}]: ", place.body_index)
                   : fmt::format("body {} (bodies[{}]): ", quoted(place.body_id), place.body_index);
  }
  if (!place.field.empty()) message += fmt::format("field {}: ", quoted(place.field));
  message += reason;
  // One line per error, whatever a file name or a parser message holds: tools grep for these.
  std::replace_if(
      message.begin(), message.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return message;
}

}  // namespace

std::string excerpt(std::string_view text) {
  if (text.size() <= kMaxQuoted) return std::string(text);
  std::size_t cut = kMaxQuoted;
  // Back to the start of a UTF-8 sequence, so that the cut text stays valid UTF-8.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return std::string(text.substr(0, cut)) + "...";
}

SceneError::SceneError(SceneErrorPlace place, std::string reason)
    : std::runtime_error(error_message(place, reason)),
      place_(std::move(place)),
      reason_(std::move(reason)) {}

SceneError::SceneError(const std::string& file, std::string reason)
    : SceneError(SceneErrorPlace{file, 0, 0, -1, "", ""}, std::move(reason)) {}

}  // namespace pge

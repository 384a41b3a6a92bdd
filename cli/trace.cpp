#include "trace.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace pge::cli {

TraceWriter::~TraceWriter() {
  if (file_) std::fclose(file_);
}

bool TraceWriter::open(const std::string& path) {
  path_ = path;
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) error_ = std::strerror(errno);
  return file_ != nullptr;
}

bool TraceWriter::close() {
  if (!file_) return false;
  const bool failed = std::ferror(file_) != 0;
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (failed || closed != 0) {
    error_ = failed ? "write error" : std::strerror(errno);
    return false;
  }
  return true;
}

void TraceWriter::header(const Scene& scene, std::string_view scalar, std::string_view solver, double horizon) {
  rotating_ = std::any_of(scene.bodies.begin(), scene.bodies.end(), [](const BodyDesc& b) { return b.rotates; });
  fmt::print(file_, "{{\"format\":\"pge-trace/2\",\"mode\":\"events\",\"scene\":{},\"scalar\":\"{}\",\"solver\":\"{}\",\"until\":{},"
             "\"bodies\":[",
             quoted(scene.name), scalar, solver, horizon);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) fmt::print(file_, "{}{}", i ? "," : "", quoted(scene.bodies[i].id));
  fmt::print(file_, "]}}\n");
}

std::string json_quoted(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

}  // namespace pge::cli

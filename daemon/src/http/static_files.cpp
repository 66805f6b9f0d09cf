#include "static_files.hpp"

#include <sys/stat.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

namespace kew::daemon::http {

namespace {

namespace fs = std::filesystem;

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// Percent-decodes `in`; nullopt on a malformed escape or a decoded NUL or backslash.
std::optional<std::string> percent_decode(std::string_view in) {
  std::string out;
  out.reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    char c = in[i];
    if (c == '%') {
      if (i + 2 >= in.size()) return std::nullopt;
      const int hi = hex_value(in[i + 1]), lo = hex_value(in[i + 2]);
      if (hi < 0 || lo < 0) return std::nullopt;
      c = static_cast<char>(hi * 16 + lo);
      i += 2;
    }
    if (c == '\0' || c == '\\') return std::nullopt;
    out.push_back(c);
  }
  return out;
}

}  // namespace

StaticResult StaticFiles::read(std::string_view path, StaticFile& file) const {
  if (root_.empty() || path.empty() || path.front() != '/') return StaticResult::NotFound;
  std::optional<std::string> decoded = percent_decode(path);
  if (!decoded) return StaticResult::Forbidden;
  std::string relative = decoded->substr(1);
  if (relative.empty() || relative.back() == '/') relative += "index.html";
  // Lexically: no segment may be "..", "." or empty, so nothing outside the root is named.
  std::size_t start = 0;
  while (start <= relative.size()) {
    const std::size_t end = std::min(relative.find('/', start), relative.size());
    const std::string_view segment(relative.data() + start, end - start);
    if (segment.empty() || segment == "." || segment == "..") return StaticResult::Forbidden;
    start = end + 1;
  }
  const std::string full = root_ + "/" + relative;
  struct stat st {};
  if (::stat(full.c_str(), &st) != 0) return StaticResult::NotFound;
  if (S_ISDIR(st.st_mode)) return read(std::string(path) + "/", file);
  if (!S_ISREG(st.st_mode)) return StaticResult::Forbidden;
  if (static_cast<std::size_t>(st.st_size) > kMaxFileBytes) return StaticResult::TooLarge;
  std::ifstream in(full, std::ios::binary);
  if (!in) return StaticResult::Forbidden;
  file.body.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  file.content_type = std::string(content_type(relative));
  return StaticResult::Found;
}

std::string_view content_type(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 16> kTypes{{
      {".html", "text/html; charset=utf-8"},
      {".htm", "text/html; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".json", "application/json"},
      {".geojson", "application/geo+json"},
      {".map", "application/json"},
      {".svg", "image/svg+xml"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".ico", "image/x-icon"},
      {".txt", "text/plain; charset=utf-8"},
      {".woff2", "font/woff2"},
      {".webp", "image/webp"},
      {".gif", "image/gif"},
  }};
  for (const auto& [extension, type] : kTypes)
    if (name.size() >= extension.size() && name.substr(name.size() - extension.size()) == extension) return type;
  return "application/octet-stream";
}

std::string default_web_root() {
  // A kewd under the build directory is a developer's: it serves the files being edited.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const std::string build_dir = KEW_BUILD_DIR;
  if (!ec && exe.string().rfind(build_dir + "/", 0) == 0) return KEW_SOURCE_WEB_ROOT;
  return KEW_INSTALLED_WEB_ROOT;
}

}  // namespace kew::daemon::http

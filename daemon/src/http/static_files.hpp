#pragma once
// The files of the map (design §5.8): only regular files under a root, found by a path
// that names no parent directory, with the content type of their extension.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace kew::daemon::http {

struct StaticFile {
  std::string content_type;
  std::string body;
};

enum class StaticResult { Found, NotFound, Forbidden, TooLarge };

class StaticFiles {
 public:
  /// `root`: a directory ("" serves nothing).
  explicit StaticFiles(std::string root) : root_(std::move(root)) {}
  /// `path`: the request target's path below the mount point, percent-encoded, starting
  /// with '/'; "/" and a path ending in '/' mean its index.html.
  StaticResult read(std::string_view path, StaticFile& file) const;
  const std::string& root() const { return root_; }

  /// Larger files are not served (the map's files are small; this bounds one reply).
  static constexpr std::size_t kMaxFileBytes = 16u << 20;

 private:
  std::string root_;
};

/// The content type of a file name by its extension; application/octet-stream if unknown.
std::string_view content_type(std::string_view name);

/// The map's directory when [http] web_root is "": the installed share/kew/web, or the
/// source tree's web/ when this kewd runs from its build tree.
std::string default_web_root();

}  // namespace kew::daemon::http

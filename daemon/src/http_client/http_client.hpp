#pragma once
// kewd's HTTP(S) client (design §5.7): one request at a time on the calling thread,
// through libcurl (Debian's libcurl4-openssl-dev; TLS, redirects, gzip and deflate,
// keep-alive, timeouts, certificate checks are libcurl's). The poll input reads
// receivers' and aggregators' JSON with it; OAuth2 tokens are fetched with it.
//
// A body is never larger than HttpRequest::max_body_bytes, counted after decompression,
// so a small compressed answer cannot unpack into gigabytes: the transfer is cut off and
// the result is HttpOutcome::TooLarge.

#include <atomic>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kew/util/name_table.hpp"

namespace kew::daemon {

enum class HttpMethod { Get, Post };

struct HttpRequest {
  std::string url;  ///< http:// or https://
  HttpMethod method = HttpMethod::Get;
  std::vector<std::string> headers;  ///< "Name: value" each
  std::string body;                  ///< Post: sent as is (give its Content-Type in headers)
  /// Connecting (name lookup, TCP, TLS handshake) and the whole transfer, seconds (> 0).
  double connect_timeout_s = 5.0;
  double timeout_s = 10.0;
  /// Largest body taken, bytes after decompression (> 0).
  std::size_t max_body_bytes = 32u << 20;
  /// Certificates of the authorities trusted besides the system's (PEM file); "" none.
  std::string ca_file;
  /// HTTP basic authentication, "user:password"; "" none.
  std::string basic_credentials;
};

enum class HttpOutcome {
  Answered,  ///< the server answered (any status; HttpResponse::status says which)
  TooLarge,  ///< the body passed max_body_bytes; the transfer was cut off
  Failed,    ///< no answer: name lookup, connection, TLS, timeout, a broken transfer
  Aborted,   ///< the caller's abort flag was raised during the transfer
};
inline constexpr util::NameTable<HttpOutcome, 4> kHttpOutcomeNames({{
    {HttpOutcome::Answered, "answered"},
    {HttpOutcome::TooLarge, "too_large"},
    {HttpOutcome::Failed, "failed"},
    {HttpOutcome::Aborted, "aborted"},
}});

struct HttpResponse {
  HttpOutcome outcome = HttpOutcome::Failed;
  long status = 0;  ///< HTTP status of the last answer (after redirects); 0 without one
  std::string body;
  /// Failed and TooLarge: what went wrong, for the log.
  std::string error;
  /// The headers of the last answer, names in lower case, values trimmed.
  std::vector<std::pair<std::string, std::string>> headers;

  /// The value of header `lower_case_name`, or nullopt.
  std::optional<std::string_view> header(std::string_view lower_case_name) const;
  /// How long the server asks to wait before the next request, seconds: Retry-After
  /// (seconds or an HTTP date) or OpenSky's X-Rate-Limit-Retry-After-Seconds; nullopt
  /// when neither is there or readable. `now_unix_s` dates an HTTP date's wait.
  std::optional<double> retry_after_s(double now_unix_s) const;
};

class HttpClient {
 public:
  HttpClient();
  ~HttpClient();
  HttpClient(const HttpClient&) = delete;
  HttpClient& operator=(const HttpClient&) = delete;

  /// Performs `request`, blocking until it is answered, fails, or `abort` (when given)
  /// becomes true (checked several times a second). Connections are kept for the next
  /// request to the same server.
  HttpResponse perform(const HttpRequest& request, const std::atomic<bool>* abort = nullptr);

 private:
  void* curl_;  // libcurl's easy handle, kept for its connection cache
};

}  // namespace kew::daemon

#include "credentials.hpp"

#include <sys/stat.h>

#include <cctype>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <curl/curl.h>
#include <fmt/format.h>
#include <simdjson.h>

namespace kew::daemon {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string form_escape(const std::string& value) {
  const std::unique_ptr<char, decltype(&curl_free)> escaped(
      curl_easy_escape(nullptr, value.c_str(), static_cast<int>(value.size())), curl_free);
  if (!escaped) throw std::bad_alloc();
  return escaped.get();
}

// Tokens are renewed this long before they expire, so that none expires in flight.
constexpr double kRenewBeforeS = 60.0;

}  // namespace

std::string read_secret_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(fmt::format("cannot read the secret file {}", path));
  std::ostringstream text;
  text << file.rdbuf();
  const std::string_view secret = trim(text.view());
  if (secret.empty()) throw std::runtime_error(fmt::format("the secret file {} is empty", path));
  if (secret.find_first_of("\r\n") != std::string_view::npos && secret.front() != '{')
    throw std::runtime_error(fmt::format("the secret file {} holds more than one line", path));
  return std::string(secret);
}

std::optional<std::string> secret_file_exposure(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return std::nullopt;
  if ((info.st_mode & S_IROTH) == 0) return std::nullopt;
  return fmt::format("the secret file {} may be read by every user (mode {:o}): chmod o-r it", path,
                     info.st_mode & 07777);
}

Credentials parse_credentials(std::string_view text) {
  text = trim(text);
  Credentials c;
  if (!text.empty() && text.front() == '{') {
    simdjson::dom::parser parser;
    simdjson::dom::element document;
    if (parser.parse(text.data(), text.size()).get(document) != simdjson::SUCCESS)
      throw std::invalid_argument("credentials: not JSON");
    std::string_view id, secret;
    if (document["clientId"].get(id) != simdjson::SUCCESS || document["clientSecret"].get(secret) != simdjson::SUCCESS ||
        id.empty() || secret.empty())
      throw std::invalid_argument("credentials: a JSON credentials file needs clientId and clientSecret (strings)");
    c.client_id = id;
    c.client_secret = secret;
    return c;
  }
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos || colon == 0 || text.find_first_of("\r\n") != std::string_view::npos)
    throw std::invalid_argument(
        "credentials: neither {\"clientId\": ..., \"clientSecret\": ...} nor one line user:password");
  c.basic = text;
  return c;
}

BearerToken::BearerToken(std::string token_url, Credentials credentials, std::string ca_file, double timeout_s)
    : token_url_(std::move(token_url)),
      credentials_(std::move(credentials)),
      ca_file_(std::move(ca_file)),
      timeout_s_(timeout_s) {}

std::optional<std::string> BearerToken::header(HttpClient& client, double now_s, std::string& error,
                                               const std::atomic<bool>* abort) {
  if (token_.empty() || now_s + kRenewBeforeS >= expires_at_s_) {
    token_.clear();
    HttpRequest request;
    request.url = token_url_;
    request.method = HttpMethod::Post;
    request.headers = {"Content-Type: application/x-www-form-urlencoded", "Accept: application/json"};
    request.body = "grant_type=client_credentials&client_id=" + form_escape(credentials_.client_id) +
                   "&client_secret=" + form_escape(credentials_.client_secret);
    request.timeout_s = timeout_s_;
    request.ca_file = ca_file_;
    request.max_body_bytes = 1 << 20;
    const HttpResponse response = client.perform(request, abort);
    if (response.outcome != HttpOutcome::Answered) {
      error = fmt::format("token server {}: {}", token_url_, response.error);
      return std::nullopt;
    }
    if (response.status != 200) {
      error = fmt::format("token server {}: HTTP {}", token_url_, response.status);
      return std::nullopt;
    }
    simdjson::dom::parser parser;
    simdjson::dom::element document;
    std::string_view token;
    double expires_in = 0;
    if (parser.parse(response.body).get(document) != simdjson::SUCCESS ||
        document["access_token"].get(token) != simdjson::SUCCESS || token.empty()) {
      error = fmt::format("token server {}: no access_token in its answer", token_url_);
      return std::nullopt;
    }
    if (document["expires_in"].get(expires_in) != simdjson::SUCCESS) {
      std::int64_t whole = 0;
      expires_in = document["expires_in"].get(whole) == simdjson::SUCCESS ? static_cast<double>(whole) : 300.0;
    }
    token_ = token;
    expires_at_s_ = now_s + expires_in;
  }
  return "Authorization: Bearer " + token_;
}

}  // namespace kew::daemon

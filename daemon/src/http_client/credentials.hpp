#pragma once
// Secrets for HTTP servers (design §5.7), always read from files the operator protects
// (mode 0640, owner root, group kew), never from the configuration, which is world
// readable and copied into bug reports:
// - an API key sent as one header (`secret_header`, `secret_file`: an aggregator's key);
// - credentials (`credentials_file`): either OpenSky's credentials.json as its account
//   page hands it out, {"clientId": "...", "clientSecret": "..."}, for the OAuth2
//   client-credentials flow (a bearer token fetched from `token_url`, renewed before it
//   expires and after a 401), or one line "user:password" for HTTP basic authentication.

#include <atomic>
#include <optional>
#include <string>
#include <string_view>

#include "http_client.hpp"

namespace kew::daemon {

/// OpenSky Network's token endpoint (OAuth2 client credentials; required by its REST API
/// since 18 March 2026: https://github.com/openskynetwork/opensky-api, "Authentication").
inline constexpr std::string_view kOpenskyTokenUrl =
    "https://auth.opensky-network.org/auth/realms/opensky-network/protocol/openid-connect/token";

/// The text of a secret file, without the blanks and newlines round it. Throws
/// std::runtime_error naming the file (never its contents) when it cannot be read or
/// holds nothing.
std::string read_secret_file(const std::string& path);

/// A warning for the log when users other than the owner and group may read `path`;
/// nullopt when they cannot (or its mode cannot be read: read_secret_file says so).
std::optional<std::string> secret_file_exposure(const std::string& path);

struct Credentials {
  std::string basic;  ///< "user:password"; empty with OAuth2
  std::string client_id;
  std::string client_secret;
  bool oauth2() const { return !client_id.empty(); }
};

/// Credentials from a credentials file's text. Throws std::invalid_argument (the message
/// never quotes the text) when it is neither form.
Credentials parse_credentials(std::string_view text);

/// An OAuth2 client-credentials bearer token (RFC 6749 §4.4), fetched when needed.
class BearerToken {
 public:
  BearerToken(std::string token_url, Credentials credentials, std::string ca_file, double timeout_s);

  /// "Authorization: Bearer …" for a request at `now_s` (a steady clock, seconds): the
  /// token held, or a new one when none is held or it expires within a minute. nullopt,
  /// with `error` saying why, when the token server does not give one.
  std::optional<std::string> header(HttpClient& client, double now_s, std::string& error,
                                    const std::atomic<bool>* abort = nullptr);
  /// Drops the token (the server refused it: 401); the next header() fetches another.
  void forget() { token_.clear(); }

 private:
  std::string token_url_;
  Credentials credentials_;
  std::string ca_file_;
  double timeout_s_;
  std::string token_;
  double expires_at_s_ = 0;
};

}  // namespace kew::daemon

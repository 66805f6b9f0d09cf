#pragma once
// NATS server URLs as configurations name them ([nats] url and servers, a NATS input's
// nats_url and nats_servers, kew-watch --nats, kew-replay --to nats://): checked here,
// so that a file that passes kewd --check-config names servers the NATS C client can
// reach, and handed to the client as a list (design §5.9).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kew::config {

/// NATS's own port, the client's when a URL names none.
inline constexpr unsigned kDefaultNatsPort = 4222;

/// Whether `url` is one server as the NATS C client takes it: "nats://HOST:PORT" or
/// "tls://HOST:PORT", optionally with "USER:PASSWORD@" or "TOKEN@" before HOST, with
/// HOST:PORT as parse_host_port (address.hpp) reads it; without ":PORT" the port is
/// kDefaultNatsPort. On false, `*error` (when given) quotes the URL and says what is wrong.
bool valid_nats_server(std::string_view url, std::string* error = nullptr);

/// A list of servers written as one string, "nats://h1:4222,nats://h2:4222" (white space
/// around the commas allowed), or one server: each checked with valid_nats_server.
/// Returns nullopt when the text is empty or any entry is malformed (with `*error`).
std::optional<std::vector<std::string>> parse_nats_servers(std::string_view text, std::string* error = nullptr);

/// The servers as one comma-separated string (for messages and logs).
std::string join_nats_servers(const std::vector<std::string>& servers);

}  // namespace kew::config

// libFuzzer target: any bytes as the frames a WebSocket client sends on /ws after a valid
// upgrade (design §5.8): Beast's frame reader with kewd's limits (1 KiB messages, pings,
// close), and WebSocketSession's answers (a client message, a broken frame or a close all
// end the connection). The server must complete the handshake, send the snapshot, end
// the connection and forget it once the client has gone (http_fuzz_harness.hpp).

#include "http_fuzz_harness.hpp"

namespace {
constexpr std::string_view kUpgrade =
    "GET /ws HTTP/1.1\r\nHost: localhost\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
    "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static kew::daemon::http::fuzz::LoopbackServer server;
  const std::string reply = server.exchange(kUpgrade, {reinterpret_cast<const char*>(data), size});
  if (reply.rfind("HTTP/1.1 101 ", 0) != 0) std::abort();  // the upgrade itself is valid
  return 0;
}

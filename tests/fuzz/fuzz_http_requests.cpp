// libFuzzer target: any bytes as what an HTTP client sends to kewd's HTTP server (design
// §5.8): Beast's parser within kewd's header, body and time limits, the Router (files,
// JSON API, POST /api/ack with its body, /metrics, refusals), keep-alive and pipelined
// requests, an upgrade to /ws ("$PORT" in an input is the server's port, so that Host and
// Origin can name it). The server must answer with HTTP or close, and forget the
// connection once the client has gone (http_fuzz_harness.hpp).

#include "http_fuzz_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static kew::daemon::http::fuzz::LoopbackServer server;
  const std::string reply = server.exchange({}, {reinterpret_cast<const char*>(data), size});
  if (!reply.empty() && reply.rfind("HTTP/1.1 ", 0) != 0) std::abort();  // only HTTP comes back
  return 0;
}

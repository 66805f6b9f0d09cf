#pragma once
// `[[input]] transport = "http"` (design §5.7): an HTTP(S) URL read again every
// poll_interval_s — tar1090's /data/aircraft.json, an aggregator's area query, OpenSky's
// /api/states/all — each answer one message of the input's format, so a snapshot
// decoder reports only the positions the earlier answers did not show. Requests are
// conditional (If-None-Match, If-Modified-Since: an unchanged file costs a 304), ask for
// gzip, carry an API key or credentials read from files, and time out; a failure backs
// off (reconnect_min_s doubling to reconnect_max_s, longer when the server says
// Retry-After) and is counted and logged (rate-limited). The requests run on a thread of
// their own (libcurl blocks); answers are decoded on the I/O thread, one at a time.

#include <memory>

#include <boost/asio/io_context.hpp>

#include "inputs.hpp"

namespace kew::daemon {

/// Throws std::runtime_error when a secret or credentials file cannot be read.
std::unique_ptr<Input> make_http_poll_input(boost::asio::io_context& io, const InputConfig& config,
                                            const protocol::DecoderOptions& options, Input::ReportHandler handler);

}  // namespace kew::daemon

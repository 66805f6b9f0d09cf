#pragma once
// `[[input]] transport = "nats"` (design §5.9): one NATS message is one datagram or line
// batch of the input's format. A plain subscription takes what is published while kewd
// listens; with `durable`, a JetStream pull consumer of that name reads the subject's
// stream, so a restarted kewd resumes after the last message it took.

#include <memory>

#include <boost/asio/io_context.hpp>

#include "inputs.hpp"

namespace kew::daemon {

std::unique_ptr<Input> make_nats_input(boost::asio::io_context& io, const InputConfig& config,
                                       const protocol::DecoderOptions& options, Input::ReportHandler handler);

}  // namespace kew::daemon

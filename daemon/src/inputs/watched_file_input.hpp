#pragma once
// `[[input]] transport = "watched-file"`: a file its writer replaces whole, read again
// each time it is (design §5.7): a receiver's aircraft.json (readsb writes
// /run/readsb/aircraft.json once a second by writing a temporary file and renaming it;
// dump1090-fa, dump1090-mutability and tar1090 likewise). Each version is one message
// of the input's format (Input::feed_message), so the aircraft.json decoder reports only
// the positions the last versions did not show.

#include <memory>

#include <boost/asio/io_context.hpp>

#include "inputs.hpp"

namespace kew::daemon {

std::unique_ptr<Input> make_watched_file_input(boost::asio::io_context& io, const InputConfig& config,
                                               const protocol::DecoderOptions& options,
                                               Input::ReportHandler handler);

}  // namespace kew::daemon

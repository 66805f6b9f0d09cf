#include "cat004_output.hpp"

#include "kew/util/clocks.hpp"

namespace kew::daemon {

void Cat004Output::alive(const AliveEvent& alive, const SharedLine&) {
  protocol::Cat004Alive message;
  // Before the first record the data clock means nothing: the wall clock stands in.
  message.t = alive.status.last_data_t ? alive.data_clock_t : util::unix_now_s();
  message.degraded = alive.status.degraded();
  message.apw = area_warning_;
  sender_.send_alive(message);
}

}  // namespace kew::daemon

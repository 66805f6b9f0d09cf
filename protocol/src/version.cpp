#include "kew/protocol/version.hpp"

namespace kew::protocol {

std::string_view release() { return KEW_RELEASE; }

}  // namespace kew::protocol

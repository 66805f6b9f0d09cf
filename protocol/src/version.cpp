#include "kew/protocol/version.hpp"

#include "kew_revision.h"  // generated at build time (cmake/kew_revision.cmake)

namespace kew::protocol {

std::string_view release() { return KEW_RELEASE; }

std::string_view revision() { return KEW_REVISION; }

std::string version_line(std::string_view tool) {
  std::string line(tool);
  line += ' ';
  line += release();
  line += " (";
  line += revision();
  line += ')';
  return line;
}

}  // namespace kew::protocol

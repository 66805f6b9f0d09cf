#include "kew/config/nats_subject.hpp"

namespace kew::config {

bool valid_nats_subject(std::string_view subject, bool wildcards) {
  if (subject.empty()) return false;
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = subject.find('.', start);
    const bool last = dot == std::string_view::npos;
    const std::string_view token = subject.substr(start, last ? std::string_view::npos : dot - start);
    if (token.empty()) return false;
    for (const char c : token) {
      if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f) return false;
      if ((c == '*' || c == '>') && (!wildcards || token.size() != 1)) return false;
    }
    if (token == ">" && !last) return false;
    if (last) return true;
    start = dot + 1;
  }
}

std::string nats_subject_token(std::string_view name) {
  if (name.empty()) return "_";
  std::string token(name);
  for (char& c : token)
    if (c == '.' || c == '*' || c == '>' || c == '/' || c == '+' || c == '#' || static_cast<unsigned char>(c) <= 0x20)
      c = '_';
  return token;
}

}  // namespace kew::config

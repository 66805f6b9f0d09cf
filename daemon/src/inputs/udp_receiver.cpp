#include "udp_receiver.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

namespace kew::daemon {

UdpReceiver::UdpReceiver(int fd) : fd_(fd) {
  const int on = 1;
  if (::setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) != 0)
    throw std::system_error(errno, std::generic_category(), "setsockopt(SO_RXQ_OVFL)");
}

UdpReceiver::Outcome UdpReceiver::receive(std::span<char> buffer, std::size_t& bytes) {
  iovec data{buffer.data(), buffer.size()};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(std::uint32_t))];
  msghdr message{};
  message.msg_iov = &data;
  message.msg_iovlen = 1;
  message.msg_control = control;
  message.msg_controllen = sizeof control;
  const ssize_t n = ::recvmsg(fd_, &message, MSG_DONTWAIT);
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK ? Outcome::Empty : Outcome::Failed;
  read_drop_count(message);
  if ((message.msg_flags & MSG_TRUNC) != 0) return Outcome::Truncated;
  bytes = static_cast<std::size_t>(n);
  return Outcome::Datagram;
}

void UdpReceiver::read_drop_count(msghdr& message) {
  for (cmsghdr* c = CMSG_FIRSTHDR(&message); c != nullptr; c = CMSG_NXTHDR(&message, c)) {
    if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SO_RXQ_OVFL) continue;
    std::uint32_t count = 0;
    std::memcpy(&count, CMSG_DATA(c), sizeof count);
    // Unsigned difference: right across the kernel counter's wrap.
    dropped_ += static_cast<std::uint32_t>(count - kernel_count_);
    kernel_count_ = count;
  }
}

}  // namespace kew::daemon

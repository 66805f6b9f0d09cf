#pragma once
// Reads a UDP socket's datagrams with recvmsg(2) and learns how many the kernel dropped
// for it. A feed faster than kewd reads fills the socket's receive buffer, and the kernel
// then discards datagrams without telling the reader: SO_RXQ_OVFL makes it attach its
// running count of the socket's drops to each datagram it queues afterwards.

#include <cstddef>
#include <cstdint>
#include <span>
#include <sys/socket.h>

namespace kew::daemon {

class UdpReceiver {
 public:
  /// Asks the kernel for the drop count of `fd`, a UDP socket the caller keeps open
  /// while this object reads it. Throws std::system_error when the kernel refuses.
  explicit UdpReceiver(int fd);

  enum class Outcome {
    Datagram,   ///< a datagram was read; `bytes` holds its length
    Truncated,  ///< a datagram longer than the buffer was read and discarded
    Empty,      ///< none waiting
    Failed,     ///< recvmsg failed (errno tells why); the socket stays usable
  };
  /// Reads one waiting datagram into `buffer` without blocking.
  Outcome receive(std::span<char> buffer, std::size_t& bytes);

  /// Datagrams the kernel dropped for this socket since it was opened, as far as the
  /// datagrams read so far tell: the count comes with the first datagram queued after
  /// a drop.
  std::uint64_t dropped() const { return dropped_; }

 private:
  /// Takes the drop count from the control messages of one datagram, if there.
  void read_drop_count(msghdr& message);

  int fd_;
  std::uint32_t kernel_count_ = 0;  // the last cumulative count seen (the kernel's wraps at 2^32)
  std::uint64_t dropped_ = 0;
};

}  // namespace kew::daemon

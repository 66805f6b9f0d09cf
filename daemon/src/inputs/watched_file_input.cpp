#include "watched_file_input.hpp"

#include <sys/inotify.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace kew::daemon {

namespace {

namespace asio = boost::asio;

// Without a notification (a file system inotify does not watch, a writer that rewrites
// in place without closing), the file is looked at this often.
constexpr auto kPollPeriod = std::chrono::seconds(5);

class WatchedFileInput final : public Input {
 public:
  WatchedFileInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)),
        io_(io),
        notifications_(io),
        poll_(io),
        path_(config_.address),
        name_(path_.filename().string()) {
    decoder_ = make_stream_decoder();
  }
  ~WatchedFileInput() override { close_watch(); }

  void start() override {
    watch();
    read_if_changed();
    schedule_poll();
  }
  void stop() override {
    stopped_ = true;
    poll_.cancel();
    close_watch();
    if (decoder_) retire(*decoder_);
  }

 private:
  void add_open_stream_rejections(Rejections& out) const override {
    if (decoder_ && !stopped_) out.merge(decoder_->rejections());
  }

  // The directory is watched, not the file: a rename puts another file under the name
  // (IN_MOVED_TO); a writer that rewrites it in place is read once it closes the file
  // (IN_CLOSE_WRITE), never half written.
  void watch() {
    const int fd = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (fd < 0) {
      spdlog::warn("input {}: no inotify ({}): {} is looked at every {} s", config_.name, std::strerror(errno),
                   path_.string(), kPollPeriod.count());
      return;
    }
    const std::string directory = path_.parent_path().empty() ? "." : path_.parent_path().string();
    if (::inotify_add_watch(fd, directory.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO) < 0) {
      spdlog::warn("input {}: cannot watch {} ({}): {} is looked at every {} s", config_.name, directory,
                   std::strerror(errno), path_.string(), kPollPeriod.count());
      ::close(fd);
      return;
    }
    notifications_.assign(fd);
    wait_for_notification();
  }

  void close_watch() {
    boost::system::error_code ignored;
    if (notifications_.is_open()) notifications_.close(ignored);
  }

  void wait_for_notification() {
    notifications_.async_read_some(asio::buffer(events_), [this](const boost::system::error_code& ec, std::size_t n) {
      if (ec || stopped_) return;
      bool ours = false;
      for (std::size_t at = 0; at + sizeof(inotify_event) <= n;) {
        const auto* event = reinterpret_cast<const inotify_event*>(events_.data() + at);
        if (event->len > 0 && name_ == event->name) ours = true;
        at += sizeof(inotify_event) + event->len;
      }
      if (ours) read_if_changed();
      wait_for_notification();
    });
  }

  void schedule_poll() {
    poll_.expires_after(kPollPeriod);
    poll_.async_wait([this](const boost::system::error_code& ec) {
      if (ec || stopped_) return;
      read_if_changed();
      schedule_poll();
    });
  }

  // A version is read once: its modification time and size tell it from the last one.
  void read_if_changed() {
    std::error_code error;
    const auto status = std::filesystem::status(path_, error);
    if (error || !std::filesystem::is_regular_file(status)) {
      if (!missing_reported_) {
        spdlog::warn("input {}: {} is not there (yet)", config_.name, path_.string());
        missing_reported_ = true;
      }
      return;
    }
    missing_reported_ = false;
    const auto modified = std::filesystem::last_write_time(path_, error);
    const auto size = std::filesystem::file_size(path_, error);
    if (error || (modified == last_modified_ && size == last_size_)) return;
    if (size > decoder_->max_message_bytes()) {
      decoder_->rejections().reject("object_too_long", fmt::format("{}: {} bytes, more than {}", path_.string(), size,
                                                                   decoder_->max_message_bytes()));
      last_modified_ = modified;
      last_size_ = size;
      return;
    }
    std::string bytes;
    if (std::FILE* file = std::fopen(path_.c_str(), "rb")) {
      std::array<char, 65536> chunk;
      for (std::size_t n; (n = std::fread(chunk.data(), 1, chunk.size(), file)) > 0;) bytes.append(chunk.data(), n);
      std::fclose(file);
    } else {
      decoder_->rejections().reject("file_unreadable", fmt::format("{}: {}", path_.string(), std::strerror(errno)));
      return;
    }
    last_modified_ = modified;
    last_size_ = size;
    ++versions_;
    feed_message(*decoder_, bytes.data(), bytes.size());
  }

  asio::io_context& io_;
  asio::posix::stream_descriptor notifications_;
  asio::steady_timer poll_;
  std::filesystem::path path_;
  std::string name_;
  std::unique_ptr<protocol::Decoder> decoder_;
  std::array<char, 4096> events_{};
  std::filesystem::file_time_type last_modified_{};
  std::uintmax_t last_size_ = 0;
  std::uint64_t versions_ = 0;
  bool missing_reported_ = false;
  bool stopped_ = false;
};

}  // namespace

std::unique_ptr<Input> make_watched_file_input(asio::io_context& io, const InputConfig& config,
                                               const protocol::DecoderOptions& options, Input::ReportHandler handler) {
  return std::make_unique<WatchedFileInput>(io, config, options, std::move(handler));
}

}  // namespace kew::daemon

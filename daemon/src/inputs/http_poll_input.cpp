#include "http_poll_input.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <boost/asio/post.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "credentials.hpp"
#include "http_client.hpp"
#include "repeated_failure.hpp"
#include "retry_schedule.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon {

namespace {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;


class HttpPollInput final : public Input {
 public:
  HttpPollInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)),
        io_(io),
        failures_("input " + config_.name) {
    decoder_ = make_stream_decoder();
    request_.url = config_.address;
    request_.timeout_s = config_.timeout_s;
    request_.connect_timeout_s = std::min(config_.timeout_s, 10.0);
    request_.max_body_bytes = std::min(config_.max_response_bytes, decoder_->max_message_bytes());
    request_.ca_file = config_.ca_file;
    request_.headers = config_.headers;
    if (!config_.secret_file.empty()) {
      warn_if_exposed(config_.secret_file);
      request_.headers.push_back(config_.secret_header + ": " + read_secret_file(config_.secret_file));
    }
    if (!config_.credentials_file.empty()) {
      warn_if_exposed(config_.credentials_file);
      Credentials credentials;
      try {
        credentials = parse_credentials(read_secret_file(config_.credentials_file));
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error(fmt::format("{} ({})", e.what(), config_.credentials_file));
      }
      if (credentials.oauth2()) {
        token_.emplace(config_.token_url.empty() ? std::string(kOpenskyTokenUrl) : config_.token_url,
                       std::move(credentials), config_.ca_file, config_.timeout_s);
      } else {
        request_.basic_credentials = credentials.basic;
      }
    }
  }
  ~HttpPollInput() override { halt(); }

  void start() override {
    worker_ = std::thread([this] { poll(); });
  }
  void stop() override {
    halt();
    stopped_ = true;
    if (decoder_) retire(*decoder_);
  }

 private:
  void warn_if_exposed(const std::string& path) {
    if (const auto warning = secret_file_exposure(path)) spdlog::warn("input {}: {}", config_.name, *warning);
  }

  void halt() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    abort_ = true;
    changed_.notify_all();
    if (worker_.joinable()) worker_.join();
  }

  void add_open_stream_rejections(Rejections& out) const override {
    if (decoder_ && !stopped_) out.merge(decoder_->rejections());
  }
  void add_live_figures(protocol::InputStatistics& s) const override {
    s.polls = polls_.load();
    s.polls_unchanged = unchanged_.load();
    s.poll_failures = poll_failures_.load();
  }

  // The worker thread: a request, then a wait until the next is due.
  void poll() {
    RetrySchedule schedule(config_.poll_interval_s, config_.reconnect_min_s, config_.reconnect_max_s);
    for (;;) {
      const Clock::time_point started = Clock::now();
      const std::optional<double> wait_s = poll_once(schedule);
      if (!wait_s) return;
      std::unique_lock lock(mutex_);
      const auto due = started + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(*wait_s));
      if (changed_.wait_until(lock, due, [this] { return stopping_; })) return;
    }
  }

  // One request and what follows from its answer: the wait before the next (s), nullopt
  // when the input stops.
  std::optional<double> poll_once(RetrySchedule& schedule) {
    HttpRequest request = request_;
    if (!etag_.empty()) request.headers.push_back("If-None-Match: " + etag_);
    if (!last_modified_.empty()) request.headers.push_back("If-Modified-Since: " + last_modified_);
    if (token_) {
      std::string error;
      const std::optional<std::string> authorization = token_->header(client_, util::steady_now_s(), error, &abort_);
      if (abort_) return std::nullopt;
      if (!authorization) return failed(schedule, error, std::nullopt);
      request.headers.push_back(*authorization);
    }
    HttpResponse response = client_.perform(request, &abort_);
    const std::optional<double> retry_after = response.retry_after_s(util::unix_now_s());
    switch (response.outcome) {
      case HttpOutcome::Aborted: return std::nullopt;
      case HttpOutcome::TooLarge:
      case HttpOutcome::Failed: return failed(schedule, fmt::format("{}: {}", config_.address, response.error), retry_after);
      case HttpOutcome::Answered: break;
    }
    if (response.status == 304) {
      ++unchanged_;
      failures_.recovered("answering again");
      return schedule.after_success(retry_after);
    }
    if (response.status != 200) {
      if (response.status == 401 && token_) token_->forget();
      return failed(schedule, fmt::format("{}: HTTP {}", config_.address, response.status), retry_after);
    }
    const auto etag = response.header("etag");
    const auto last_modified = response.header("last-modified");
    etag_ = etag ? std::string(*etag) : std::string();
    last_modified_ = last_modified ? std::string(*last_modified) : std::string();
    ++polls_;
    failures_.recovered("answering again");
    if (!hand_over(std::move(response.body))) return std::nullopt;
    return schedule.after_success(retry_after);
  }

  double failed(RetrySchedule& schedule, const std::string& what, std::optional<double> retry_after) {
    ++poll_failures_;
    const double wait_s = schedule.after_failure(retry_after);
    failures_.report(fmt::format("{} (next request in {:.3g} s)", what, wait_s));
    return wait_s;
  }

  // Gives an answer to the I/O thread and waits until it is decoded: one answer at a
  // time, so a slow pipeline slows the polling rather than piling answers up. False
  // when the input stops meanwhile.
  bool hand_over(std::string body) {
    std::unique_lock lock(mutex_);
    in_flight_ = true;
    asio::post(io_, [this, body = std::move(body)] { take(body); });
    changed_.wait(lock, [this] { return stopping_ || !in_flight_; });
    return !stopping_;
  }

  // On the I/O thread.
  void take(const std::string& body) {
    if (!stopped_) feed_message(*decoder_, body.data(), body.size());
    {
      const std::lock_guard lock(mutex_);
      in_flight_ = false;
    }
    changed_.notify_all();
  }

  asio::io_context& io_;
  std::unique_ptr<protocol::Decoder> decoder_;  // the I/O thread's
  bool stopped_ = false;                        // the I/O thread's

  // The worker thread's.
  HttpClient client_;
  HttpRequest request_;
  std::optional<BearerToken> token_;
  std::string etag_;
  std::string last_modified_;
  RepeatedFailure failures_;

  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stopping_ = false;   // under mutex_
  bool in_flight_ = false;  // under mutex_
  std::atomic<bool> abort_ = false;
  std::atomic<std::uint64_t> polls_ = 0;
  std::atomic<std::uint64_t> unchanged_ = 0;
  std::atomic<std::uint64_t> poll_failures_ = 0;
};

}  // namespace

std::unique_ptr<Input> make_http_poll_input(asio::io_context& io, const InputConfig& config,
                                            const protocol::DecoderOptions& options, Input::ReportHandler handler) {
  return std::make_unique<HttpPollInput>(io, config, options, std::move(handler));
}

}  // namespace kew::daemon

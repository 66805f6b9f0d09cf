#include "notifier.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "credentials.hpp"
#include "http_client.hpp"
#include "message_template.hpp"
#include "repeated_failure.hpp"
#include "retry_schedule.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon {

namespace {

/// max_per_minute as a token bucket: a minute's worth may go at once, then one every
/// 60 / max_per_minute seconds.
class MessagePace {
 public:
  explicit MessagePace(double per_minute) : rate_per_s_(per_minute / 60.0), capacity_(std::max(1.0, per_minute)), tokens_(capacity_) {}
  /// Seconds until a message may go (0: now).
  double wait_s(double now_s) {
    if (rate_per_s_ <= 0) return 0.0;
    refill(now_s);
    return tokens_ >= 1.0 ? 0.0 : (1.0 - tokens_) / rate_per_s_;
  }
  void sent(double now_s) {
    if (rate_per_s_ <= 0) return;
    refill(now_s);
    tokens_ -= 1.0;
  }

 private:
  void refill(double now_s) {
    if (last_s_ > 0) tokens_ = std::min(capacity_, tokens_ + (now_s - last_s_) * rate_per_s_);
    last_s_ = now_s;
  }
  double rate_per_s_;
  double capacity_;
  double tokens_;
  double last_s_ = 0.0;
};

/// The URL without its path and query, which may carry a secret (a web hook's key).
std::string origin_of(const std::string& url) {
  const std::size_t host = url.find("://");
  const std::size_t path = host == std::string::npos ? std::string::npos : url.find('/', host + 3);
  std::string origin = url.substr(0, path);
  if (const std::size_t at = origin.find('@'); at != std::string::npos) origin.erase(host + 3, at - host - 2);
  return origin;
}

std::chrono::duration<double> seconds(double s) { return std::chrono::duration<double>(std::max(0.0, s)); }

}  // namespace

Notifier::Notifier(NotifyConfig config, std::string outbox_path, std::unique_ptr<ProgressStore> store,
                   std::function<bool()> may_speak)
    : config_(std::move(config)),
      url_(config_.url_file.empty() ? config_.url : read_secret_file(config_.url_file)),
      token_(config_.token_file.empty() ? std::string() : read_secret_file(config_.token_file)),
      store_(std::move(store)),
      may_speak_(std::move(may_speak)),
      filter_(config_),
      outbox_(std::move(outbox_path), config_.outbox, config_.coalesce_s) {
  for (const std::string* file : {&config_.url_file, &config_.token_file})
    if (!file->empty())
      if (const auto exposure = secret_file_exposure(*file)) spdlog::warn("[notify {}] {}", config_.name, *exposure);
  if (const std::string loaded = outbox_.load(util::steady_now_s()); !loaded.empty())
    spdlog::info("[notify {}] outbox: {}", config_.name, loaded);
  thread_ = std::thread([this] { run(); });
}

Notifier::~Notifier() { stop(); }

void Notifier::alert(const AlertEvent& event, const std::string& line) {
  const std::optional<NotifyState> state = filter_.classify(event);
  if (!state) return;
  {
    const std::lock_guard lock(mutex_);
    if (!outbox_.add(event, *state, line, util::steady_now_s())) return;
  }
  wake_.notify_one();
}

void Notifier::set_active(bool active) {
  {
    const std::lock_guard lock(mutex_);
    if (active_ == active) return;
    active_ = active;
    // Whatever the other instance delivered meanwhile is read again before delivering.
    caught_up_ = false;
  }
  wake_.notify_one();
}

NotifierFigures Notifier::figures() const {
  const std::lock_guard lock(mutex_);
  NotifierFigures f;
  f.delivered = delivered_;
  f.failures = failures_;
  f.dropped = outbox_.dropped();
  f.queued = outbox_.waiting_events();
  f.outbox_write_errors = outbox_.write_errors();
  const std::optional<double> oldest = outbox_.oldest_queued_s();
  f.failing = consecutive_failures_ > 0 && oldest && util::steady_now_s() - *oldest > config_.failing_after_s;
  return f;
}

void Notifier::stop() {
  {
    const std::lock_guard lock(mutex_);
    if (stopping_) return;
    stopping_ = true;
  }
  abort_ = true;
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  const std::lock_guard lock(mutex_);
  outbox_.sync();
  if (const std::size_t left = outbox_.waiting_events())
    spdlog::warn("[notify {}] {} events not delivered {}", config_.name, left,
                 outbox_.persistent() ? "wait in the outbox for the next start" : "are lost (no state directory)");
}

bool Notifier::catch_up_with_store() {
  std::string error;
  const std::optional<DeliveryProgress> progress = store_->load(error);
  if (!progress) return false;
  const std::lock_guard lock(mutex_);
  outbox_.forget(*progress);
  return true;
}

void Notifier::save_progress() {
  if (!store_) return;
  DeliveryProgress progress;
  {
    const std::lock_guard lock(mutex_);
    progress = outbox_.progress();
  }
  std::string error;
  if (!store_->save(progress, error))
    spdlog::warn("[notify {}] the pair's record of deliveries cannot be written: {}", config_.name, error);
}

bool Notifier::deliver(const OutboxEntry& entry, HttpClient& client, RepeatedFailure& failure, double& wait_s) {
  const NotifyMessage message = render_message(config_, entry, token_);
  HttpRequest request;
  request.url = url_;
  request.method = HttpMethod::Post;
  request.headers = message.headers;
  request.body = message.body;
  request.timeout_s = config_.timeout_s;
  request.connect_timeout_s = std::min(5.0, config_.timeout_s);
  request.max_body_bytes = 1u << 20;
  request.ca_file = config_.ca_file;
  const HttpResponse response = client.perform(request, &abort_);
  wait_s = 0;
  if ((response.outcome == HttpOutcome::Answered || response.outcome == HttpOutcome::TooLarge) &&
      response.status >= 200 && response.status < 300)
    return true;
  if (response.outcome == HttpOutcome::Aborted) return false;
  const std::string why = response.outcome == HttpOutcome::Answered
                              ? fmt::format("answered {}", response.status)
                              : fmt::format("{}: {}", kHttpOutcomeNames.name(response.outcome), response.error);
  failure.report(fmt::format("{} (alert {}, seq {})", why, entry.latest.id, entry.seqs.back()));
  // A refused token may have been replaced in its file meanwhile.
  if ((response.status == 401 || response.status == 403) && !config_.token_file.empty()) {
    try {
      token_ = read_secret_file(config_.token_file);
    } catch (const std::exception& e) {
      spdlog::warn("[notify {}] {}", config_.name, e.what());
    }
  }
  wait_s = response.retry_after_s(util::unix_now_s()).value_or(0.0);
  return false;
}

void Notifier::run() {
  RetrySchedule schedule(1e-3, config_.backoff_min_s, config_.backoff_max_s);
  MessagePace pace(config_.max_per_minute);
  HttpClient client;
  RepeatedFailure failure(fmt::format("[notify {}] {}", config_.name, origin_of(url_)));
  RepeatedFailure store_failure(fmt::format("[notify {}]", config_.name));
  double last_sync_s = util::steady_now_s();
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    const double now = util::steady_now_s();
    if (now - last_sync_s >= 1.0) {
      // The disk may be slow: the I/O thread must not wait for it on this lock.
      if (const int fd = outbox_.sync_handle(); fd >= 0) {
        lock.unlock();
        ::fdatasync(fd);
        ::close(fd);
        lock.lock();
      }
      last_sync_s = now;
      if (const std::uint64_t drops = outbox_.take_new_drops())
        spdlog::error("[notify {}] outbox full ({} events): the oldest {} events were dropped", config_.name,
                      config_.outbox, drops);
    }
    if (!active_ || (store_ && !caught_up_)) {
      const bool active = active_;
      if (store_) {
        lock.unlock();
        const bool read = catch_up_with_store();
        lock.lock();
        if (active && read && active_) caught_up_ = true;
        if (active && !read) store_failure.report("cannot read what the pair delivered; no delivery until it can");
        if (active_ && caught_up_) continue;
      }
      wake_.wait_for(lock, seconds(active ? 0.5 : 1.0), [&] { return stopping_ || active_ != active; });
      continue;
    }
    double wake_s = 0;
    OutboxEntry* entry = outbox_.next_due(now, wake_s, config_.format == NotifyTemplate::Json);
    const double paced_s = entry ? pace.wait_s(now) : 0.0;
    if (!entry || paced_s > 0 || (may_speak_ && !may_speak_())) {
      const double wait = !entry ? std::min(1.0, wake_s - now) : paced_s > 0 ? std::min(1.0, paced_s) : 0.1;
      const std::size_t waiting = outbox_.waiting_events();
      wake_.wait_for(lock, seconds(wait), [&] { return stopping_ || !active_ || outbox_.waiting_events() != waiting; });
      continue;
    }
    entry->in_flight = true;
    const OutboxEntry copy = *entry;
    lock.unlock();
    double retry_after_s = 0;
    const bool delivered = deliver(copy, client, failure, retry_after_s);
    lock.lock();
    if (delivered) {
      outbox_.delivered(copy.seqs.front(), util::steady_now_s());
      ++delivered_;
      if (consecutive_failures_) failure.recovered("delivered again");
      consecutive_failures_ = 0;
      schedule.after_success();
      pace.sent(util::steady_now_s());
      lock.unlock();
      save_progress();
      lock.lock();
      continue;
    }
    outbox_.returned(copy.seqs.front());
    if (stopping_) break;
    ++failures_;
    ++consecutive_failures_;
    const double wait = schedule.after_failure(retry_after_s > 0 ? std::optional(retry_after_s) : std::nullopt);
    wake_.wait_for(lock, seconds(wait), [&] { return stopping_ || !active_; });
  }
}

}  // namespace kew::daemon

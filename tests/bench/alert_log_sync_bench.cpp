// The cost of [service] alert_log_sync (design §6.6, docs/reliability.md "Restarts and the alert
// log"): alert-sized lines written as kewd writes them (LineFile::append + flush per
// event), with fdatasync never ("none"), once a second ("interval") or after each event
// ("every"). Run by hand on the disk that will hold the alert log:
//   kew_alert_log_sync_bench DIRECTORY [EVENTS]
// Prints one line per policy: microseconds per event and events per second.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "line_file.hpp"

namespace {

double run(const std::filesystem::path& file, const std::string& line, int events, const char* policy) {
  std::filesystem::remove(file);
  const bool every = std::string(policy) == "every";
  const bool interval = std::string(policy) == "interval";
  kew::daemon::LineFile log(file.string(), 0, 0, every);
  const auto start = std::chrono::steady_clock::now();
  auto last_sync = start;
  for (int i = 0; i < events; ++i) {
    log.append(line);
    log.flush();
    const auto now = std::chrono::steady_clock::now();
    if (interval && now - last_sync >= std::chrono::seconds(1)) {  // kewd's housekeeping timer
      log.sync();
      last_sync = now;
    }
  }
  if (interval) log.sync();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::filesystem::remove(file);
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DIRECTORY [EVENTS]\n", argv[0]);
    return 64;
  }
  const std::filesystem::path file = std::filesystem::path(argv[1]) / "kew-sync-bench.jsonl";
  const int events = argc > 2 ? std::atoi(argv[2]) : 20000;
  // An update event of the busy sector scenario, 640 bytes with its line end.
  std::string line = R"({"class":"ALERT","id":"9f3c2a51d0e4b7c8","number":42,"seq":17,"state":"update",)";
  line.resize(639, ' ');
  line += '\n';
  for (const char* policy : {"none", "interval", "every"}) {
    const double seconds = run(file, line, events, policy);
    std::printf("%-8s %7d events  %9.1f us/event  %10.0f events/s\n", policy, events, 1e6 * seconds / events,
                events / seconds);
  }
  return 0;
}

#pragma once
// Small pieces shared by kew_peers_bench and kew_pipeline_bench: the machine's name for
// the report, a streaming JSON writer (no JSON library is installed), and a monotonic
// stopwatch. Header-only; benchmarks only.

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

// The benchmarks' CMake targets define it; timings from a Debug build are not comparable.
#ifndef KEW_BUILD_TYPE
#define KEW_BUILD_TYPE "unknown"
#endif

namespace kew::bench {

/// "model name" of the first CPU in /proc/cpuinfo ("unknown" when absent).
inline std::string cpu_model_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.compare(0, 10, "model name") != 0) continue;
    const std::size_t value = line.find_first_not_of(" \t:", line.find(':'));
    return value == std::string::npos ? std::string("unknown") : line.substr(value);
  }
  return "unknown";
}

inline unsigned hardware_threads() { return std::thread::hardware_concurrency(); }

/// CPU seconds of the calling thread since construction or the last restart(). The
/// benchmarks are single-threaded, and the machines they run on are often shared (CI,
/// parallel builds): thread CPU time does not count the time another process held the
/// core, which wall time would.
class Stopwatch {
 public:
  Stopwatch() : start_(now()) {}
  void restart() { start_ = now(); }
  double seconds() const { return now() - start_; }

 private:
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
  double start_;
};

/// The q-quantile (q in [0, 1]) of `values` by nth_element, which reorders them; NaN
/// when empty.
inline double percentile(std::vector<double>& values, double q) {
  if (values.empty()) return std::nan("");
  const auto k = static_cast<std::size_t>(std::min(1.0, q) * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

/// Writes one JSON document into a string: begin()/end() objects and arrays, key()
/// before each member of an object. Commas and indentation are the writer's; a
/// non-finite number is written null (JSON has none).
class JsonText {
 public:
  JsonText& begin_object() { return open('{'); }
  JsonText& end_object() { return close('}'); }
  JsonText& begin_array() { return open('['); }
  JsonText& end_array() { return close(']'); }
  JsonText& key(std::string_view name) {
    separate();
    string(name);
    text_ += ": ";
    after_key_ = true;
    return *this;
  }
  JsonText& value(double x) {
    separate();
    if (!std::isfinite(x)) {
      text_ += "null";
      return *this;
    }
    char digits[40];
    std::snprintf(digits, sizeof digits, "%.6g", x);
    text_ += digits;
    return *this;
  }
  JsonText& value(std::uint64_t n) {
    separate();
    text_ += std::to_string(n);
    return *this;
  }
  JsonText& value(bool b) {
    separate();
    text_ += b ? "true" : "false";
    return *this;
  }
  JsonText& value(std::string_view s) {
    separate();
    string(s);
    return *this;
  }
  JsonText& value(const char* s) { return value(std::string_view(s)); }

  const std::string& text() const { return text_; }
  /// Writes the document and a newline to `path`; false when the file cannot be written.
  bool save(const std::string& path) const {
    std::ofstream out(path);
    out << text_ << '\n';
    return static_cast<bool>(out);
  }

 private:
  JsonText& open(char bracket) {
    separate();
    text_ += bracket;
    has_members_.push_back(false);
    return *this;
  }
  JsonText& close(char bracket) {
    const bool had_members = has_members_.back();
    has_members_.pop_back();
    if (had_members) newline();
    text_ += bracket;
    return *this;
  }
  // Called before every value and key: a value right after its key stays on its line.
  void separate() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (has_members_.empty()) return;
    if (has_members_.back()) text_ += ',';
    has_members_.back() = true;
    newline();
  }
  void newline() {
    text_ += '\n';
    text_.append(2 * has_members_.size(), ' ');
  }
  void string(std::string_view s) {
    text_ += '"';
    for (const char c : s) {
      if (c == '"' || c == '\\') text_ += '\\';
      text_ += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
    }
    text_ += '"';
  }

  std::string text_;
  std::vector<bool> has_members_;  // per open container: a member was written
  bool after_key_ = false;
};

/// The "machine" member of a benchmark's JSON: CPU, threads, compiler and build type
/// (timings of a Debug build are not comparable).
inline void put_machine(JsonText& json, std::string_view build_type) {
  json.key("machine").begin_object();
  json.key("cpu").value(cpu_model_name());
  json.key("hardware_threads").value(std::uint64_t{hardware_threads()});
  json.key("compiler").value(__VERSION__);
  json.key("build_type").value(build_type);
  json.end_object();
}

}  // namespace kew::bench

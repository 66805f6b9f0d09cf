// kew_peers_bench's command line.

#include "params.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <stdexcept>

namespace kew::bench::peers {

namespace {

constexpr const char* kMethodNames[] = {"kew-centred", "kew-eager", "kew-tau50", "kew-renumbered", "kew-index", "kew-lookahead", "cgal", "flip", "grid", "brute"};

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    out.push_back(text.substr(begin, comma - begin));
    begin = comma + 1;
  }
  return out;
}

std::vector<std::size_t> parse_list(const std::string& text) {
  std::vector<std::size_t> out;
  for (const std::string& item : split_list(text)) out.push_back(std::stoul(item));
  return out;
}

}  // namespace

bool wanted(const Params& p, const std::string& method) {
  return p.methods.empty() || std::find(p.methods.begin(), p.methods.end(), method) != p.methods.end();
}

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "kew_peers_bench: " << why
            << "\nusage: kew_peers_bench [--quick] [--aircraft N,N,...] [--periods N] [--warmup N] [--seed S]"
               " [--scenario NAME] [--recording FILE] [--methods NAME,...] [--lookahead-tolerance M] [--lookahead-keep S]"
               " [--first-order arrival|shuffled|hilbert] [--renumber-every S]"
               " [--brute-budget PAIRS] [--json FILE]\n";
  std::exit(2);
}

Params parse(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage("missing value for " + flag);
      return argv[++i];
    };
    try {
      if (flag == "--quick") {  // CI smoke run (< 1 min); later flags still override
        p.aircraft = {1000, 10000};
        p.periods = 2;
        p.warmup = 1;
        p.brute_budget = 3e7;
      } else if (flag == "--aircraft") {
        p.aircraft = parse_list(value());
      } else if (flag == "--periods") {
        p.periods = std::stoul(value());
      } else if (flag == "--warmup") {
        p.warmup = std::stoul(value());
      } else if (flag == "--scenario") {
        const auto scenario = kew::replay::kScenarioNames.parse(value());
        if (!scenario) usage("unknown scenario");
        p.scenario = *scenario;
      } else if (flag == "--seed") {
        p.seed = std::stoull(value());
      } else if (flag == "--brute-budget") {
        p.brute_budget = std::stod(value());
      } else if (flag == "--recording") {
        p.recording = value();
        p.aircraft = {0};  // one fleet: the recording's
      } else if (flag == "--lookahead-keep") {
        p.lookahead_keep_s = std::stod(value());
      } else if (flag == "--lookahead-tolerance") {
        p.lookahead_tolerance_m = std::stod(value());
      } else if (flag == "--renumber-every") {
        p.renumber_every_s = std::stod(value());
        if (!(p.renumber_every_s > 0.0)) usage("--renumber-every wants seconds > 0");
      } else if (flag == "--first-order") {
        const std::string order = value();
        if (order == "arrival") p.first_order = Params::FirstOrder::Arrival;
        else if (order == "shuffled") p.first_order = Params::FirstOrder::Shuffled;
        else if (order == "hilbert") p.first_order = Params::FirstOrder::Hilbert;
        else usage("unknown --first-order " + order);
      } else if (flag == "--json") {
        p.json_path = value();
      } else if (flag == "--methods") {
        for (const std::string& name : split_list(value())) {
          if (name == "kew") continue;  // always run: every other method is checked against it
          if (std::find_if(std::begin(kMethodNames), std::end(kMethodNames), [&](const char* m) { return name == m; }) ==
              std::end(kMethodNames))
            usage("unknown method " + name);
          p.methods.push_back(name);
        }
        if (p.methods.empty()) p.methods.push_back("kew");  // kew alone
      } else {
        usage("unknown flag " + flag);
      }
    } catch (const std::logic_error&) {
      usage("bad value for " + flag);
    }
  }
  for (const std::size_t n : p.aircraft)
    if (p.recording.empty() && (n < 10 || n > 1000000)) usage("aircraft must be in [10, 1000000]");
  if (p.periods < 1 || p.warmup < 1 || !(p.brute_budget > 0)) usage("need periods >= 1, warmup >= 1, budget > 0");
  return p;
}

}  // namespace kew::bench::peers

#include "kew/pipeline/pair_watch.hpp"

namespace kew {

std::size_t PairWatch::watch(std::string a_source, std::string a_id, std::string b_source, std::string b_id,
                             double from_t, double to_t) {
  WatchedPair p;
  p.a_source = std::move(a_source);
  p.a_id = std::move(a_id);
  p.b_source = std::move(b_source);
  p.b_id = std::move(b_id);
  p.from_t = from_t;
  p.to_t = to_t;
  parties_.insert(key(p.a_source, p.a_id));
  parties_.insert(key(p.b_source, p.b_id));
  pairs_.push_back(std::move(p));
  return pairs_.size() - 1;
}

std::string PairWatch::key(std::string_view source, std::string_view id) {
  std::string k(source);
  k += '\x1f';  // not in a source name
  k.append(id);
  return k;
}

bool PairWatch::watches(std::string_view source, std::string_view id) const {
  return parties_.count(key(source, id)) != 0;
}

void PairWatch::seen(std::string_view source, std::string_view id, double t) { last_seen_[key(source, id)] = t; }

std::optional<double> PairWatch::last_seen(std::string_view source, std::string_view id) const {
  const auto it = last_seen_.find(key(source, id));
  if (it == last_seen_.end()) return std::nullopt;
  return it->second;
}

void PairWatch::note_track(std::string_view source, std::string_view id, const PairNote& note) {
  for_each_partner(source, id, note.t, [&](WatchedPair& p, std::string_view, std::string_view) { p.notes.push_back(note); });
}

std::string party_label(std::string_view source, std::string_view id) {
  std::string out;
  if (!source.empty()) {
    out.append(source);
    out += ':';
  }
  out.append(id);
  return out;
}

}  // namespace kew

#include "kew/replay/pair_watch.hpp"

#include "evaluation/pair_note.hpp"

namespace kew::replay {

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

namespace {
bool is_party(std::string_view source, std::string_view id, const std::string& s, const std::string& i) {
  return s == source && i == id;
}
}  // namespace

std::vector<alert::PartyName> PairWatch::partners(std::string_view source, std::string_view id, double t) const {
  std::vector<alert::PartyName> out;
  const auto add = [&](const std::string& s, const std::string& i) {
    for (const alert::PartyName& known : out)
      if (is_party(known.source, known.id, s, i)) return;  // a pair watched in several windows is judged once
    out.push_back({s, i});
  };
  for (const WatchedPair& p : pairs_) {
    if (t < p.from_t || t > p.to_t) continue;
    if (is_party(source, id, p.a_source, p.a_id)) add(p.b_source, p.b_id);
    if (is_party(source, id, p.b_source, p.b_id)) add(p.a_source, p.a_id);
  }
  return out;
}

void PairWatch::record(const TrackReport& report, const RecordOutcome& outcome) {
  if (outcome.applied()) last_seen_[key(report.source, report.id)] = report.t;
  if (const std::optional<PairNote> note = note_of(report, outcome)) note_track(report.source, report.id, *note);
}

void PairWatch::pair_judged(const PairObservation& observation) {
  const PairNote note = note_of(observation, last_seen(observation.partner.source, observation.partner.id));
  const alert::PartyName& self = observation.updated;
  const alert::PartyName& partner = observation.partner;
  for (WatchedPair& p : pairs_) {
    if (note.t < p.from_t || note.t > p.to_t) continue;
    if (is_party(self.source, self.id, p.a_source, p.a_id) && is_party(partner.source, partner.id, p.b_source, p.b_id))
      p.notes.push_back(note);
    if (is_party(self.source, self.id, p.b_source, p.b_id) && is_party(partner.source, partner.id, p.a_source, p.a_id))
      p.notes.push_back(note);
  }
}

std::optional<double> PairWatch::last_seen(std::string_view source, std::string_view id) const {
  const auto it = last_seen_.find(key(source, id));
  if (it == last_seen_.end()) return std::nullopt;
  return it->second;
}

void PairWatch::note_track(std::string_view source, std::string_view id, const PairNote& note) {
  for (WatchedPair& p : pairs_) {
    if (note.t < p.from_t || note.t > p.to_t) continue;
    if (is_party(source, id, p.a_source, p.a_id)) p.notes.push_back(note);
    if (is_party(source, id, p.b_source, p.b_id)) p.notes.push_back(note);
  }
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

}  // namespace kew::replay

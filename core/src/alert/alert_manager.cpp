#include "kew/alert/alert_manager.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

namespace kew::alert {

namespace {

void erase_value(std::vector<Slot>& v, Slot value) {
  const auto it = std::find(v.begin(), v.end(), value);
  if (it != v.end()) {
    *it = v.back();
    v.pop_back();
  }
}

constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= bytes[i];
    h *= kFnvPrime;
  }
  return h;
}

std::uint64_t fnv1a(std::uint64_t h, const std::string& s) {
  h = fnv1a(h, s.data(), s.size());
  const unsigned char separator = 0x1f;  // unit separator: "ab"+"c" ≠ "a"+"bc"
  return fnv1a(h, &separator, 1);
}

}  // namespace

std::string make_alert_id(const AlertParty& a, const AlertParty& b, double opened_t) {
  return format_alert_id(alert_id_hash(a, b, opened_t));
}

std::string format_alert_id(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

std::uint64_t alert_id_hash(const AlertParty& a, const AlertParty& b, double opened_t) {
  std::uint64_t h = kFnvOffset;
  h = fnv1a(h, a.source);
  h = fnv1a(h, a.id);
  h = fnv1a(h, b.source);
  h = fnv1a(h, b.id);
  // Millisecond resolution: the ids do not depend on the last bits of a double.
  const auto ms = static_cast<std::int64_t>(std::llround(opened_t * 1000.0));
  return fnv1a(h, &ms, sizeof ms);
}

std::uint64_t area_alert_id_hash(const AlertParty& a, const std::string& volume, double opened_t) {
  std::uint64_t h = kFnvOffset;
  h = fnv1a(h, std::string("apw"));  // never a pair's: a source is never followed by "apw", ""
  h = fnv1a(h, a.source);
  h = fnv1a(h, a.id);
  h = fnv1a(h, volume);
  const auto ms = static_cast<std::int64_t>(std::llround(opened_t * 1000.0));
  return fnv1a(h, &ms, sizeof ms);
}

AlertManager::AlertManager(const AlertConfig& config, PartyNames names) : config_(config), names_(std::move(names)) {}

Severity AlertManager::classify(bool lost_now, double t_los_s, double warning_s) const {
  if (lost_now) return Severity::Loss;
  if (t_los_s <= (warning_s < 0.0 ? config_.warning_s : warning_s)) return Severity::Warning;
  return Severity::Caution;
}

AlertManager::PairState AlertManager::state_of_key(std::uint64_t key) {
  PairState s;
  s.area = (key & kAreaBit) != 0;
  s.lo = static_cast<Slot>(s.area ? (key >> 31) & 0xffffffffu : key >> 32);
  s.hi = static_cast<Slot>(s.area ? key & 0x7fffffffu : key & 0xffffffffu);
  return s;
}

AlertManager::Pairs::iterator AlertManager::create(std::uint64_t key) {
  PairState s = state_of_key(key);
  if (s.area) {
    volumes_[s.lo].push_back(s.hi);
  } else {
    partners_[s.lo].push_back(s.hi);
    partners_[s.hi].push_back(s.lo);
  }
  return pairs_.emplace(key, std::move(s)).first;
}

void AlertManager::forget(Pairs::iterator it) {
  const Slot lo = it->second.lo, hi = it->second.hi;
  if (it->second.area) {
    const auto v = volumes_.find(lo);
    if (v != volumes_.end()) {
      erase_value(v->second, hi);
      if (v->second.empty()) volumes_.erase(v);
    }
    pairs_.erase(it);
    return;
  }
  for (const auto& [slot, other] : {std::pair{lo, hi}, std::pair{hi, lo}}) {
    const auto p = partners_.find(slot);
    if (p == partners_.end()) continue;
    erase_value(p->second, other);
    if (p->second.empty()) partners_.erase(p);
  }
  pairs_.erase(it);
}

void AlertManager::record_clear(Pairs::iterator it, double t, double look_t, int clear, std::vector<AlertEvent>& out) {
  PairState& s = it->second;
  s.conflicts_in_row = 0;
  if (!s.active) {
    forget(it);
    return;
  }
  if (counts(s, look_t)) ++s.clears_in_row;
  if (s.clears_in_row < clear) return;
  end(s, t, AlertEndReason::Cleared, out);
  forget(it);
}

void AlertManager::open(PairState& s, AlertEvent&& event, std::vector<AlertEvent>& out) {
  s.active = true;
  ++active_;
  ++counters_.opened;
  event.state = AlertState::New;
  event.opened_t = event.t;
  event.kind = s.area ? AlertKind::Apw : AlertKind::Stca;
  s.last.id_hash = s.area ? area_alert_id_hash(event.a, event.volume, event.t) : alert_id_hash(event.a, event.b, event.t);
  event.id = format_alert_id(s.last.id_hash);
  event.number = next_number_;
  next_number_ = static_cast<std::uint16_t>(next_number_ == 0xffff ? 1 : next_number_ + 1);
  event.acknowledged = false;
  emit(s, std::move(event), out);
  s.opened_seq = s.last.seq;
}

bool AlertManager::changed(const PairState& s, const Evaluation& e, double t) const {
  const DecidedFigures& last = s.decided;
  const double aged_t_los = std::max(0.0, last.t_los_s - (t - s.last.t));
  return e.severity != s.last.severity || std::abs(e.t_los_s - aged_t_los) >= config_.update_t_los_s ||
         std::abs(e.cpa_h_m - last.cpa_h_m) >= config_.update_cpa_h_m ||
         std::abs(e.cpa_v_ft - last.cpa_v_ft) >= config_.update_cpa_v_ft;
}

void AlertManager::update(PairState& s, AlertEvent&& event, std::vector<AlertEvent>& out) {
  const LastEvent& last = s.last;
  ++counters_.updated;
  event.state = AlertState::Update;
  event.kind = s.area ? AlertKind::Apw : AlertKind::Stca;
  event.id = format_alert_id(last.id_hash);
  event.number = last.number;
  event.opened_t = last.opened_t;
  event.acknowledged = last.acknowledged && event.severity <= last.severity;
  emit(s, std::move(event), out);
}

void AlertManager::end(PairState& s, double t, AlertEndReason reason, std::vector<AlertEvent>& out) {
  AlertEvent event = recall(s);
  event.state = AlertState::End;
  event.end_reason = reason;
  event.t = t;
  s.active = false;
  --active_;
  ++counters_.ended;
  // Not emit(): both callers forget the pair next, so there is nothing to remember.
  event.seq = ++seq_;
  out.push_back(std::move(event));
}

void AlertManager::emit(PairState& s, AlertEvent event, std::vector<AlertEvent>& out) {
  event.seq = ++seq_;
  remember(s, event);
  out.push_back(std::move(event));
}

namespace {

// AlertParty and AlertManager::PartyFigures name their numbers and callsign alike.
template <class From, class To>
void copy_party_figures(const From& from, To& to) {
  to.lat_deg = from.lat_deg;
  to.lon_deg = from.lon_deg;
  to.alt_ft = from.alt_ft;
  to.gs_kt = from.gs_kt;
  to.trk_deg = from.trk_deg;
  to.vr_fpm = from.vr_fpm;
  to.callsign = from.callsign;
  to.track_number = from.track_number;
}

}  // namespace

void AlertManager::remember(PairState& s, const AlertEvent& event) {
  LastEvent& last = s.last;
  if (event.state == AlertState::New) {
    const PartyName lo = names_(s.lo);
    last.lo_is_a = event.a.source == lo.source && event.a.id == lo.id;
  }
  last.seq = event.seq;
  last.t = event.t;
  last.opened_t = event.opened_t;
  last.t_los_s = event.t_los_s;
  last.t_cpa_s = event.t_cpa_s;
  last.cpa_h_m = event.cpa_h_m;
  last.cpa_v_ft = event.cpa_v_ft;
  last.sep_h_m = event.sep_h_m;
  last.sep_v_ft = event.sep_v_ft;
  copy_party_figures(last.lo_is_a ? event.a : event.b, last.lo);
  copy_party_figures(last.lo_is_a ? event.b : event.a, last.hi);
  last.number = event.number;
  last.state = event.state;
  last.severity = event.severity;
  last.hypothesis = event.hypothesis;
  if (last.region != event.region) last.region = event.region;
  if (last.volume != event.volume) last.volume = event.volume;
  if (last.volume_kind != event.volume_kind) last.volume_kind = event.volume_kind;
  last.acknowledged = event.acknowledged;
}

AlertEvent AlertManager::recall(const PairState& s) const {
  const LastEvent& last = s.last;
  AlertEvent event;
  event.id = format_alert_id(last.id_hash);
  event.number = last.number;
  event.seq = last.seq;
  event.state = last.state;
  event.severity = last.severity;
  event.hypothesis = last.hypothesis;
  event.kind = s.area ? AlertKind::Apw : AlertKind::Stca;
  event.region = last.region;
  event.volume = last.volume;
  event.volume_kind = last.volume_kind;
  event.t = last.t;
  event.opened_t = last.opened_t;
  AlertParty& lo = last.lo_is_a ? event.a : event.b;
  AlertParty& hi = last.lo_is_a ? event.b : event.a;
  copy_party_figures(last.lo, lo);
  const PartyName lo_name = names_(s.lo);
  lo.source = lo_name.source;
  lo.id = lo_name.id;
  if (!s.area) {  // an area's b is empty
    copy_party_figures(last.hi, hi);
    const PartyName hi_name = names_(s.hi);
    hi.source = hi_name.source;
    hi.id = hi_name.id;
  }
  event.t_los_s = last.t_los_s;
  event.t_cpa_s = last.t_cpa_s;
  event.cpa_h_m = last.cpa_h_m;
  event.cpa_v_ft = last.cpa_v_ft;
  event.sep_h_m = last.sep_h_m;
  event.sep_v_ft = last.sep_v_ft;
  event.acknowledged = last.acknowledged;
  return event;
}

void AlertManager::end_and_forget(std::vector<std::uint64_t>& keys, double t, std::vector<AlertEvent>& out) {
  std::sort(keys.begin(), keys.end());  // deterministic order of the End events
  for (const std::uint64_t key : keys) {
    const auto it = pairs_.find(key);
    if (it == pairs_.end()) continue;
    if (it->second.active) end(it->second, t, AlertEndReason::TrackDropped, out);
    forget(it);
  }
}

void AlertManager::drop_track(Slot slot, double t, std::vector<AlertEvent>& out) {
  std::vector<std::uint64_t> keys;
  if (const auto p = partners_.find(slot); p != partners_.end())
    for (const Slot other : p->second) keys.push_back(pair_key(slot, other));
  end_and_forget(keys, t, out);
  keys.clear();
  if (const auto v = volumes_.find(slot); v != volumes_.end())
    for (const std::uint32_t volume : v->second) keys.push_back(area_key(slot, volume));
  end_and_forget(keys, t, out);
}

void AlertManager::drop_volume(std::uint32_t volume, double t, std::vector<AlertEvent>& out) {
  std::vector<std::uint64_t> keys;
  for (const auto& [slot, volumes] : volumes_)
    if (std::find(volumes.begin(), volumes.end(), volume) != volumes.end()) keys.push_back(area_key(slot, volume));
  end_and_forget(keys, t, out);
}

void AlertManager::partners_of(Slot slot, std::vector<Slot>& out) const {
  const auto p = partners_.find(slot);
  if (p != partners_.end()) out.insert(out.end(), p->second.begin(), p->second.end());
}

void AlertManager::volumes_of(Slot slot, std::vector<std::uint32_t>& out) const {
  const auto v = volumes_.find(slot);
  if (v != volumes_.end()) out.insert(out.end(), v->second.begin(), v->second.end());
}

std::vector<AlertEvent> AlertManager::snapshot() const {
  std::vector<const PairState*> active;
  for (const auto& [key, s] : pairs_)
    if (s.active) active.push_back(&s);
  std::sort(active.begin(), active.end(),
            [](const PairState* x, const PairState* y) { return x->opened_seq < y->opened_seq; });
  std::vector<AlertEvent> out;
  out.reserve(active.size());
  for (const PairState* s : active) out.push_back(recall(*s));
  return out;
}

Severity AlertManager::highest_severity() const {
  Severity highest = Severity::None;
  for (const auto& [key, s] : pairs_)
    if (s.active && s.last.severity > highest) highest = s.last.severity;
  return highest;
}

std::vector<std::string> AlertManager::acknowledge_all() {
  std::vector<const LastEvent*> newly;
  for (auto& [key, s] : pairs_) {
    if (!s.active || s.last.acknowledged) continue;
    s.last.acknowledged = true;
    newly.push_back(&s.last);
  }
  std::sort(newly.begin(), newly.end(), [](const LastEvent* a, const LastEvent* b) { return a->number < b->number; });
  std::vector<std::string> ids;
  ids.reserve(newly.size());
  for (const LastEvent* e : newly) ids.push_back(format_alert_id(e->id_hash));
  return ids;
}

std::vector<std::string> AlertManager::acknowledge(std::string_view id) {
  for (auto& [key, s] : pairs_) {
    if (!s.active || format_alert_id(s.last.id_hash) != id) continue;
    if (s.last.acknowledged) return {};
    s.last.acknowledged = true;
    return {std::string(id)};
  }
  return {};
}

bool AlertManager::forget(std::string_view id) {
  for (auto it = pairs_.begin(); it != pairs_.end(); ++it) {
    if (!it->second.active || format_alert_id(it->second.last.id_hash) != id) continue;
    pairs_.erase(it);
    --active_;
    return true;
  }
  return false;
}

std::size_t AlertManager::unacknowledged_count() const {
  std::size_t n = 0;
  for (const auto& [key, s] : pairs_)
    if (s.active && !s.last.acknowledged) ++n;
  return n;
}

}  // namespace kew::alert

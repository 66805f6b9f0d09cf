#pragma once
// A track as an alert names it: its identity and its last reported state (design §5.3).

#include "kew/alert/alert_event.hpp"
#include "kew/track/track_table.hpp"

namespace kew::pipeline {

inline AlertParty party_of(const track::Track& t) {
  AlertParty p;
  p.id = t.id;
  p.source = t.source;
  p.callsign = t.callsign;
  p.track_number = t.number;
  p.lat_deg = t.lat_deg;
  p.lon_deg = t.lon_deg;
  p.alt_ft = t.alt_ft;
  p.gs_kt = t.gs_kt;
  p.trk_deg = t.trk_deg;
  p.vr_fpm = t.vr_fpm;
  return p;
}

}  // namespace kew::pipeline

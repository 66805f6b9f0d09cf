// kew live map: shared constants and formatting (units, colours, severity order).
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const METRES_PER_NM = 1852;

  // Altitude bands (ft, lower bound) and their colours; severity colours are kept out of
  // this palette (no yellow, orange or red) so an aircraft never looks like an alert.
  Kew.ALTITUDE_BANDS = [
    { from: -Infinity, label: "below 5,000 ft", color: "#7fdc7f" },
    { from: 5000, label: "5,000–10,000 ft", color: "#3fd0c9" },
    { from: 10000, label: "FL100–FL200", color: "#4aa8ff" },
    { from: 20000, label: "FL200–FL300", color: "#8f8cff" },
    { from: 30000, label: "FL300–FL400", color: "#d58bff" },
    { from: 40000, label: "FL400 and above", color: "#f2f2f2" },
  ];
  Kew.GROUND_COLOR = "#8a8a8a";

  Kew.altitudeColor = function (track) {
    if (track.gnd) return Kew.GROUND_COLOR;
    const alt = track.alt_ft;
    if (typeof alt !== "number" || !isFinite(alt)) return Kew.GROUND_COLOR;
    let color = Kew.ALTITUDE_BANDS[0].color;
    for (const band of Kew.ALTITUDE_BANDS) if (alt >= band.from) color = band.color;
    return color;
  };

  Kew.SEVERITY_RANK = { none: 0, caution: 1, warning: 2, loss: 3 };
  Kew.SEVERITY_COLOR = { none: "#888888", caution: "#ffd400", warning: "#ff8c00", loss: "#ff2a2a" };
  Kew.SEVERITY_SHORT = { none: "—", caution: "CAU", warning: "WRN", loss: "LOS" };

  // Most severe first, then the soonest loss of separation, then the alert number: the
  // order of the stream's snapshot and of the Modbus alert table.
  Kew.compareAlerts = function (x, y) {
    const s = (Kew.SEVERITY_RANK[y.severity] || 0) - (Kew.SEVERITY_RANK[x.severity] || 0);
    if (s !== 0) return s;
    const t = num(x.t_los_s, Infinity) - num(y.t_los_s, Infinity);
    if (t !== 0 && !isNaN(t)) return t;
    return num(x.number, 0) - num(y.number, 0);
  };

  function num(v, fallback) {
    return typeof v === "number" && isFinite(v) ? v : fallback;
  }

  Kew.trackKey = function (src, id) {
    return (src || "") + "|" + id;
  };

  Kew.trackName = function (t) {
    const cs = (t.cs || "").trim();
    return cs !== "" ? cs : t.id;
  };

  // "FL350" (flight level: hundreds of feet, three digits).
  Kew.flightLevel = function (altFt) {
    if (typeof altFt !== "number" || !isFinite(altFt)) return "FL---";
    const fl = Math.max(0, Math.round(altFt / 100));
    return "FL" + String(fl).padStart(3, "0");
  };

  Kew.speed = function (gsKt) {
    return typeof gsKt === "number" && isFinite(gsKt) ? Math.round(gsKt) + "kt" : "";
  };

  Kew.verticalArrow = function (vrFpm) {
    if (typeof vrFpm !== "number" || !isFinite(vrFpm)) return "";
    if (vrFpm > 300) return "↑";
    if (vrFpm < -300) return "↓";
    return "";
  };

  Kew.nm = function (metres) {
    if (typeof metres !== "number" || !isFinite(metres)) return "?";
    return (metres / METRES_PER_NM).toFixed(1) + " NM";
  };

  Kew.seconds = function (s) {
    if (typeof s !== "number" || !isFinite(s)) return "?";
    return Math.round(s) + " s";
  };

  Kew.feet = function (ft) {
    if (typeof ft !== "number" || !isFinite(ft)) return "?";
    return Math.round(ft) + " ft";
  };

  // "2024-04-29 14:13:20Z" from UTC seconds.
  Kew.utc = function (t) {
    if (typeof t !== "number" || !isFinite(t)) return "—";
    return new Date(t * 1000).toISOString().replace("T", " ").replace(/\.\d+Z$/, "Z");
  };

  Kew.duration = function (s) {
    if (typeof s !== "number" || !isFinite(s)) return "—";
    if (s < 0) s = 0;
    if (s < 60) return s.toFixed(1) + " s";
    if (s < 3600) return Math.floor(s / 60) + " min " + Math.round(s % 60) + " s";
    return Math.floor(s / 3600) + " h " + Math.round((s % 3600) / 60) + " min";
  };

  // An area proximity warning (design §4.11): one aircraft (a) and a volume, no b. An
  // ALERT without "kind" is a pair's (kewd before area alerts).
  Kew.isAreaAlert = function (a) {
    return a.kind === "apw" || (!a.b && typeof a.volume === "string");
  };

  // The aircraft an alert is about: the pair, or an area alert's one.
  Kew.alertParties = function (a) {
    return a.b ? [a.a, a.b] : [a.a];
  };

  // "EDR-1 (restricted) in 40 s", or "… inside" when the aircraft is in the volume.
  Kew.areaTarget = function (a) {
    const inside = a.severity === "loss" || a.t_los_s === 0;
    return a.volume + (a.volume_kind ? " (" + a.volume_kind + ")" : "") + (inside ? " inside" : " in " + Kew.seconds(a.t_los_s));
  };

  // The alert line's figures of an area alert: "EDR-1 in 40 s", "in EDR-1".
  Kew.areaSummary = function (a) {
    return a.severity === "loss" || a.t_los_s === 0 ? "in " + a.volume : a.volume + " in " + Kew.seconds(a.t_los_s);
  };

  Kew.alertSummary = function (a) {
    const los = a.severity === "loss" || a.t_los_s === 0 ? "LoS now" : "LoS in " + Kew.seconds(a.t_los_s);
    return los + " · CPA " + Kew.nm(a.cpa_h_m) + " / " + Kew.feet(a.cpa_v_ft) + " in " + Kew.seconds(a.t_cpa_s);
  };
})(window.Kew);

// kew live map: the page's state (tracks, alerts, feed health), fed by connection.js and
// drawn by map-layers.js and alert-list.js. Updates mark what changed; one animation frame
// then draws only that.
//
// Stable hooks for tests and tools: each aircraft marker has data-track-id (and
// data-track-src), each alert line and each alert list row data-alert-id (an area
// alert's line data-alert-volume, its row data-volume), each acknowledge button
// data-ack-id; each volume's path and label data-volume (map-volumes.js);
// #aircraft-count and #alert-count hold what is drawn
// (also as data-count); #connection-state has data-state (connecting, live, polling,
// offline); #feed-health has data-health; #replay-clock is shown in replays.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const REPLAY_THRESHOLD_S = 30; // |data time − wall time| beyond which the replay clock shows
  const PAIR_MAX_ZOOM = 12; // selecting an alert zooms in to its pair (or aircraft and volume), at most this far

  const state = {
    tracks: new Map(), // key -> track record
    alerts: new Map(), // id -> latest ALERT object (not ended)
    alive: null, // latest ALIVE object
    status: null, // latest /api/status reply, with receivedAt (ms, local clock)
  };
  const dirty = new Set();
  const removed = new Set();
  let alertsDirty = false;
  let volumesDirty = false;
  let frameRequested = false;
  let fitted = false;
  let userMoved = false;
  let alertedBefore = new Map();
  let selectedAlert = null; // the alert chosen in the list

  const $ = (id) => document.getElementById(id);

  // --- the map -------------------------------------------------------------------------
  const map = L.map("map", { worldCopyJump: true, minZoom: 2, maxZoom: 14, zoomSnap: 0.5 }).setView([48, 5], 5);
  map.attributionControl.setPrefix("Leaflet");
  // A tile server when kewd's [http] tile_url names one, else the offline base map.
  Kew.getJson("api/map-config").catch(() => ({})).then((config) => Kew.addBaseLayer(map, config));
  const aircraft = new Kew.AircraftLayer(map);
  const alertLines = new Kew.AlertLines(map);
  const zones = new Kew.ZoneLayer(map);
  const reference = new Kew.ReferenceLayer(map);
  const volumes = new Kew.VolumeLayer(map, state.tracks);
  reference.load();
  volumes.start(() => {
    volumesDirty = true;
    requestFrame();
  });
  L.control.layers(null, Object.assign({ zones: zones.group }, volumes.overlays(), reference.overlays()),
                   { position: "bottomleft" }).addTo(map);
  const labels = new Kew.LabelLayout(map, { aircraft, alertLines, reference, volumes }, () => $("show-labels").checked);
  const audible = new Kew.AudibleCue($("audible"));
  const ZONES_INTERVAL_MS = 10000;
  const refreshZones = () =>
    Kew.getJson("api/zones").then((z) => zones.update(z)).catch(() => {});
  map.on("dragstart zoomstart", (e) => {
    if (e.hard !== true && fitted) userMoved = true;
  });

  const connection = new Kew.Connection({
    onSnapshot: (objects) => applySnapshot(objects),
    onBatch: (objects) => objects.forEach(applyObject),
    onPoll: ({ tracks, alerts, status }) => {
      replaceTracks(tracks.tracks || []);
      replaceAlerts(alerts.alerts || []);
      applyStatus(status);
    },
    onStatus: (status) => applyStatus(status),
    onReconcile: (reply) => forgetDroppedTracks(reply),
    onState: (s, detail) => {
      const el = $("connection-state");
      el.dataset.state = s;
      el.textContent = { connecting: "connecting", live: "live", polling: "polling", offline: "offline" }[s] || s;
      el.title = detail;
    },
  });

  const alertList = new Kew.AlertList($("alert-list"), $("no-alerts"), {
    onSelect: (id) => centreOnAlert(id),
    onAck: (id, button) => acknowledge({ id }, button),
  });

  $("ack-all").addEventListener("click", (e) => acknowledge({ all: true }, e.currentTarget));
  $("show-labels").addEventListener("change", () => labels.request());
  $("show-trails").addEventListener("change", (e) => aircraft.showTrails(e.target.checked, state.tracks));

  const legend = $("altitude-legend");
  for (const band of Kew.ALTITUDE_BANDS.slice().reverse()) {
    const li = document.createElement("li");
    li.innerHTML = '<span class="swatch"></span>';
    li.firstChild.style.background = band.color;
    li.append(band.label);
    legend.append(li);
  }
  const ground = document.createElement("li");
  ground.innerHTML = '<span class="swatch"></span>on the ground / unknown';
  ground.firstChild.style.background = Kew.GROUND_COLOR;
  legend.append(ground);
  volumes.legend($("volume-legend"));

  // --- applying stream objects ---------------------------------------------------------
  function applyObject(o) {
    if (!o || typeof o !== "object") return;
    switch (o.class) {
      case "TRACK": applyTrack(o); break;
      case "TRACKS": replaceTracks(o.tracks || []); break;
      case "ALERT": applyAlert(o); break;
      case "ALERTS": replaceAlerts(o.alerts || []); break;
      case "ACK": markAcknowledged(o.ids || []); break;
      case "ALIVE": applyAlive(o); break;
      default: break; // VERSION, START, ERROR and classes this page does not know
    }
  }

  // The first message after a (re)connect: every track and every active alert.
  function applySnapshot(objects) {
    const tracks = [];
    const alerts = [];
    for (const o of objects) {
      if (!o) continue;
      if (o.class === "TRACK") tracks.push(o);
      else if (o.class === "TRACKS") tracks.push(...(o.tracks || []));
      else if (o.class === "ALERT") alerts.push(o);
      else if (o.class === "ALERTS") alerts.push(...(o.alerts || []));
      else applyObject(o);
    }
    replaceTracks(tracks);
    replaceAlerts(alerts);
  }

  function applyTrack(o) {
    if (typeof o.lat !== "number" || typeof o.lon !== "number") return;
    const key = Kew.trackKey(o.src, o.id);
    let t = state.tracks.get(key);
    if (!t) {
      t = { key, trail: [] };
      state.tracks.set(key, t);
      removed.delete(key);
    }
    t.id = o.id;
    t.src = o.src || "";
    t.cs = o.cs || "";
    t.lat = o.lat;
    t.lon = o.lon;
    t.alt_ft = o.alt_ft;
    t.gs_kt = o.gs_kt; // absent when the report has none
    t.trk_deg = o.trk_deg;
    t.vr_fpm = o.vr_fpm;
    t.gnd = o.gnd === true;
    t.t = o.t;
    if (o.tn !== undefined) t.tn = o.tn;
    if (o.sq !== undefined) t.sq = o.sq;
    Kew.pushTrail(t);
    dirty.add(key);
    requestFrame();
  }

  function removeTrack(key) {
    if (!state.tracks.delete(key)) return;
    dirty.delete(key);
    removed.add(key);
    requestFrame();
  }

  function replaceTracks(list) {
    const keep = new Set();
    for (const o of list) {
      applyTrack(o);
      keep.add(Kew.trackKey(o.src, o.id));
    }
    for (const key of Array.from(state.tracks.keys())) if (!keep.has(key)) removeTrack(key);
  }

  // /api/tracks during a live socket: tracks kewd no longer has are forgotten, unless the
  // socket has brought a record newer than the reply meanwhile.
  function forgetDroppedTracks(reply) {
    const present = new Set((reply.tracks || []).map((o) => Kew.trackKey(o.src, o.id)));
    for (const [key, t] of Array.from(state.tracks)) {
      if (!present.has(key) && !(typeof reply.t === "number" && t.t > reply.t)) removeTrack(key);
    }
  }

  // A pair's alert has a and b; an area alert (kind "apw") has a and its volume, no b.
  function drawable(o) {
    return !!(o.id && o.a && (o.b || (Kew.isAreaAlert(o) && o.volume)));
  }

  function applyAlert(o) {
    if (!drawable(o)) return;
    audible.consider(o, state.alerts.get(o.id));
    if (o.state === "end") state.alerts.delete(o.id);
    else state.alerts.set(o.id, o);
    alertsDirty = true;
    requestFrame();
  }

  function replaceAlerts(list) {
    state.alerts.clear();
    for (const o of list) if (o.state !== "end" && drawable(o)) state.alerts.set(o.id, o);
    alertsDirty = true;
    requestFrame();
  }

  function markAcknowledged(ids) {
    for (const id of ids) {
      const a = state.alerts.get(id);
      if (a && !a.ack) {
        state.alerts.set(id, Object.assign({}, a, { ack: true }));
        alertsDirty = true;
      }
    }
    requestFrame();
  }

  function applyAlive(o) {
    state.alive = o;
    if (typeof o.data_t === "number" && typeof o.wall_t === "number") applyStatus(o);
    renderHealth();
  }

  function applyStatus(s) {
    if (!s || typeof s !== "object") return;
    state.status = Object.assign({}, s, { receivedAt: Date.now() });
    if (s.class === "ALIVE" || s.rates) state.alive = s;
    renderHealth();
  }

  // --- acknowledging ---------------------------------------------------------------------
  function acknowledge(body, button) {
    const error = $("ack-error");
    if (button) button.disabled = true;
    connection
      .acknowledge(body)
      .then((reply) => {
        error.hidden = true;
        markAcknowledged(reply.acknowledged || []);
        if (button && button.id === "ack-all") button.disabled = false;
      })
      .catch((e) => {
        error.textContent = e.message;
        error.hidden = false;
        if (button) button.disabled = false;
      });
  }

  // --- drawing -------------------------------------------------------------------------
  function requestFrame() {
    if (frameRequested) return;
    frameRequested = true;
    requestAnimationFrame(render);
  }

  function render() {
    frameRequested = false;
    for (const key of removed) aircraft.remove(key);
    const moved = dirty.size > 0 || removed.size > 0;
    for (const key of dirty) {
      const t = state.tracks.get(key);
      if (t) aircraft.upsert(t);
    }
    dirty.clear();
    removed.clear();
    if (moved) {
      aircraft.redrawTrails(state.tracks);
      volumes.follow(state.tracks);
    }
    if (moved || alertsDirty || volumesDirty) {
      alertLines.update(state.alerts, state.tracks, volumes);
      highlightAlerted();
      if (alertsDirty || volumesDirty) volumes.highlight(state.alerts);
      volumesDirty = false;
      if (selectedAlert && !state.alerts.has(selectedAlert)) selectedAlert = null;
      labels.update(state.alerts, selectedAlert);
    }
    if (alertsDirty) {
      alertList.render(state.alerts);
      alertsDirty = false;
    }
    setCount("aircraft-count", aircraft.count());
    setCount("alert-count", alertLines.count());
    fitOnce();
  }

  function setCount(id, n) {
    const el = $(id);
    if (el.dataset.count !== String(n)) {
      el.dataset.count = String(n);
      el.textContent = n.toLocaleString("en");
    }
  }

  // A ring of the alert's colour around each aircraft of an alert (both of a pair, the
  // one of an area alert).
  function highlightAlerted() {
    const now = new Map();
    for (const a of state.alerts.values()) {
      for (const p of Kew.alertParties(a)) {
        const key = Kew.trackKey(p.src, p.id);
        const prev = now.get(key);
        if (!prev || Kew.SEVERITY_RANK[a.severity] > Kew.SEVERITY_RANK[prev]) now.set(key, a.severity);
      }
    }
    for (const key of alertedBefore.keys()) if (!now.has(key)) aircraft.setAlerted(key, null);
    for (const [key, severity] of now) aircraft.setAlerted(key, severity);
    alertedBefore = now;
  }

  function fitOnce() {
    if (fitted || userMoved || state.tracks.size === 0) return;
    const bounds = L.latLngBounds(Array.from(state.tracks.values(), (t) => [t.lat, t.lon]));
    map.fitBounds(bounds.pad(0.05), { maxZoom: 9, animate: false });
    fitted = true;
  }

  // Zooms to the pair: both aircraft in view (where their tracks are and where the alert
  // saw them) with a margin that leaves room for their labels, as close as PAIR_MAX_ZOOM;
  // the pair's labels are then laid out first. An area alert: its aircraft and the whole
  // volume (a followed one's circle) in view.
  function centreOnAlert(id) {
    const a = state.alerts.get(id);
    if (!a) return;
    const seen = Kew.alertParties(a).filter((p) => typeof p.lat === "number" && typeof p.lon === "number")
      .map((p) => [p.lat, p.lon]);
    const ends = Kew.alertEnds(a, state.tracks);
    const volume = Kew.isAreaAlert(a) ? volumes.extent(a.volume) : [];
    const bounds = L.latLngBounds(ends.concat(seen, volume));
    userMoved = true;
    selectedAlert = id;
    map.fitBounds(bounds, { padding: [120, 120], maxZoom: PAIR_MAX_ZOOM });
    labels.update(state.alerts, selectedAlert);
    for (const li of document.querySelectorAll("#alert-list .selected")) li.classList.remove("selected");
    const row = document.querySelector('#alert-list [data-alert-id="' + CSS.escape(id) + '"]');
    if (row) row.classList.add("selected");
  }

  // The pipeline's clock now: /api/status's data_t moved on by the local time since.
  function dataClock() {
    const s = state.status;
    if (!s || typeof s.data_t !== "number") return null;
    return s.data_t + (Date.now() - s.receivedAt) / 1000;
  }

  function renderHealth() {
    const alive = state.alive;
    const s = state.status;
    const health = $("feed-health");
    if (alive) {
      const name = alive.health || (alive.degraded ? "degraded" : "healthy");
      health.textContent = name.replace(/_/g, " ");
      health.dataset.health = name;
      health.dataset.degraded = alive.degraded ? "true" : "false";
      const rate = alive.rates && alive.rates.records_per_s;
      $("feed-rate").textContent = typeof rate === "number" ? rate.toFixed(1) : "—";
    }
    const clock = dataClock();
    const last = alive && typeof alive.t === "number" ? alive.t : null;
    const ageFrom = clock !== null ? clock : Date.now() / 1000;
    $("data-age").textContent = last !== null ? Kew.duration(ageFrom - last) : "no data";
    $("data-time").textContent = Kew.utc(clock !== null ? clock : last);
    const replay = s && typeof s.data_t === "number" && typeof s.wall_t === "number" &&
      Math.abs(s.data_t - s.wall_t) > REPLAY_THRESHOLD_S;
    const replayEl = $("replay-clock");
    replayEl.hidden = !replay;
    if (replay) $("replay-time").textContent = Kew.utc(clock);
    document.body.classList.toggle("replay", !!replay);
  }
  setInterval(renderHealth, 1000);
  refreshZones();
  setInterval(refreshZones, ZONES_INTERVAL_MS);

  Kew.state = state; // for the browser's console and tests
  Kew.map = map;
  Kew.volumes = volumes;
  connection.start();
})(window.Kew);

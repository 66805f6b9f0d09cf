// kew live map: the map's layers — the offline base map, aircraft, trails and alert lines
// (pairs, and area alerts' aircraft to their volumes; the volumes are map-volumes.js's).
//
// Cost per tick is proportional to what changed: an aircraft's marker is created once and
// then only moved, rotated, recoloured or relabelled when its figures change; all trails
// are one canvas polyline; alert lines (a few) are SVG paths so each carries its id.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const TRAIL_POINTS = 10;

  // North-up aircraft silhouette, 24×24, rotated by track; fill follows CSS `color`.
  const AIRCRAFT_SVG =
    '<svg class="ac-symbol" viewBox="0 0 24 24" width="20" height="20" aria-hidden="true">' +
    '<path d="M12 1.5 L13.6 8.6 L21.5 13 L21.5 14.8 L13.6 12.6 L13.1 18.4 L15.8 20.4 L15.8 21.8 ' +
    'L12 20.8 L8.2 21.8 L8.2 20.4 L10.9 18.4 L10.4 12.6 L2.5 14.8 L2.5 13 L10.4 8.6 Z"/></svg>';
  const NO_HEADING_SVG =
    '<svg class="ac-symbol" viewBox="0 0 24 24" width="14" height="14" aria-hidden="true">' +
    '<rect x="5" y="5" width="14" height="14"/></svg>';

  // The base map: Natural Earth land (with its coastlines as outlines) and country borders,
  // vendored in web/vendor (web/LICENSES.md). Drawn on its own canvas under everything.
  Kew.addBaseMap = function (map) {
    const renderer = L.canvas({ pane: "basemap", padding: 0.5 }); // under the zones and reference layers
    map.createPane("basemap");
    map.getPane("basemap").style.zIndex = 150;
    return fetch("vendor/naturalearth-50m.json")
      .then((r) => {
        if (!r.ok) throw new Error("HTTP " + r.status);
        return r.json();
      })
      .then((data) => {
        L.geoJSON(data.land, {
          pane: "basemap", renderer, interactive: false,
          style: { color: "#5d7385", weight: 0.8, fillColor: "#1f2b33", fillOpacity: 1 },
        }).addTo(map);
        L.geoJSON(data.borders, {
          pane: "basemap", renderer, interactive: false,
          style: { color: "#4b5b68", weight: 0.7, dashArray: "4 3", fill: false },
        }).addTo(map);
        document.getElementById("map").dataset.basemap = "loaded";
      })
      .catch((e) => {
        document.getElementById("map").dataset.basemap = "failed";
        console.warn("kew: base map not loaded:", e);
      });
  };

  Kew.AircraftLayer = class {
    constructor(map) {
      this.map = map;
      this.markers = new Map(); // track key -> {marker, sym, name, data, color, rot, ...}
      map.createPane("trails");
      map.getPane("trails").style.zIndex = 390;
      this.trailRenderer = L.canvas({ pane: "trails", padding: 0.3 });
      this.trails = L.polyline([], {
        renderer: this.trailRenderer, pane: "trails", interactive: false,
        color: "#9fb3c8", weight: 1.2, opacity: 0.55,
      }).addTo(map);
      this.trailsShown = true;
    }

    count() {
      return this.markers.size;
    }

    // Creates or updates the marker of `track` (the page's track record, kew-map.js).
    upsert(track) {
      let m = this.markers.get(track.key);
      const hasHeading = typeof track.trk_deg === "number" && isFinite(track.trk_deg);
      if (!m || m.hasHeading !== hasHeading) {
        if (m) this.map.removeLayer(m.marker);
        const icon = L.divIcon({
          className: "aircraft",
          iconSize: [0, 0],
          html: '<div class="leader"></div>' + (hasHeading ? AIRCRAFT_SVG : NO_HEADING_SVG) +
                '<div class="ac-label"><span class="ac-name"></span><span class="ac-data"></span></div>',
        });
        const marker = L.marker([track.lat, track.lon], { icon, keyboard: false, interactive: false }).addTo(this.map);
        const el = marker.getElement();
        el.dataset.trackId = track.id;
        el.dataset.trackSrc = track.src || "";
        m = {
          marker, el, hasHeading,
          sym: el.querySelector(".ac-symbol"),
          label: el.querySelector(".ac-label"),
          name: el.querySelector(".ac-name"),
          data: el.querySelector(".ac-data"),
          lat: track.lat, lon: track.lon, color: "", rot: null, nameText: "", dataText: "",
        };
        this.markers.set(track.key, m);
      } else if (m.lat !== track.lat || m.lon !== track.lon) {
        m.marker.setLatLng([track.lat, track.lon]);
        m.lat = track.lat;
        m.lon = track.lon;
      }
      m.gnd = track.gnd;
      const color = Kew.altitudeColor(track);
      if (color !== m.color) {
        m.el.style.color = color;
        m.color = color;
      }
      const rot = hasHeading ? Math.round(track.trk_deg) : 0;
      if (rot !== m.rot) {
        m.sym.style.transform = "rotate(" + rot + "deg)";
        m.rot = rot;
      }
      const nameText = Kew.trackName(track);
      if (nameText !== m.nameText) {
        m.name.textContent = nameText;
        m.nameText = nameText;
      }
      const dataText = Kew.flightLevel(track.alt_ft) + Kew.verticalArrow(track.vr_fpm) + " " + Kew.speed(track.gs_kt);
      if (dataText !== m.dataText) {
        m.data.textContent = dataText;
        m.dataText = dataText;
      }
    }

    remove(key) {
      const m = this.markers.get(key);
      if (!m) return;
      this.map.removeLayer(m.marker);
      this.markers.delete(key);
    }

    setAlerted(key, severity) {
      const m = this.markers.get(key);
      if (!m) return;
      const want = severity ? "sev-" + severity : "";
      if (m.el.dataset.alert !== want) {
        m.el.dataset.alert = want;
      }
    }

    // All trails as one multi-polyline: one canvas redraw per tick, whatever the count.
    redrawTrails(tracks) {
      if (!this.trailsShown) {
        this.trails.setLatLngs([]);
        return;
      }
      const lines = [];
      for (const t of tracks.values()) if (t.trail.length >= 2) lines.push(t.trail);
      this.trails.setLatLngs(lines);
    }

    showTrails(on, tracks) {
      this.trailsShown = on;
      this.redrawTrails(tracks);
    }
  };

  Kew.pushTrail = function (track) {
    const last = track.trail[track.trail.length - 1];
    if (last && last[0] === track.lat && last[1] === track.lon) return;
    track.trail.push([track.lat, track.lon]);
    if (track.trail.length > TRAIL_POINTS) track.trail.shift();
  };

  // One SVG line per active alert between its two aircraft, coloured by severity, with
  // t_los and CPA in a permanent label at its middle. Ends follow the aircraft's latest
  // positions (tracks update more often than alerts). An area alert's line runs from its
  // aircraft to the nearest point of the volume's boundary (map-volumes.js), with the
  // time to entry; while the page does not know the volume's shape, it is a point at the
  // aircraft, which still carries the figures.
  Kew.AlertLines = class {
    constructor(map) {
      this.map = map;
      this.lines = new Map(); // alert id -> {line, severity, ack, text}
      this.renderer = L.svg({ padding: 0.5 });
    }

    count() {
      return this.lines.size;
    }

    // `volumes`: the VolumeLayer, for area alerts.
    update(alerts, tracks, volumes) {
      for (const [id, entry] of this.lines) {
        if (!alerts.has(id)) {
          this.map.removeLayer(entry.line);
          this.lines.delete(id);
        }
      }
      for (const a of alerts.values()) {
        const area = Kew.isAreaAlert(a);
        const ends = lineEnds(a, tracks, volumes);
        let entry = this.lines.get(a.id);
        if (!entry) {
          const line = L.polyline(ends, {
            renderer: this.renderer, weight: 3, opacity: 0.95, interactive: true,
            className: area ? "alert-line area" : "alert-line",
          }).addTo(this.map);
          line.bindTooltip("", { permanent: true, direction: "center", className: "alert-label", opacity: 0.95 });
          line.getElement().setAttribute("data-alert-id", a.id);
          if (area) line.getElement().setAttribute("data-alert-volume", a.volume);
          entry = { line, severity: null, ack: null, text: null };
          this.lines.set(a.id, entry);
        } else {
          entry.line.setLatLngs(ends);
        }
        // The figures sit at the middle of the pair (map-labels.js moves them off it when
        // they would overprint).
        entry.line.getTooltip().setLatLng([(ends[0][0] + ends[1][0]) / 2, (ends[0][1] + ends[1][1]) / 2]);
        if (entry.severity !== a.severity || entry.ack !== a.ack) {
          entry.line.setStyle({ color: Kew.SEVERITY_COLOR[a.severity] || "#888", dashArray: a.ack ? "8 6" : null });
          const el = entry.line.getElement();
          el.setAttribute("data-severity", a.severity);
          el.setAttribute("data-ack", a.ack ? "true" : "false");
          entry.severity = a.severity;
          entry.ack = a.ack;
        }
        // A loss says so itself ("LoS now"); the others name their severity first.
        const text = (a.severity === "loss" && !area ? "" : Kew.SEVERITY_SHORT[a.severity] + " ") +
          (area ? Kew.areaSummary(a) : Kew.alertSummary(a));
        if (text !== entry.text) {
          entry.line.setTooltipContent(text);
          const tip = entry.line.getTooltip().getElement();
          if (tip) {
            tip.setAttribute("data-alert-label", a.id);
            tip.dataset.severity = a.severity;
          }
          entry.text = text;
        }
      }
    }
  };

  // The zones of design §4.9 (GET /api/zones): each core as a faint outline with its
  // name, tracks and the time its work took, in a layer the user may hide. A single
  // plane has no cores to draw.
  Kew.ZoneLayer = class {
    constructor(map) {
      map.createPane("zones");
      map.getPane("zones").style.zIndex = 200;
      this.group = L.layerGroup().addTo(map);
      this.rects = new Map(); // zone name -> rectangle
      this.renderer = L.svg({ pane: "zones" });
    }

    update(reply) {
      const seen = new Set();
      for (const z of reply.list || []) {
        if (z.south === undefined) continue;
        seen.add(z.name);
        let rect = this.rects.get(z.name);
        if (!rect) {
          rect = L.rectangle([[z.south, z.west], [z.north, z.east]], {
            renderer: this.renderer, pane: "zones", color: "#6f8fa8", weight: 1, opacity: 0.5,
            fill: false, dashArray: "2 4", interactive: true,
          });
          rect.bindTooltip("", { sticky: true, className: "zone-label" });
          rect.addTo(this.group);
          rect.getElement().setAttribute("data-zone", z.name);
          this.rects.set(z.name, rect);
        }
        rect.setTooltipContent(z.name + ": " + z.tracks + " tracks, " + z.busy_s.toFixed(1) + " s of work");
        rect.getElement().setAttribute("data-tracks", String(z.tracks));
      }
      for (const [name, rect] of this.rects) {
        if (seen.has(name)) continue;
        this.group.removeLayer(rect);
        this.rects.delete(name);
      }
      document.getElementById("map").dataset.zones = String(this.rects.size);
    }
  };

  // The positions of the alert's aircraft (both of a pair, one of an area alert): the
  // tracks' latest when known, else those the alert carries.
  function alertEnds(a, tracks) {
    return Kew.alertParties(a).map((p) => {
      const t = tracks.get(Kew.trackKey(p.src, p.id));
      return t ? [t.lat, t.lon] : [p.lat, p.lon];
    });
  }
  Kew.alertEnds = alertEnds;

  // The ends of the alert's line: the pair, or the aircraft and the volume's nearest
  // boundary point (the aircraft itself while the volume is unknown).
  function lineEnds(a, tracks, volumes) {
    const ends = alertEnds(a, tracks);
    if (ends.length === 2) return ends;
    const boundary = volumes ? volumes.nearestBoundary(a.volume, ends[0]) : null;
    return [ends[0], boundary || ends[0]];
  }
})(window.Kew);

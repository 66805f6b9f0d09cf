// kew live map: the volumes of the area proximity warning (design §4.11), from GET
// /api/volumes (a GeoJSON FeatureCollection, read again every VOLUMES_INTERVAL_MS for
// the schedules' active_now).
//
// A fixed volume is an SVG polygon (holes included) or circle styled by its kind; a
// volume that follows an aircraft is a circle around the track whose id or callsign its
// `follow` pattern matches, moved with it, and not drawn while no such track is seen.
// Kinds differ by colour (Okabe and Ito's colour-blind-safe palette, none of the
// severity colours), by line (thick, solid, dashed, dotted) and by fill (cross-hatched,
// hatched, tinted, none), so that they read apart without colour too; a volume outside
// its schedule is faint and dashed whatever its kind. The volume an area alert is about
// is outlined in the alert's severity colour (highlight()), and the alert's line runs
// from the aircraft to the volume's nearest boundary point (nearestBoundary()).
//
// Each volume's name is a label laid out with the others (map-labels.js), anchored at
// the polygon's centroid (or, when that is out of view, the middle of the part of its
// bounds in view), at a circle's centre, at the top of a followed circle.
//
// Hooks for tests: each volume's path has data-volume (its name), data-volume-kind,
// data-active ("true"/"false") and, while an alert is about it, data-alert ("sev-…");
// each label has data-volume; #map has data-volumes (how many the page knows) and
// data-volumes-drawn.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const VOLUMES_INTERVAL_MS = 30000;
  const METRES_PER_DEG = 111195; // along a meridian, for short local distances
  const SVG_NS = "http://www.w3.org/2000/svg";

  // Per kind: the outline's colour, weight and dashes, and the fill (a pattern defined
  // below or a tint).
  Kew.VOLUME_STYLES = {
    prohibited: { label: "prohibited", color: "#cc79a7", weight: 2.5, dashArray: null, hatch: "cross", fillOpacity: 0.7 },
    restricted: { label: "restricted", color: "#56b4e9", weight: 2, dashArray: null, hatch: "diagonal", fillOpacity: 0.6 },
    danger: { label: "danger", color: "#009e73", weight: 2, dashArray: "10 5", hatch: null, fillOpacity: 0.12 },
    watch: { label: "watch", color: "#bbbbbb", weight: 1.5, dashArray: "2 5", hatch: null, fillOpacity: 0 },
  };
  const INACTIVE = { opacity: 0.6, weight: 1.25, dashArray: "4 6", fillOpacity: 0 };

  function styleOf(kind) {
    return Kew.VOLUME_STYLES[kind] || Kew.VOLUME_STYLES.watch;
  }

  // The fills' patterns, once per page, in an SVG of their own that every other SVG's
  // url(#…) can reach.
  function definePatterns() {
    if (document.getElementById("kew-volume-patterns")) return;
    const svg = document.createElementNS(SVG_NS, "svg");
    svg.id = "kew-volume-patterns";
    svg.setAttribute("width", "0");
    svg.setAttribute("height", "0");
    svg.setAttribute("aria-hidden", "true");
    svg.style.position = "absolute";
    const defs = document.createElementNS(SVG_NS, "defs");
    for (const [kind, s] of Object.entries(Kew.VOLUME_STYLES)) {
      if (!s.hatch) continue;
      const pattern = document.createElementNS(SVG_NS, "pattern");
      pattern.id = "kew-hatch-" + kind;
      pattern.setAttribute("patternUnits", "userSpaceOnUse");
      pattern.setAttribute("width", "8");
      pattern.setAttribute("height", "8");
      pattern.setAttribute("patternTransform", "rotate(45)");
      const lines = s.hatch === "cross" ? [[0, 4, 8, 4], [4, 0, 4, 8]] : [[0, 4, 8, 4]];
      for (const [x1, y1, x2, y2] of lines) {
        const line = document.createElementNS(SVG_NS, "line");
        line.setAttribute("x1", x1);
        line.setAttribute("y1", y1);
        line.setAttribute("x2", x2);
        line.setAttribute("y2", y2);
        line.setAttribute("stroke", s.color);
        line.setAttribute("stroke-width", "1.2");
        pattern.append(line);
      }
      defs.append(pattern);
    }
    svg.append(defs);
    document.body.append(svg);
  }

  // Leaflet path options for a volume of `kind`, active or not.
  function pathStyle(kind, active) {
    const s = styleOf(kind);
    const fillColor = s.hatch ? "url(#kew-hatch-" + kind + ")" : s.color;
    if (!active) {
      return { color: s.color, weight: INACTIVE.weight, opacity: INACTIVE.opacity, dashArray: INACTIVE.dashArray,
               fill: true, fillColor, fillOpacity: INACTIVE.fillOpacity };
    }
    return { color: s.color, weight: s.weight, opacity: 0.95, dashArray: s.dashArray, fill: true, fillColor,
             fillOpacity: s.fillOpacity };
  }

  // A small picture of a kind's style for the legend.
  Kew.volumeSwatch = function (kind, active) {
    definePatterns();
    const st = pathStyle(kind, active);
    const svg = document.createElementNS(SVG_NS, "svg");
    svg.setAttribute("class", "volume-swatch");
    svg.setAttribute("width", "26");
    svg.setAttribute("height", "14");
    svg.setAttribute("aria-hidden", "true");
    const rect = document.createElementNS(SVG_NS, "rect");
    rect.setAttribute("x", "1.5");
    rect.setAttribute("y", "1.5");
    rect.setAttribute("width", "23");
    rect.setAttribute("height", "11");
    rect.setAttribute("stroke", st.color);
    rect.setAttribute("stroke-width", String(Math.min(st.weight, 2)));
    rect.setAttribute("stroke-opacity", String(st.opacity));
    if (st.dashArray) rect.setAttribute("stroke-dasharray", st.dashArray);
    rect.setAttribute("fill", st.fillOpacity > 0 ? st.fillColor : "none");
    rect.setAttribute("fill-opacity", String(st.fillOpacity));
    svg.append(rect);
    return svg;
  };

  // `text` matches `pattern` ('*' any run, '?' one character, no case), as kewd matches
  // a volume's `follow` (kew/util/wildcard.hpp).
  Kew.wildcardMatch = function (pattern, text) {
    const p = String(pattern).toUpperCase();
    const t = String(text).toUpperCase();
    let pi = 0, ti = 0, star = -1, mark = 0;
    while (ti < t.length) {
      if (pi < p.length && (p[pi] === "?" || p[pi] === t[ti])) {
        pi++;
        ti++;
      } else if (pi < p.length && p[pi] === "*") {
        star = pi++;
        mark = ti;
      } else if (star >= 0) {
        pi = star + 1;
        ti = ++mark;
      } else {
        return false;
      }
    }
    while (pi < p.length && p[pi] === "*") pi++;
    return pi === p.length;
  };

  function namesTrack(pattern, track) {
    const cs = (track.cs || "").trim();
    return Kew.wildcardMatch(pattern, track.id) || (cs !== "" && Kew.wildcardMatch(pattern, cs));
  }

  // Local metres east and north of `origin` ([lat, lon]) for a point near it.
  function local(origin, p) {
    const k = Math.cos((origin[0] * Math.PI) / 180);
    let dlon = p[1] - origin[1];
    dlon -= 360 * Math.round(dlon / 360);
    return [dlon * k * METRES_PER_DEG, (p[0] - origin[0]) * METRES_PER_DEG];
  }

  function fromLocal(origin, xy) {
    const k = Math.max(1e-6, Math.cos((origin[0] * Math.PI) / 180));
    return [origin[0] + xy[1] / METRES_PER_DEG, origin[1] + xy[0] / (k * METRES_PER_DEG)];
  }

  // The point at `radius_m` from `centre` towards `p` (north when p is the centre).
  function circlePointTowards(centre, radius_m, p) {
    const [x, y] = local(centre, p);
    const d = Math.hypot(x, y);
    return fromLocal(centre, d > 0 ? [(x / d) * radius_m, (y / d) * radius_m] : [0, radius_m]);
  }

  // Ray casting on [lat, lon] rings (outer first): inside the outer ring, outside the holes.
  function insideRings(rings, p) {
    let inside = false;
    rings.forEach((ring) => {
      let crossing = false;
      for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
        const [yi, xi] = ring[i];
        const [yj, xj] = ring[j];
        if (yi > p[0] !== yj > p[0] && p[1] < ((xj - xi) * (p[0] - yi)) / (yj - yi) + xi) crossing = !crossing;
      }
      if (crossing) inside = !inside;
    });
    return inside;
  }

  // The area-weighted centroid of a ring of [lat, lon], or its first vertex when flat.
  function centroid(ring) {
    let a = 0, x = 0, y = 0;
    for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
      const f = ring[j][1] * ring[i][0] - ring[i][1] * ring[j][0];
      a += f;
      x += (ring[j][1] + ring[i][1]) * f;
      y += (ring[j][0] + ring[i][0]) * f;
    }
    if (Math.abs(a) < 1e-12) return ring[0];
    return [y / (3 * a), x / (3 * a)];
  }

  Kew.VolumeLayer = class {
    // `tracks`: the page's tracks (key -> track), which followed circles are centred on.
    constructor(map, tracks) {
      this.map = map;
      map.createPane("volumes");
      map.getPane("volumes").style.zIndex = 300; // above the reference layers, under trails and alerts
      map.createPane("volumeLabels");
      map.getPane("volumeLabels").style.zIndex = 595; // over the reference labels, under the aircraft
      this.renderer = L.svg({ pane: "volumes", padding: 0.5 });
      this.group = L.layerGroup().addTo(map);
      this.entries = new Map(); // name -> entry (see add())
      this.highlighted = new Map(); // name -> severity
      this.tracks = tracks || new Map();
      this.lastScan = 0;
      definePatterns();
      map.on("overlayadd overlayremove", () => this.count());
    }

    // GET /api/volumes now and every VOLUMES_INTERVAL_MS; `changed` is called after each
    // reply that was applied.
    start(changed) {
      const load = () =>
        Kew.getJson("api/volumes")
          .then((fc) => {
            this.update(fc);
            changed();
          })
          .catch((e) => console.warn("kew: volumes not loaded:", e));
      load();
      setInterval(load, VOLUMES_INTERVAL_MS);
    }

    // Applies a FeatureCollection: new volumes drawn, changed ones restyled, gone ones removed.
    update(fc) {
      const seen = new Set();
      for (const f of (fc && Array.isArray(fc.features) ? fc.features : [])) {
        const p = f && f.properties;
        if (!p || typeof p.name !== "string") continue;
        seen.add(p.name);
        let entry = this.entries.get(p.name);
        const shape = JSON.stringify([f.geometry, p.follow, p.radius_m]);
        if (entry && entry.shape !== shape) {
          this.removeEntry(entry);
          entry = null;
        }
        if (!entry) entry = this.add(f, shape);
        entry.props = p;
        this.restyle(entry);
      }
      for (const entry of Array.from(this.entries.values())) if (!seen.has(entry.name)) this.removeEntry(entry);
      this.map.getContainer().dataset.volumes = String(this.entries.size);
      this.follow(this.tracks, true);
      this.count();
    }

    add(f, shape) {
      const p = f.properties;
      const entry = { name: p.name, shape, props: p, layer: null, rings: null, centre: null, radius: 0,
                      followed: typeof p.follow === "string" && !f.geometry, trackKey: null, follows: null,
                      label: null, anchor: null, styleKey: null };
      const g = f.geometry;
      if (entry.followed) {
        entry.radius = p.radius_m;
      } else if (p.circle && typeof p.circle.radius_m === "number") {
        entry.centre = [p.circle.lat, p.circle.lon];
        entry.radius = p.circle.radius_m;
        // kewd's geodesic outline when given, else Leaflet's circle.
        if (g && g.type === "Polygon" && Array.isArray(g.coordinates) && g.coordinates.length > 0) {
          entry.rings = g.coordinates.map((ring) => ring.slice(0, -1).map(([lon, lat]) => [lat, lon]));
          entry.layer = L.polygon(entry.rings, { renderer: this.renderer, pane: "volumes" });
        } else {
          entry.layer = L.circle(entry.centre, { radius: entry.radius, renderer: this.renderer, pane: "volumes" });
        }
      } else if (g && g.type === "Polygon" && Array.isArray(g.coordinates) && g.coordinates.length > 0) {
        // [lon, lat] closed rings to Leaflet's [lat, lon], the repeated vertex left out.
        entry.rings = g.coordinates.map((ring) => ring.slice(0, -1).map(([lon, lat]) => [lat, lon]));
        entry.layer = L.polygon(entry.rings, { renderer: this.renderer, pane: "volumes" });
      } else {
        return this.keep(entry); // a shape this page does not know: listed, not drawn
      }
      if (entry.layer) this.attach(entry);
      return this.keep(entry);
    }

    keep(entry) {
      this.entries.set(entry.name, entry);
      return entry;
    }

    // Puts the entry's shape and label in the group (a followed circle: once its aircraft
    // is seen); their elements exist while the group is on the map, and are marked and
    // styled each time they are made.
    attach(entry) {
      entry.layer.bindTooltip("", { sticky: true, className: "volume-tip" });
      entry.layer.on("add", () => {
        const el = entry.layer.getElement();
        el.setAttribute("data-volume", entry.name);
        if (entry.follows) el.setAttribute("data-follows", entry.follows);
        el.classList.add("volume");
        entry.styleKey = null;
        this.restyle(entry);
      });
      const icon = L.divIcon({ className: "ref-label volume", iconSize: [0, 0],
                               html: '<div class="leader"></div><div class="map-label"></div>' });
      entry.anchor = this.anchorOf(entry) || [0, 0];
      entry.label = L.marker(entry.anchor, { icon, pane: "volumeLabels", keyboard: false, interactive: false });
      entry.label.on("add", () => {
        const el = entry.label.getElement();
        el.dataset.volume = entry.name;
        el.querySelector(".map-label").textContent = entry.name;
        entry.styleKey = null;
        this.restyle(entry);
      });
      entry.layer.addTo(this.group);
      entry.label.addTo(this.group);
    }

    detach(entry) {
      if (entry.layer) this.group.removeLayer(entry.layer);
      if (entry.label) this.group.removeLayer(entry.label);
      entry.label = null;
    }

    removeEntry(entry) {
      this.detach(entry);
      this.entries.delete(entry.name);
    }

    restyle(entry) {
      if (!entry.layer || !entry.layer.getElement()) return;
      const p = entry.props;
      const active = p.active_now !== false;
      const severity = this.highlighted.get(entry.name) || null;
      const key = [p.kind, active, severity].join("|");
      if (key !== entry.styleKey) {
        const style = pathStyle(p.kind, active);
        if (severity) {
          style.color = Kew.SEVERITY_COLOR[severity] || style.color;
          style.weight = Math.max(style.weight, 2) + 1.5;
          style.opacity = 1;
        }
        entry.layer.setStyle(style);
        const el = entry.layer.getElement();
        el.setAttribute("data-volume-kind", p.kind);
        el.setAttribute("data-active", active ? "true" : "false");
        el.setAttribute("data-alert", severity ? "sev-" + severity : "");
        el.classList.toggle("inactive", !active);
        const labelEl = entry.label && entry.label.getElement();
        if (labelEl) {
          labelEl.classList.toggle("inactive", !active);
          labelEl.dataset.alert = severity ? "sev-" + severity : "";
          labelEl.dataset.kind = p.kind;
        }
        entry.styleKey = key;
      }
      entry.layer.setTooltipContent(this.describe(entry));
    }

    // "EDR-1 · restricted · 0–5,000 ft · look-ahead 120 s, warning 60 s", whether it is
    // inactive now, and a followed one's band about its aircraft ("-1,000 to +1,000 ft
    // about CHX*").
    describe(entry) {
      const p = entry.props;
      const ft = (v) => (typeof v === "number" ? Math.round(v).toLocaleString("en") : "?");
      const signed = (v) => (typeof v === "number" && v > 0 ? "+" : "") + ft(v);
      const band = entry.followed ? signed(p.floor_ft) + " to " + signed(p.ceiling_ft) + " ft about " + (p.follow || "")
                                  : ft(p.floor_ft) + "–" + ft(p.ceiling_ft) + " ft";
      return p.name + " · " + p.kind + (p.active_now === false ? " (inactive now)" : "") + " · " + band +
             " · look-ahead " + Kew.seconds(p.lookahead_s) + ", warning " + Kew.seconds(p.warning_s);
    }

    // Moves each followed circle to its aircraft (the page's tracks, key -> track): the
    // one it followed while that one is seen, as the pipeline keeps its centre (design
    // §4.11), else the first that matches in key order (scanned for at most once a second
    // while there is none). With several matching tracks the page may pick another than
    // the pipeline did.
    follow(tracks, force) {
      this.tracks = tracks;
      const now = Date.now();
      const scan = force || now - this.lastScan > 1000;
      let scanned = false;
      let keys = null; // the tracks' keys in order, sorted once per call at most
      for (const entry of this.entries.values()) {
        if (!entry.followed) continue;
        let t = entry.trackKey ? tracks.get(entry.trackKey) : null;
        if (!t && scan) {
          scanned = true;
          if (!keys) keys = Array.from(tracks.keys()).sort();
          const key = keys.find((k) => namesTrack(entry.props.follow, tracks.get(k)));
          t = key ? tracks.get(key) : null;
        }
        entry.trackKey = t ? t.key : null;
        if (!t) {
          if (entry.layer) {
            this.detach(entry);
            entry.layer = null;
          }
          entry.centre = null;
          entry.follows = null;
          continue;
        }
        const same = entry.layer && entry.centre && entry.centre[0] === t.lat && entry.centre[1] === t.lon &&
                     entry.follows === t.id;
        if (same) continue;
        entry.centre = [t.lat, t.lon];
        entry.follows = t.id;
        if (!entry.layer) {
          entry.layer = L.circle(entry.centre, { radius: entry.radius, renderer: this.renderer, pane: "volumes" });
          this.attach(entry);
        } else {
          entry.layer.setLatLng(entry.centre);
          const el = entry.layer.getElement();
          if (el) el.setAttribute("data-follows", t.id);
        }
        const anchor = this.anchorOf(entry);
        entry.label.setLatLng(anchor);
        entry.anchor = anchor;
      }
      if (scanned) this.lastScan = now;
      this.count();
    }

    count() {
      let drawn = 0;
      for (const entry of this.entries.values()) if (entry.layer && this.map.hasLayer(entry.layer)) drawn++;
      const container = this.map.getContainer();
      if (container.dataset.volumesDrawn !== String(drawn)) container.dataset.volumesDrawn = String(drawn);
    }

    // Where the name hangs: see the header.
    anchorOf(entry) {
      if (entry.followed) return entry.centre ? fromLocal(entry.centre, [0, entry.radius]) : null;
      if (entry.centre) return entry.centre;
      if (!entry.rings) return null;
      if (!entry.centroid) {
        const c = centroid(entry.rings[0]);
        entry.centroid = insideRings(entry.rings, c) ? c : entry.rings[0][0];
        entry.bounds = L.latLngBounds(entry.rings[0]);
      }
      const view = this.map.getBounds();
      if (view.contains(entry.centroid) || !view.intersects(entry.bounds)) return entry.centroid;
      const south = Math.max(view.getSouth(), entry.bounds.getSouth());
      const north = Math.min(view.getNorth(), entry.bounds.getNorth());
      const west = Math.max(view.getWest(), entry.bounds.getWest());
      const east = Math.min(view.getEast(), entry.bounds.getEast());
      return [(south + north) / 2, (west + east) / 2];
    }

    // The labels to lay out (map-labels.js): [{key, kind, latlng, el, r, priority}]; below
    // the aircraft's, above the aerodromes'. A highlighted volume's name comes first.
    labels() {
      const out = [];
      if (!this.map.hasLayer(this.group)) return out;
      let i = 0;
      for (const entry of this.entries.values()) {
        i++;
        if (!entry.label || !entry.layer) continue;
        const anchor = this.anchorOf(entry);
        if (!anchor) continue;
        if (!entry.anchor || entry.anchor[0] !== anchor[0] || entry.anchor[1] !== anchor[1]) {
          entry.label.setLatLng(anchor);
          entry.anchor = anchor;
        }
        const el = entry.label.getElement();
        if (!el) continue;
        const alerted = this.highlighted.has(entry.name);
        out.push({ key: "vol" + entry.name, kind: "volume", latlng: L.latLng(anchor), el, r: 0,
                   priority: (alerted ? 9e5 : 8e5) - i / 1e4 });
      }
      return out;
    }

    // Outlines the volumes of `alerts` (the page's Map id -> ALERT) in their most severe
    // alert's colour.
    highlight(alerts) {
      const now = new Map();
      for (const a of alerts.values()) {
        if (!Kew.isAreaAlert(a)) continue;
        const prev = now.get(a.volume);
        if (!prev || Kew.SEVERITY_RANK[a.severity] > Kew.SEVERITY_RANK[prev]) now.set(a.volume, a.severity);
      }
      this.highlighted = now;
      for (const entry of this.entries.values()) this.restyle(entry);
    }

    // The point of the volume's boundary nearest `p` ([lat, lon]), or null when the page
    // does not know the volume or a followed one's aircraft.
    nearestBoundary(name, p) {
      const entry = this.entries.get(name);
      if (!entry) return null;
      if (entry.followed) return entry.centre ? circlePointTowards(entry.centre, entry.radius, p) : null;
      if (entry.centre && entry.radius > 0) return circlePointTowards(entry.centre, entry.radius, p);
      if (!entry.rings) return null;
      let best = null;
      let bestD = Infinity;
      for (const ring of entry.rings) {
        for (let i = 0; i < ring.length; i++) {
          const a = local(p, ring[i]);
          const b = local(p, ring[(i + 1) % ring.length]);
          const dx = b[0] - a[0], dy = b[1] - a[1];
          const len2 = dx * dx + dy * dy;
          const u = len2 > 0 ? Math.max(0, Math.min(1, -(a[0] * dx + a[1] * dy) / len2)) : 0;
          const q = [a[0] + u * dx, a[1] + u * dy];
          const d = Math.hypot(q[0], q[1]);
          if (d < bestD) {
            bestD = d;
            best = q;
          }
        }
      }
      return best ? fromLocal(p, best) : null;
    }

    // The volume's extent as [[lat, lon], …] (its bounds' corners), or [] when unknown.
    extent(name) {
      const entry = this.entries.get(name);
      if (!entry) return [];
      let b = null;
      if (entry.rings) b = L.latLngBounds(entry.rings[0]);
      else if (entry.centre && entry.radius > 0) b = L.latLng(entry.centre).toBounds(2 * entry.radius);
      if (!b || !b.isValid()) return [];
      return [[b.getSouth(), b.getWest()], [b.getNorth(), b.getEast()]];
    }

    // The legend: one row per kind, then an inactive one.
    legend(list) {
      for (const kind of ["prohibited", "restricted", "danger", "watch"]) {
        const li = document.createElement("li");
        li.dataset.kind = kind;
        li.append(Kew.volumeSwatch(kind, true), Kew.VOLUME_STYLES[kind].label);
        list.append(li);
      }
      const li = document.createElement("li");
      li.dataset.kind = "inactive";
      li.append(Kew.volumeSwatch("restricted", false), "inactive now (schedule)");
      list.append(li);
    }

    // For the layers control.
    overlays() {
      return { volumes: this.group };
    }
  };
})(window.Kew);

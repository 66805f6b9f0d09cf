// kew live map: the labels on the map laid out so that none overprints another
// (label-placement.js decides, this writes). Runs after each redraw and each move or zoom
// of the map, over the labels in view: aircraft (an alerting pair's always, the others
// from LABEL_MIN_ZOOM with "labels" ticked), alert lines' figures, the volumes' names
// (map-volumes.js), aerodromes and range rings. Order: the aircraft of the alerts (a
// pair's two, an area alert's one), most severe first (the selected alert before all),
// then the alerts' figures, the other aircraft (airborne before on the ground), the
// volumes (those of an alert first), aerodromes, range rings. A dropped label is hidden (visibility, so that it keeps its size).
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const LABEL_MIN_ZOOM = 6;
  const SYMBOL_R = 10; // px, half the aircraft symbol: labels start beyond it
  const SYMBOL_BOX = 8; // px, half the box a label should not cover

  Kew.LabelLayout = class {
    // layers: {aircraft: AircraftLayer, alertLines: AlertLines, reference: ReferenceLayer,
    // volumes: VolumeLayer (optional)}
    constructor(map, layers, showLabels) {
      this.map = map;
      this.layers = layers;
      this.showLabels = showLabels; // () -> whether ordinary aircraft labels are wanted
      this.selected = null;
      this.alerts = new Map();
      this.frame = false;
      map.on("moveend zoomend resize", () => this.request());
    }

    // `alerts`: the page's Map id -> ALERT; `selected`: the alert chosen in the list.
    update(alerts, selected) {
      this.alerts = alerts;
      this.selected = selected;
      this.request();
    }

    request() {
      if (this.frame) return;
      this.frame = true;
      requestAnimationFrame(() => {
        this.frame = false;
        this.place();
      });
    }

    place() {
      const map = this.map;
      const size = map.getSize();
      const view = { x0: 0, y0: 0, x1: size.x, y1: size.y };
      const near = (p) => p.x >= -50 && p.y >= -50 && p.x <= size.x + 50 && p.y <= size.y + 50;
      const point = (latlng) => map.layerPointToContainerPoint(map.latLngToLayerPoint(latlng).round());
      const items = [];
      const hosts = new Map(); // item key -> what to write
      const symbols = [];

      // Alerting aircraft, by their most severe alert (the selected one first).
      const sorted = Array.from(this.alerts.values()).sort(Kew.compareAlerts);
      const rank = new Map();
      sorted.forEach((a, i) => {
        const r = a.id === this.selected ? -1 : i;
        for (const p of Kew.alertParties(a)) {
          const key = Kew.trackKey(p.src, p.id);
          if (!rank.has(key) || rank.get(key) > r) rank.set(key, r);
        }
      });
      const ordinary = this.showLabels() && map.getZoom() >= LABEL_MIN_ZOOM;
      const n = sorted.length + 2;
      for (const [key, m] of this.layers.aircraft.markers) {
        const p = point([m.lat, m.lon]);
        hosts.set("ac|" + key, { kind: "aircraft", m, p });
        if (!near(p)) continue;
        symbols.push({ x0: p.x - SYMBOL_BOX, y0: p.y - SYMBOL_BOX, x1: p.x + SYMBOL_BOX, y1: p.y + SYMBOL_BOX });
        const alerted = rank.has(key);
        if (!alerted && !ordinary) continue;
        const size = this.measure(m.label, m, m.nameText + "|" + m.dataText);
        const priority = alerted ? 3e6 + (n - rank.get(key)) : 1e6 + (m.gnd ? 0 : 1);
        items.push({ key: "ac|" + key, kind: "aircraft", x: p.x, y: p.y, r: SYMBOL_R, w: size.w, h: size.h,
                     priority, must: alerted });
      }
      // The alerts' figures, at the middle of their lines.
      sorted.forEach((a, i) => {
        const entry = this.layers.alertLines.lines.get(a.id);
        const tip = entry && entry.line.getTooltip();
        const el = tip && tip.getElement();
        if (!el) return;
        const p = point(tip.getLatLng());
        const w = el.offsetWidth;
        const h = el.offsetHeight;
        items.push({ key: "al|" + a.id, kind: "alert", x: p.x, y: p.y, w, h,
                     priority: 2e6 + (a.id === this.selected ? n : n - 1 - i) });
        hosts.set("al|" + a.id, { kind: "alert", el, p, w, h });
      });
      // Volumes, aerodromes and range rings: each layer says what it wants labelled.
      const fixed = this.layers.volumes ? this.layers.volumes.labels() : [];
      for (const label of fixed.concat(this.layers.reference.labels())) {
        const p = point(label.latlng);
        const key = "rf|" + label.key;
        hosts.set(key, { kind: label.kind, el: label.el, p });
        if (!near(p)) continue;
        const text = label.el.querySelector(".map-label");
        items.push({ key, kind: label.kind, x: p.x, y: p.y, r: label.r || 0, w: text.offsetWidth,
                     h: text.offsetHeight, priority: label.priority });
      }

      const placed = Kew.placeLabels(items, symbols, view);
      for (const [key, host] of hosts) this.write(host, placed.get(key) || null, host.p);
      map.getContainer().dataset.labels = String(placed.size);
    }

    // The label's size, measured again only when its text changed.
    measure(el, memo, text) {
      if (memo.labelText !== text || !memo.labelSize) {
        memo.labelText = text;
        memo.labelSize = { w: el.offsetWidth, h: el.offsetHeight };
      }
      return memo.labelSize;
    }

    // Shows `host`'s label at `box` (container px) or hides it (box null); `p` is its
    // anchor, the point its element hangs from.
    write(host, box, p) {
      if (host.kind === "alert") {
        const el = host.el;
        el.classList.toggle("label-dropped", !box);
        if (!box) return;
        // Leaflet centres the tooltip on its anchor; the margin moves it to the box.
        el.style.marginLeft = Math.round(box.x0 - (p.x - host.w / 2)) + "px";
        el.style.marginTop = Math.round(box.y0 - (p.y - host.h / 2)) + "px";
        return;
      }
      const el = host.kind === "aircraft" ? host.m.el : host.el;
      const label = host.kind === "aircraft" ? host.m.label : el.querySelector(".map-label");
      const leader = el.querySelector(".leader");
      el.classList.toggle("label-dropped", !box);
      if (!box) return;
      label.style.left = box.x0 - p.x + "px";
      label.style.top = box.y0 - p.y + "px";
      if (!leader) return;
      if (!box.leader) {
        leader.style.display = "none";
        return;
      }
      // From the anchor to the nearest point of the box.
      const nx = Math.max(box.x0, Math.min(p.x, box.x1)) - p.x;
      const ny = Math.max(box.y0, Math.min(p.y, box.y1)) - p.y;
      leader.style.display = "block";
      leader.style.width = Math.hypot(nx, ny).toFixed(1) + "px";
      leader.style.transform = "rotate(" + Math.atan2(ny, nx).toFixed(4) + "rad)";
    }
  };
})(window.Kew);

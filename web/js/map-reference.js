// kew live map: the reference layers — the base map (a tile server when kewd's
// [http] tile_url names one, else the offline Natural Earth map), the aerodromes of kewd's
// table (GET /api/aerodromes, the table the eligibility lower limit uses), range rings
// around the view's centre and a scale bar in nautical miles and kilometres.
//
// Aerodromes are culled to the view: none below AERODROME_DOT_ZOOM; a dot each from it;
// the ident (and the name, where the table has one, from AERODROME_NAME_ZOOM) from
// AERODROME_LABEL_ZOOM when at most MAX_AERODROME_LABELS are in view. Labels take their
// place with the aircraft's (map-labels.js), below them in priority.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const AERODROME_DOT_ZOOM = 6;
  const AERODROME_LABEL_ZOOM = 7;
  const AERODROME_NAME_ZOOM = 10;
  const MAX_AERODROME_DOTS = 2000;
  const MAX_AERODROME_LABELS = 150;
  const RING_STEPS_NM = [1, 2, 5, 10, 25, 50, 100, 250, 500];
  const RING_MIN_PX = 90; // rings at least this far apart on screen
  const RINGS = 5;
  const METRES_PER_NM = 1852;

  // The base map: `config` is GET /api/map-config. Tiles are darkened (style.css) so that
  // the aircraft's and alerts' colours keep their contrast.
  Kew.addBaseLayer = function (map, config) {
    const url = config && typeof config.tile_url === "string" ? config.tile_url : "";
    if (url === "") {
      map.attributionControl.addAttribution("Base map: Natural Earth (public domain)");
      return Kew.addBaseMap(map);
    }
    const attribution = document.createElement("span");
    attribution.textContent = config.tile_attribution || "";
    L.tileLayer(url, { attribution: attribution.innerHTML, maxZoom: 19, className: "kew-tiles" }).addTo(map);
    map.getContainer().dataset.basemap = "tiles";
    return Promise.resolve();
  };

  // Nautical miles (instead of Leaflet's statute miles) under the metric bar.
  const ScaleNm = L.Control.Scale.extend({
    _updateImperial(maxMetres) {
      const maxNm = maxMetres / METRES_PER_NM;
      const nm = maxNm >= 1 ? this._getRoundNum(maxNm) : [0.5, 0.2, 0.1].find((v) => v <= maxNm) || 0.05;
      this._updateScale(this._iScale, nm + " NM", nm / maxNm);
    },
  });

  Kew.ReferenceLayer = class {
    constructor(map) {
      this.map = map;
      map.createPane("reference");
      map.getPane("reference").style.zIndex = 250;
      map.createPane("referenceLabels");
      map.getPane("referenceLabels").style.zIndex = 590; // under the aircraft (600)
      this.renderer = L.canvas({ pane: "reference", padding: 0.2 });
      this.aerodromes = L.layerGroup().addTo(map);
      this.rings = L.layerGroup().addTo(map);
      this.table = []; // [{icao, name, lat, lon, elevation_ft}]
      this.cells = new Map(); // "lat,lon" (whole degrees) -> indices into table
      this.shown = new Map(); // icao -> {dot, marker}
      this.ringLabels = [];
      new ScaleNm({ metric: true, imperial: true, maxWidth: 140, position: "bottomleft" }).addTo(map);
      map.on("moveend zoomend", () => this.refresh());
      map.on("overlayadd overlayremove", () => this.refresh());
    }

    // GET /api/aerodromes once.
    load() {
      return Kew.getJson("api/aerodromes")
        .then((list) => {
          this.table = Array.isArray(list) ? list : [];
          this.table.forEach((a, i) => {
            const key = Math.floor(a.lat) + "," + Math.floor(a.lon);
            if (!this.cells.has(key)) this.cells.set(key, []);
            this.cells.get(key).push(i);
          });
          this.map.getContainer().dataset.aerodromes = String(this.table.length);
          this.refresh();
        })
        .catch((e) => console.warn("kew: aerodromes not loaded:", e));
    }

    refresh() {
      this.refreshAerodromes();
      this.refreshRings();
    }

    // The aerodromes in view (padded), in the table's order.
    inView() {
      const b = this.map.getBounds().pad(0.1);
      const out = [];
      for (let lat = Math.floor(b.getSouth()); lat <= Math.floor(b.getNorth()); lat++) {
        for (let lon = Math.floor(b.getWest()); lon <= Math.floor(b.getEast()); lon++) {
          const wrapped = ((((lon + 180) % 360) + 360) % 360) - 180;
          for (const i of this.cells.get(lat + "," + wrapped) || []) {
            const a = this.table[i];
            if (b.contains([a.lat, a.lon]) || b.contains([a.lat, a.lon + (lon - wrapped)])) out.push(i);
          }
        }
      }
      return out.sort((x, y) => x - y);
    }

    refreshAerodromes() {
      const zoom = this.map.getZoom();
      const on = this.map.hasLayer(this.aerodromes) && zoom >= AERODROME_DOT_ZOOM;
      const want = on ? this.inView().slice(0, MAX_AERODROME_DOTS) : [];
      const labelled = zoom >= AERODROME_LABEL_ZOOM && want.length <= MAX_AERODROME_LABELS;
      const named = zoom >= AERODROME_NAME_ZOOM;
      const keep = new Set(want.map((i) => this.table[i].icao));
      for (const [icao, shown] of this.shown) {
        if (keep.has(icao)) continue;
        this.aerodromes.removeLayer(shown.dot);
        if (shown.marker) this.aerodromes.removeLayer(shown.marker);
        this.shown.delete(icao);
      }
      for (const i of want) {
        const a = this.table[i];
        let shown = this.shown.get(a.icao);
        if (!shown) {
          const dot = L.circleMarker([a.lat, a.lon], {
            renderer: this.renderer, pane: "reference", radius: 3, weight: 1, color: "#c8d4dc", opacity: 0.8,
            fillColor: "#0b151d", fillOpacity: 1, interactive: false,
          }).addTo(this.aerodromes);
          shown = { dot, marker: null, index: i, text: "" };
          this.shown.set(a.icao, shown);
        }
        const text = labelled ? a.icao + (named && a.name ? " " + a.name : "") : "";
        if (text === shown.text) continue;
        if (shown.marker) this.aerodromes.removeLayer(shown.marker);
        shown.marker = text ? this.labelMarker([a.lat, a.lon], "aerodrome", text, { icao: a.icao }) : null;
        if (shown.marker) shown.marker.addTo(this.aerodromes);
        shown.text = text;
      }
      this.map.getContainer().dataset.aerodromesShown = String(this.shown.size);
    }

    // A label hanging from a 0×0 marker at `latlng`, laid out by map-labels.js.
    labelMarker(latlng, kind, text, data) {
      const icon = L.divIcon({ className: "ref-label " + kind, iconSize: [0, 0],
                               html: '<div class="leader"></div><div class="map-label"></div>' });
      const marker = L.marker(latlng, { icon, pane: "referenceLabels", keyboard: false, interactive: false });
      marker.on("add", () => {
        const el = marker.getElement();
        el.querySelector(".map-label").textContent = text;
        for (const [k, v] of Object.entries(data)) el.dataset[k] = v;
      });
      return marker;
    }

    // Rings around the view's centre, RINGS of them, a round step apart that is at least
    // RING_MIN_PX on screen; each with its distance where it crosses the centre's meridian
    // to the north.
    refreshRings() {
      this.rings.clearLayers();
      this.ringLabels = [];
      const map = this.map;
      const container = map.getContainer();
      if (!map.hasLayer(this.rings)) {
        container.dataset.rings = "0";
        return;
      }
      const centre = map.getCenter();
      const size = map.getSize();
      const metresPerPx = map.distance(map.containerPointToLatLng([0, size.y / 2]),
                                       map.containerPointToLatLng([size.x, size.y / 2])) / size.x;
      const step = RING_STEPS_NM.find((nm) => (nm * METRES_PER_NM) / metresPerPx >= RING_MIN_PX) ||
                   RING_STEPS_NM[RING_STEPS_NM.length - 1];
      for (let k = 1; k <= RINGS; k++) {
        const metres = k * step * METRES_PER_NM;
        L.circle(centre, { radius: metres, renderer: this.renderer, pane: "reference", color: "#7f95a6", weight: 1,
                           opacity: 0.45, fill: false, interactive: false }).addTo(this.rings);
        const north = [Math.min(89, centre.lat + metres / 111195), centre.lng];
        const marker = this.labelMarker(north, "ring", k * step + " NM", { ring: String(k * step) }).addTo(this.rings);
        this.ringLabels.push({ key: "ring" + k, marker, latlng: north });
      }
      container.dataset.rings = String(RINGS);
      container.dataset.ringStepNm = String(step);
    }

    // The labels to lay out: [{key, kind, latlng, el, r, priority}].
    labels() {
      const out = [];
      for (const shown of this.shown.values()) {
        const el = shown.marker && shown.marker.getElement();
        if (el) out.push({ key: "ad" + shown.index, kind: "aerodrome", latlng: shown.dot.getLatLng(), el, r: 3,
                           priority: 5e5 - shown.index / 1e5 });
      }
      for (const ring of this.ringLabels) {
        const el = ring.marker.getElement();
        if (el) out.push({ key: ring.key, kind: "fixed", latlng: ring.latlng, el, r: 0, priority: 1e5 });
      }
      return out;
    }

    // For the layers control.
    overlays() {
      return { aerodromes: this.aerodromes, "range rings": this.rings };
    }
  };
})(window.Kew);

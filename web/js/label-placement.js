// kew live map: where each label goes. Pure arithmetic on screen boxes (pixels of the map
// container, y down): no DOM, no Leaflet, so the same input always gives the same output.
//
// Each item is a label of w×h hanging from an anchor (x, y): an aircraft symbol, the middle
// of an alert line, an aerodrome dot. Items are placed one by one, highest `priority`
// first (ties by `key`); each takes the first of its candidate positions whose box meets no
// label placed before it and lies inside the view, preferring positions that cover no
// aircraft symbol. An aircraft's candidates are the eight compass points next to its
// symbol, then the same eight farther out in rings, joined to the symbol by a leader line.
// An item with `must` (an alerting pair's aircraft) is shown even when it meets a symbol
// or leaves the view; an item that finds no free position is dropped.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const GAP = 2; // px kept free between two labels
  const CELL = 64; // px, the side of a cell of the grid that finds nearby boxes
  // Compass points, east first (where a label sits by default), then those beside it.
  const DIRECTIONS = [0, -45, 45, 180, -135, 135, -90, 90].map((deg) => {
    const rad = (deg * Math.PI) / 180;
    return [Math.cos(rad), Math.sin(rad)];
  });
  // Distance of each ring from the anchor's edge, px, by kind of label; ring 0 needs no leader.
  const RINGS = {
    aircraft: [2, 16, 30, 46, 64, 86, 112, 144],
    alert: [0, 8, 20, 34, 52, 74],
    aerodrome: [3, 14, 28, 44],
    volume: [0, 10, 24, 40],
    fixed: [0],
  };
  // Farther rings, for a label that must show when the nearer ones are taken.
  const MUST_RINGS = [180, 224, 276, 336, 404];

  // A set of boxes {x0, y0, x1, y1} with a grid to find those near a box.
  class BoxSet {
    constructor() {
      this.cells = new Map();
    }

    *cellsOf(b) {
      for (let cx = Math.floor(b.x0 / CELL); cx <= Math.floor(b.x1 / CELL); cx++)
        for (let cy = Math.floor(b.y0 / CELL); cy <= Math.floor(b.y1 / CELL); cy++) yield cx + "," + cy;
    }

    add(b) {
      for (const c of this.cellsOf(b)) {
        const list = this.cells.get(c);
        if (list) list.push(b);
        else this.cells.set(c, [b]);
      }
    }

    // How many boxes of the set `b` meets, each at least `gap` px away.
    hits(b, gap) {
      const seen = new Set();
      for (const c of this.cellsOf(b)) {
        for (const o of this.cells.get(c) || []) {
          if (seen.has(o)) continue;
          if (b.x0 < o.x1 + gap && o.x0 < b.x1 + gap && b.y0 < o.y1 + gap && o.y0 < b.y1 + gap) seen.add(o);
        }
      }
      return seen.size;
    }
  }

  // The candidate boxes of `item`, in order of preference: [{x0, y0, x1, y1, leader}],
  // leader true when the box is off its anchor (beyond ring 0).
  function candidates(item) {
    const r = item.r || 0;
    const out = [];
    const rings = (RINGS[item.kind] || RINGS.fixed).concat(item.must ? MUST_RINGS : []);
    rings.forEach((d, ring) => {
      // An alert label (and a volume's or a fixed one) sits on its anchor first.
      const centred = item.kind === "alert" || item.kind === "volume" || item.kind === "fixed";
      const dirs = centred && ring === 0 ? [[0, 0]] : DIRECTIONS;
      for (const [ux, uy] of dirs) {
        // The point of the box nearest the anchor is d beyond the anchor's edge.
        const px = item.x + ux * (r + d);
        const py = item.y + uy * (r + d);
        const x0 = ux > 0.3 ? px : ux < -0.3 ? px - item.w : px - item.w / 2;
        const y0 = uy > 0.3 ? py : uy < -0.3 ? py - item.h : py - item.h / 2;
        const box = { x0: Math.round(x0), y0: Math.round(y0) };
        box.x1 = box.x0 + item.w;
        box.y1 = box.y0 + item.h;
        box.leader = ring > 0 && item.kind !== "alert" && item.kind !== "volume";
        out.push(box);
      }
    });
    return out;
  }

  function inside(b, view) {
    return b.x0 >= view.x0 && b.y0 >= view.y0 && b.x1 <= view.x1 && b.y1 <= view.y1;
  }

  // items: [{key, kind ("aircraft", "alert", "volume", "aerodrome", "fixed"), x, y, r (anchor's
  // half-size), w, h, priority, must}]; symbols: [{x0, y0, x1, y1}] boxes labels should
  // not cover; view: {x0, y0, x1, y1}. Returns Map key -> {x0, y0, x1, y1, leader} for the
  // labels shown (container pixels); an item missing from it is dropped.
  Kew.placeLabels = function (items, symbols, view) {
    const order = items.slice().sort((a, b) => b.priority - a.priority || (a.key < b.key ? -1 : a.key > b.key ? 1 : 0));
    const placed = new BoxSet();
    const covered = new BoxSet();
    for (const s of symbols) covered.add(s);
    const result = new Map();
    for (const item of order) {
      let best = null; // free of labels; prefers in view, then covering the fewest symbols
      let bestScore = Infinity;
      for (const box of candidates(item)) {
        if (placed.hits(box, GAP) > 0) continue;
        const score = (inside(box, view) ? 0 : 1000) + covered.hits(box, 0);
        if (score < bestScore) {
          best = box;
          bestScore = score;
          if (score === 0) break;
        }
      }
      // An ordinary label shows only in view and over no symbol; one that must show
      // takes the best free position there is.
      if (!best || (!item.must && bestScore > 0)) continue;
      placed.add(best);
      result.set(item.key, best);
    }
    return result;
  };
})(window.Kew);

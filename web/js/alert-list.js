// kew live map: the alert list — most severe first; a click on a row centres the map on
// the pair (or an area alert's aircraft and volume), its button acknowledges the alert. Rows are kept per alert id and only
// reordered and refreshed, never rebuilt.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  Kew.AlertList = class {
    constructor(listEl, emptyEl, { onSelect, onAck }) {
      this.listEl = listEl;
      this.emptyEl = emptyEl;
      this.rows = new Map(); // alert id -> {li, parts, text}
      this.onSelect = onSelect;
      this.onAck = onAck;
    }

    // `alerts`: Map id -> latest ALERT object; returns them sorted as shown.
    render(alerts) {
      const sorted = Array.from(alerts.values()).sort(Kew.compareAlerts);
      for (const [id, row] of this.rows) {
        if (!alerts.has(id)) {
          row.li.remove();
          this.rows.delete(id);
        }
      }
      let previous = null;
      for (const a of sorted) {
        let row = this.rows.get(a.id);
        if (!row) {
          row = this.createRow(a.id);
          this.rows.set(a.id, row);
        }
        this.fill(row, a);
        // Moves the row only when it is out of place.
        const wanted = previous ? previous.nextSibling : this.listEl.firstChild;
        if (wanted !== row.li) this.listEl.insertBefore(row.li, wanted);
        previous = row.li;
      }
      this.emptyEl.hidden = sorted.length > 0;
      return sorted;
    }

    createRow(id) {
      const li = document.createElement("li");
      li.className = "alert-row";
      li.dataset.alertId = id;
      li.tabIndex = 0;
      const badge = document.createElement("span");
      badge.className = "sev-badge";
      const pair = document.createElement("span");
      pair.className = "pair";
      const figures = document.createElement("span");
      figures.className = "figures";
      const button = document.createElement("button");
      button.type = "button";
      button.className = "ack";
      button.dataset.ackId = id;
      button.textContent = "Ack";
      button.title = "Acknowledge this alert";
      li.append(badge, pair, button, figures);
      li.addEventListener("click", (e) => {
        if (e.target === button) return;
        this.onSelect(id);
      });
      li.addEventListener("keydown", (e) => {
        if (e.key === "Enter" && e.target === li) this.onSelect(id);
      });
      button.addEventListener("click", (e) => {
        e.stopPropagation();
        this.onAck(id, button);
      });
      return { li, badge, pair, figures, button, key: null };
    }

    fill(row, a) {
      const area = Kew.isAreaAlert(a);
      const key = [a.severity, a.ack, a.t_los_s, a.t_cpa_s, a.cpa_h_m, a.cpa_v_ft, a.a.cs, a.a.alt_ft,
                   a.b ? a.b.cs : a.volume, a.volume_kind, a.hypothesis, a.region, a.number].join("|");
      if (key === row.key) return;
      row.key = key;
      row.li.dataset.severity = a.severity;
      row.li.dataset.ack = a.ack ? "true" : "false";
      row.li.dataset.kind = area ? "apw" : "stca";
      if (area) row.li.dataset.volume = a.volume;
      row.li.classList.toggle("acked", !!a.ack);
      row.badge.textContent = Kew.SEVERITY_SHORT[a.severity] || a.severity;
      row.badge.className = "sev-badge sev-" + a.severity;
      const number = typeof a.number === "number" ? "  #" + a.number : "";
      const hypothesis = a.hypothesis && a.hypothesis !== "linear" && a.hypothesis !== "proximity"
        ? " · " + a.hypothesis.replace("_", " ") : "";
      if (area) {
        // One aircraft and the volume it approaches: "DLH4AB → EDR-1 (restricted) in 40 s".
        row.pair.textContent = Kew.trackName(a.a) + " → " + Kew.areaTarget(a) + number;
        row.figures.textContent = "area proximity · " + Kew.flightLevel(a.a.alt_ft) + hypothesis;
      } else {
        row.pair.textContent = Kew.trackName(a.a) + " – " + Kew.trackName(a.b) + number;
        row.figures.textContent = Kew.alertSummary(a) + (a.region ? " · " + a.region : "") +
          (a.hypothesis && a.hypothesis !== "linear" ? " · " + a.hypothesis.replace("_", " ") : "");
      }
      row.button.disabled = !!a.ack;
      row.button.textContent = a.ack ? "Acked" : "Ack";
    }
  };
})(window.Kew);

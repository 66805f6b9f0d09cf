// kew live map: the connection to kewd (design §5.8).
//
// Live updates come over the WebSocket /ws: one message per service tick, a JSON array of
// stream objects (TRACK, ALERT, ACK, ALIVE); the first message after each (re)connect is a
// snapshot. When the socket closes the page reconnects with backoff (1 s doubling to 30 s,
// with jitter) and, while it has none, polls /api/tracks, /api/alerts and /api/status.
// /api/status is also read every few seconds on a healthy socket for the data and wall
// clocks (replay clock, data age), and /api/tracks now and then to forget tracks kewd has
// dropped (the stream has no object for a dropped track).
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const POLL_INTERVAL_MS = 2000;
  const STATUS_INTERVAL_MS = 2000;
  const RECONCILE_INTERVAL_MS = 10000;
  const BACKOFF_MIN_MS = 1000;
  const BACKOFF_MAX_MS = 30000;
  const SILENT_SOCKET_MS = 5000; // an open socket with no snapshot yet: fill from the API

  function apiUrl(path) {
    return new URL(path, document.baseURI).toString();
  }

  function getJson(path) {
    return fetch(apiUrl(path), { cache: "no-store", headers: { Accept: "application/json" } }).then((r) => {
      if (!r.ok) throw new Error(path + ": HTTP " + r.status);
      return r.json();
    });
  }

  Kew.getJson = getJson;

  Kew.Connection = class {
    // handlers: onSnapshot(objects), onBatch(objects), onPoll({tracks, alerts, status}),
    // onStatus(status), onReconcile(tracksReply), onState(state, detail)
    constructor(handlers) {
      this.h = handlers;
      this.ws = null;
      this.backoffMs = BACKOFF_MIN_MS;
      this.pollTimer = null;
      this.reconnectTimer = null;
      this.silentTimer = null;
      this.gotSnapshot = false;
      this.state = "connecting";
      this.wsSupported = typeof WebSocket === "function";
    }

    start() {
      setInterval(() => this.refreshStatus(), STATUS_INTERVAL_MS);
      setInterval(() => this.reconcile(), RECONCILE_INTERVAL_MS);
      this.refreshStatus();
      if (this.wsSupported) this.openSocket();
      else this.startPolling("no WebSocket in this browser");
    }

    setState(state, detail) {
      this.state = state;
      this.h.onState(state, detail || "");
    }

    openSocket() {
      this.reconnectTimer = null;
      const url = new URL("ws", document.baseURI);
      url.protocol = url.protocol === "https:" ? "wss:" : "ws:";
      let ws;
      try {
        ws = new WebSocket(url.toString());
      } catch (e) {
        this.socketFailed("WebSocket refused: " + e.message);
        return;
      }
      this.ws = ws;
      this.gotSnapshot = false;
      ws.onopen = () => {
        if (this.ws !== ws) return;
        clearTimeout(this.silentTimer);
        // A server that accepts the socket but sends nothing: the page still shows data.
        this.silentTimer = setTimeout(() => {
          if (this.ws === ws && !this.gotSnapshot) this.pollOnce();
        }, SILENT_SOCKET_MS);
      };
      ws.onmessage = (event) => {
        if (this.ws !== ws) return;
        let objects;
        try {
          objects = JSON.parse(event.data);
        } catch (e) {
          console.warn("kew: /ws message is not JSON:", e);
          return;
        }
        if (!Array.isArray(objects)) objects = [objects];
        if (!this.gotSnapshot) {
          this.gotSnapshot = true;
          this.backoffMs = BACKOFF_MIN_MS;
          this.stopPolling();
          this.setState("live", "WebSocket");
          this.h.onSnapshot(objects);
        } else {
          this.h.onBatch(objects);
        }
      };
      ws.onerror = () => {}; // onclose follows and says what to do
      ws.onclose = (event) => {
        if (this.ws !== ws) return;
        this.ws = null;
        clearTimeout(this.silentTimer);
        this.socketFailed("WebSocket closed (" + event.code + (event.reason ? ": " + event.reason : "") + ")");
      };
    }

    socketFailed(detail) {
      this.startPolling(detail);
      const delay = Math.min(this.backoffMs, BACKOFF_MAX_MS) * (0.8 + 0.4 * Math.random());
      this.backoffMs = Math.min(this.backoffMs * 2, BACKOFF_MAX_MS);
      clearTimeout(this.reconnectTimer);
      this.reconnectTimer = setTimeout(() => this.openSocket(), delay);
    }

    startPolling(detail) {
      if (this.state !== "polling" && this.state !== "offline") this.setState("polling", detail);
      if (this.pollTimer) return;
      this.pollOnce();
      this.pollTimer = setInterval(() => this.pollOnce(), POLL_INTERVAL_MS);
    }

    stopPolling() {
      clearInterval(this.pollTimer);
      this.pollTimer = null;
    }

    pollOnce() {
      return Promise.all([getJson("api/tracks"), getJson("api/alerts"), getJson("api/status")])
        .then(([tracks, alerts, status]) => {
          // A socket that delivered its snapshot meanwhile is newer than this reply.
          if (this.gotSnapshot && this.ws) return;
          if (this.state === "offline") this.setState("polling", "HTTP");
          this.h.onPoll({ tracks, alerts, status });
        })
        .catch((e) => {
          if (!this.ws) this.setState("offline", e.message);
        });
    }

    refreshStatus() {
      getJson("api/status").then((s) => this.h.onStatus(s)).catch(() => {});
    }

    reconcile() {
      if (!this.ws || !this.gotSnapshot) return; // polling replaces everything anyway
      getJson("api/tracks").then((t) => this.h.onReconcile(t)).catch(() => {});
    }

    // POST /api/ack with a JSON body and the X-Kew-Ack header (design §5.8): the header and
    // the JSON content type make it a request another site's page cannot send unasked.
    acknowledge(body) {
      return fetch(apiUrl("api/ack"), {
        method: "POST",
        cache: "no-store",
        headers: { "Content-Type": "application/json", "X-Kew-Ack": "1" },
        body: JSON.stringify(body),
      }).then((r) => {
        if (!r.ok) {
          return r.text().then((text) => {
            throw new Error("acknowledgement refused: HTTP " + r.status + (text ? " " + text.slice(0, 200) : ""));
          });
        }
        return r.json();
      });
    }
  };
})(window.Kew);

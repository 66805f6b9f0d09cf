// kew live map: the audible cue, opt-in. A toggle button (off unless the user turned it on
// on this browser: remembered in localStorage) and a short tone made with the Web Audio API
// when an alert opens or its severity rises — never for an update or an end. The tone
// rises with severity (caution, warning, then loss of separation, which sounds twice).
//
// Browsers start audio only after a gesture on the page: the click that turns the cue on is
// one; a cue remembered from an earlier visit sounds once the user has clicked or pressed
// a key on the page.
"use strict";
window.Kew = window.Kew || {};

(function (Kew) {
  const STORAGE_KEY = "kew.audible";
  const TONE_HZ = { caution: 660, warning: 880, loss: 1175 };
  const TONE_S = 0.16;
  const VOLUME = 0.2;

  Kew.AudibleCue = class {
    constructor(button) {
      this.button = button;
      this.context = null;
      this.cues = 0;
      let stored = null;
      try {
        stored = window.localStorage.getItem(STORAGE_KEY);
      } catch (e) {
        stored = null; // storage refused (private window, file://): off
      }
      this.setOn(stored === "on", false);
      button.addEventListener("click", () => {
        this.setOn(!this.on, true);
        if (this.on) this.play("caution"); // the user hears what it sounds like
      });
      const wake = () => {
        if (this.context && this.context.state === "suspended") this.context.resume();
      };
      document.addEventListener("pointerdown", wake, true);
      document.addEventListener("keydown", wake, true);
    }

    setOn(on, remember) {
      this.on = on;
      this.button.setAttribute("aria-pressed", on ? "true" : "false");
      this.button.dataset.on = on ? "true" : "false";
      this.button.textContent = on ? "Sound on" : "Sound off";
      this.button.title = on ? "A tone sounds when an alert opens or escalates: click to silence"
                             : "Click for a tone when an alert opens or escalates";
      if (!remember) return;
      try {
        window.localStorage.setItem(STORAGE_KEY, on ? "on" : "off");
      } catch (e) {
        // not remembered; the choice holds for this page
      }
    }

    // An ALERT object arrived: `previous` is the page's last of the same id (undefined when
    // it is new to the page). Sounds for a stream "new" or a higher severity than before.
    consider(alert, previous) {
      if (alert.state === "end" || !TONE_HZ[alert.severity]) return;
      const opened = alert.state === "new" && !previous;
      const escalated = previous && (Kew.SEVERITY_RANK[alert.severity] || 0) > (Kew.SEVERITY_RANK[previous.severity] || 0);
      if (opened || escalated) this.cue(alert.severity);
    }

    cue(severity) {
      if (!this.on) return;
      this.cues += 1;
      this.button.dataset.cues = String(this.cues);
      this.play(severity);
    }

    play(severity) {
      const Context = window.AudioContext || window.webkitAudioContext;
      if (!Context) return;
      if (!this.context) this.context = new Context();
      const ctx = this.context;
      const beeps = severity === "loss" ? 2 : 1;
      for (let i = 0; i < beeps; i++) {
        const start = ctx.currentTime + 0.02 + i * (TONE_S + 0.08);
        const osc = ctx.createOscillator();
        const gain = ctx.createGain();
        osc.type = "sine";
        osc.frequency.value = TONE_HZ[severity] || TONE_HZ.caution;
        // Short ramps at both ends: no click.
        gain.gain.setValueAtTime(0, start);
        gain.gain.linearRampToValueAtTime(VOLUME, start + 0.015);
        gain.gain.setValueAtTime(VOLUME, start + TONE_S - 0.03);
        gain.gain.linearRampToValueAtTime(0, start + TONE_S);
        osc.connect(gain).connect(ctx.destination);
        osc.start(start);
        osc.stop(start + TONE_S + 0.01);
      }
    }
  };
})(window.Kew);

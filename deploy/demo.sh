#!/usr/bin/env bash
# The demo of the README's run command (deploy/bootstrap.sh run): kewd replays a recording
# with its live map on loopback, kew-watch shows the alerts as they open and end, and when
# the recording ends kew-eval scores the same alerts in hindsight against what the
# aircraft did. Any recording kew reads works the same way:
#   KEW_DEMO_RECORDING  the file (default: an hour of ADS-B around a busy GA airfield,
#                       tests/data/text/readsb_1hr.json.gz)
#   KEW_DEMO_SPEED      times faster than recorded (default 30: the hour in two minutes,
#                       an alert on screen for several seconds)
#   KEW_DEMO_SECONDS    the longest the demo runs before it stops kewd (default 180)
#   KEW_DEMO_ALERT_PORT, KEW_DEMO_HTTP_PORT  loopback ports (default 4747, 8747)
#   KEW_DEMO_DIR        where the alert log, the logs and the map's picture go
#                       (default BUILD_DIR/demo)
#   KEW_DEMO_SCREENSHOT 0: no picture of the map (default 1, when Chromium is installed)
#   bash deploy/demo.sh [BUILD_DIR]
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-${KEW_BUILD_DIR:-$here/build}}
recording=${KEW_DEMO_RECORDING:-$here/tests/data/text/readsb_1hr.json.gz}
speed=${KEW_DEMO_SPEED:-30}
seconds=${KEW_DEMO_SECONDS:-180}
alert_port=${KEW_DEMO_ALERT_PORT:-4747}
http_port=${KEW_DEMO_HTTP_PORT:-8747}
demo=${KEW_DEMO_DIR:-$build/demo}
mkdir -p "$demo"
rm -f "$demo/demo-alerts.jsonl" "$demo/map.png"

echo "kew demo: kewd replays $(basename "$recording") ${speed} times faster than recorded."
echo "Live map: http://127.0.0.1:${http_port}/  (open it: each alert is drawn between its two aircraft)"
"$build/daemon/kewd" --replay "$recording" --speed "$speed" --exit-at-end \
  --alert-listen "127.0.0.1:$alert_port" --http-listen "127.0.0.1:$http_port" \
  --alert-log "$demo/demo-alerts.jsonl" 2>"$demo/kewd.log" &
kewd_pid=$!
trap 'kill "$kewd_pid" 2>/dev/null || true' EXIT
tries=0
until (exec 3<>"/dev/tcp/127.0.0.1/$alert_port") 2>/dev/null; do
  tries=$((tries + 1))
  if [ "$tries" -gt 100 ] || ! kill -0 "$kewd_pid" 2>/dev/null; then
    echo "demo: kewd did not start:" >&2
    cat "$demo/kewd.log" >&2
    exit 1
  fi
  sleep 0.1
done

# A picture of the map halfway through, when a browser is at hand (the test command
# installs Chromium); the run goes on without one.
browser=$(command -v chromium || true)
[ "${KEW_DEMO_SCREENSHOT:-1}" = 1 ] || browser=
if [ -n "$browser" ]; then
  (sleep "${KEW_DEMO_SHOT_AFTER_S:-20}" &&
   timeout 60 "$browser" --headless=new --no-sandbox --disable-gpu --hide-scrollbars --window-size=1280,800 \
     --virtual-time-budget=4000 --screenshot="$demo/map.png" "http://127.0.0.1:$http_port/" \
     >/dev/null 2>&1) &
fi

# kew-watch ends when kewd closes the stream, at the end of the recording.
watch_status=0
timeout "$seconds" "$build/daemon/kew-watch" --alive "127.0.0.1:$alert_port" || watch_status=$?
if [ "$watch_status" = 124 ]; then
  echo "demo: stopped after ${seconds} s (KEW_DEMO_SECONDS)"
  kill -TERM "$kewd_pid" 2>/dev/null || true
fi
wait "$kewd_pid" || true
trap - EXIT
wait || true  # the screenshot

"$build/replay/kew-eval" --json --alerts "$demo/demo-alerts.jsonl" "$recording" >"$demo/eval.json" 2>"$demo/kew-eval.log"
python3 "$here/deploy/demo_summary.py" "$demo/demo-alerts.jsonl" "$demo/eval.json"
echo "Every alert event: $demo/demo-alerts.jsonl; kewd's log: $demo/kewd.log"
if [ -s "$demo/map.png" ]; then
  echo "The map, halfway through: $demo/map.png"
else
  echo "The map (a picture from the documentation): $here/docs/img/kew-map.png"
fi

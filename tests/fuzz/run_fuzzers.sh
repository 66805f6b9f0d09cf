#!/usr/bin/env bash
# Smoke run of every libFuzzer target built in a KEW_BUILD_FUZZERS build:
#   bash tests/fuzz/run_fuzzers.sh BUILD_DIR/tests/fuzz [SECONDS_EACH]
# Each fuzz_* executable runs for SECONDS_EACH (default 20) from a seed corpus cut from
# tests/data, plus the kept corpus tests/fuzz/corpus/TARGET when it exists, two at a time
# on two cores. A long run that grows the kept corpus (docs/testing.md):
#   KEW_FUZZ_KEEP=1 KEW_FUZZ_TARGETS="fuzz_ndjson fuzz_asterix_datagram" \
#     bash tests/fuzz/run_fuzzers.sh BUILD_DIR/tests/fuzz 3600
# KEW_FUZZ_JOBS runs that many at a time (default: the cores). KEW_FUZZ_TARGETS limits the run to those targets; KEW_FUZZ_KEEP=1 merges what the run
# found into tests/fuzz/corpus/TARGET (libFuzzer -merge=1 keeps only inputs that add
# coverage), to be committed. Any crash, sanitizer report, leak, timeout
# or out-of-memory fails the script (exit 1) after printing the end of that target's log;
# the input that triggered it is left in BUILD_DIR/tests/fuzz/artifacts/.
set -euo pipefail

bin_dir=$(cd "$1" && pwd)
seconds=${2:-20}
here=$(cd "$(dirname "$0")/../.." && pwd)
data=$here/tests/data
jobs=${KEW_FUZZ_JOBS:-$(nproc)}
work=$bin_dir/fuzz-run
rm -rf "$work"
mkdir -p "$work" "$bin_dir/artifacts"

# The text targets read 4 control bytes (chunk boundaries) before the stream; a seed gets
# a prefix that cuts it into three chunks. Seeds are cut to 16 KiB (the run's max_len
# trims them further).
text_seed() {  # NAME SOURCE_FILE [gunzip]
  local out=$work/seeds/$target/$1
  mkdir -p "$(dirname "$out")"
  { printf '\003\020\200\360'
    if [ "${3:-}" = gunzip ]; then gzip -dc "$2" | head -c 16384; else head -c 16384 "$2"; fi
  } >"$out" || true  # head closing the pipe early is fine
}

binary_seeds() {  # DIR: every file below, cut to 16 KiB, no prefix
  local i=0
  mkdir -p "$work/seeds/$target"
  while IFS= read -r -d '' f; do
    head -c 16384 "$f" >"$work/seeds/$target/seed$((i++))"
  done < <(find "$1" -type f ! -name '*.md' ! -name '*.py' ! -name '*.json' -print0 2>/dev/null)
}

prefixed_seeds() {  # DIR: every data file below, cut to 16 KiB, after the 4 control bytes
  local i=0
  mkdir -p "$work/seeds/$target"
  while IFS= read -r -d '' f; do
    { printf '\003\020\200\360'; head -c 16384 "$f"; } >"$work/seeds/$target/seed$((i++))" || true
  done < <(find "$1" -type f ! -name '*.md' ! -name '*.py' ! -name '*.txt' ! -name '*.json' -print0 2>/dev/null)
}

seed() {
  case "$target" in
    fuzz_ndjson) text_seed canonical "$data/text/canonical_sample.ndjson" ;;
    fuzz_sbs) text_seed japan "$data/text/sbs_japan_13501-16500.csv" ;;
    fuzz_opensky_csv) text_seed states "$data/text/opensky_states_sample.csv" ;;
    fuzz_opensky_json) text_seed switzerland "$data/text/opensky_switzerland_first2000.json.gz" gunzip ;;
    fuzz_readsb) text_seed minutes "$data/text/readsb_20minutes.json" ;;
    fuzz_aircraft_json) text_seed history "$data/text/aircraft_json_history.json" ;;
    fuzz_readsb_trace)
      text_seed plain "$data/text/readsb_traces/trace_full_a0ee5d.json"
      text_seed inflated "$data/text/readsb_traces/trace_full_aab1cf.json" gunzip ;;
    fuzz_gzip)
      mkdir -p "$work/seeds/$target"
      { printf '\003\020\200\360'; gzip -c "$data/text/canonical_sample.ndjson"; } >"$work/seeds/$target/member"
      { printf '\003\020\200\360'; gzip -c "$data/text/canonical_sample.ndjson"
        gzip -c "$data/text/opensky_states_sample.csv"; } >"$work/seeds/$target/two_members"
      text_seed switzerland "$data/text/opensky_switzerland_first2000.json.gz" ;;
    fuzz_detect)
      text_seed canonical "$data/text/canonical_sample.ndjson"
      text_seed japan "$data/text/sbs_japan_13501-16500.csv"
      text_seed states "$data/text/opensky_states_sample.csv"
      text_seed minutes "$data/text/readsb_20minutes.json"
      text_seed history "$data/text/aircraft_json_history.json"
      text_seed trace "$data/text/readsb_traces/trace_full_a0ee5d.json"
      text_seed trace_gz "$data/text/readsb_traces/trace_full_aab1cf.json"
      text_seed switzerland_gz "$data/text/opensky_switzerland_first2000.json.gz" ;;
    fuzz_asterix_raw|fuzz_asterix_ff|fuzz_asterix_pcap|fuzz_asterix_datagram) prefixed_seeds "$data/asterix" ;;
    fuzz_asterix*) binary_seeds "$data/asterix" ;;
    fuzz_cat004*) binary_seeds "$data/cat004" ;;
    fuzz_modbus_requests)  # shape byte, then a read of the status registers and a coil-0 write
      mkdir -p "$work/seeds/$target"
      printf '\010\000\001\000\000\000\006\001\004\000\000\000\020\000\002\000\000\000\006\001\005\000\000\377\000' >"$work/seeds/$target/read_and_ack" ;;
    fuzz_config)  # every configuration the project ships or tests with
      local i=0
      mkdir -p "$work/seeds/$target"
      while IFS= read -r -d '' f; do cp "$f" "$work/seeds/$target/seed$((i++)).toml"; done \
        < <(find "$here/deploy" "$here/tests" -name '*.toml' -print0) ;;
    fuzz_http_requests)  # each route, keep-alive, a pipelined pair, acknowledgements, an upgrade ($PORT: the server's)
      mkdir -p "$work/seeds/$target"
      local s=$work/seeds/$target
      printf 'GET /api/status HTTP/1.1\r\nHost: localhost\r\n\r\n' >"$s/status"
      printf 'GET / HTTP/1.1\r\nHost: localhost\r\n\r\nGET /metrics HTTP/1.1\r\nHost: localhost\r\n\r\n' >"$s/pipelined"
      printf 'HEAD /api/tracks HTTP/1.0\r\n\r\nGET /api/zones?x=1 HTTP/1.1\r\nConnection: close\r\n\r\n' >"$s/head_and_close"
      printf 'POST /api/ack HTTP/1.1\r\nHost: localhost:$PORT\r\nContent-Type: application/json\r\nX-Kew-Ack: 1\r\nContent-Length: 10\r\n\r\n{"id":"1"}' >"$s/ack"
      printf 'POST /api/ack HTTP/1.1\r\nHost: 127.0.0.1:$PORT\r\nOrigin: http://127.0.0.1:$PORT\r\nX-Kew-Ack: 1\r\nTransfer-Encoding: chunked\r\n\r\n5\r\n{"all\r\n5\r\n":tru\r\n2\r\ne}\r\n0\r\n\r\n' >"$s/ack_chunked"
      printf 'GET /leaflet/leaflet.js HTTP/1.1\r\nHost: localhost\r\n\r\nGET /../etc/passwd HTTP/1.1\r\n\r\n' >"$s/files"
      printf 'GET /ws HTTP/1.1\r\nHost: localhost\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n' >"$s/upgrade" ;;
    fuzz_websocket_frames)  # masked client frames: text, ping, close, fragments
      mkdir -p "$work/seeds/$target"
      local s=$work/seeds/$target
      printf '\201\205\001\002\003\004idolk' >"$s/text"
      printf '\211\200\001\002\003\004' >"$s/ping"
      printf '\210\202\001\002\003\004\002\352' >"$s/close"
      printf '\001\202\000\000\000\000ab\200\202\000\000\000\000cd' >"$s/fragments"
      printf '\212\200\000\000\000\000\202\176\000\004\000\000\000\000abcd' >"$s/pong_and_binary" ;;
    *) mkdir -p "$work/seeds/$target" ;;
  esac
}

run_one() {  # TARGET: exit status of the fuzzer
  local target=$1
  # Text inputs of a few KiB reach every path (lines are short) and run ten times
  # faster than 64 KiB ones; binary framings get room for several blocks.
  local max_len=4096
  case "$target" in
    fuzz_asterix*|fuzz_cat004*) max_len=65536 ;;
    fuzz_config) max_len=32768 ;;  # deploy/kew.toml whole
    fuzz_http*|fuzz_websocket*) max_len=16384 ;;  # what the loopback buffers take at once
  esac
  mkdir -p "$work/corpus/$target"
  local kept=()
  [ -d "$here/tests/fuzz/corpus/$target" ] && kept=("$here/tests/fuzz/corpus/$target")
  "$bin_dir/$target" "$work/corpus/$target" "$work/seeds/$target" "${kept[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=2048 -max_len="$max_len" -timeout=20 \
    -print_final_stats=1 -artifact_prefix="$bin_dir/artifacts/$target-" \
    >"$work/$target.log" 2>&1 || return
  if [ "${KEW_FUZZ_KEEP:-0}" = 1 ]; then
    mkdir -p "$here/tests/fuzz/corpus/$target"
    "$bin_dir/$target" -merge=1 -max_len="$max_len" "$here/tests/fuzz/corpus/$target" "$work/corpus/$target" \
      >>"$work/$target.log" 2>&1
  fi
}

targets=()
for exe in "$bin_dir"/fuzz_*; do
  [ -f "$exe" ] && [ -x "$exe" ] || continue
  target=$(basename "$exe")
  if [ -n "${KEW_FUZZ_TARGETS:-}" ] && [[ " $KEW_FUZZ_TARGETS " != *" $target "* ]]; then continue; fi
  seed
  targets+=("$target")
done
[ ${#targets[@]} -gt 0 ] || { echo "run_fuzzers: no fuzz_* executables in $bin_dir" >&2; exit 1; }

echo "run_fuzzers: ${#targets[@]} targets, ${seconds} s each, $jobs at a time"
failed=()
pids=()
names=()
wait_one() {
  local status=0
  wait "${pids[0]}" || status=$?
  if [ $status -ne 0 ]; then
    failed+=("${names[0]}")
    echo "run_fuzzers: ${names[0]} FAILED (exit $status); end of its log:" >&2
    tail -n 60 "$work/${names[0]}.log" >&2
  else
    echo "run_fuzzers: ${names[0]} ok ($(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$work/${names[0]}.log" | grep -o '[0-9]*$') runs)"
  fi
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
}
for target in "${targets[@]}"; do
  run_one "$target" &
  pids+=($!)
  names+=("$target")
  [ ${#pids[@]} -lt "$jobs" ] || wait_one
done
while [ ${#pids[@]} -gt 0 ]; do wait_one; done

if [ ${#failed[@]} -gt 0 ]; then
  echo "run_fuzzers: failed: ${failed[*]}" >&2
  exit 1
fi
echo "run_fuzzers: all ${#targets[@]} targets ran clean"

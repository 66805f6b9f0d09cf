"""aircraft.json snapshots as readsb writes them, made from readsb JSON lines (real
positions): every aircraft whose last position is at most 30 s old, that position with its
age (seen_pos), "now" 0.3 s after the second.

  python3 make_aircraft_json_history.py
      the bundled aircraft_json_history.json: the first 120 s of readsb_20minutes.json,
      one snapshot a second, one snapshot a line
  python3 make_aircraft_json_history.py SOURCE.json DIRECTORY [--every S] [--seconds N]
      a receiver's history directory: DIRECTORY/history_K.json every S seconds (default 1)
      over the first N seconds of SOURCE (default: all of it)
"""
import argparse
import json
import os


def snapshots(lines, every, seconds):
    last, i = {}, 0
    t0 = lines[0]['now']
    end = lines[-1]['now'] + 1 if seconds is None else t0 + seconds
    for now in range(t0, end, every):
        while i < len(lines) and lines[i]['now'] <= now:
            line = lines[i]
            i += 1
            if 'hex' in line and 'lat' in line:
                last[line['hex']] = line
        aircraft = []
        for hexid, line in sorted(last.items()):
            age = now - line['now']
            if age > 30:
                continue
            aircraft.append({"hex": hexid, "type": "adsb_icao", "flight": (line.get('flight') or '').ljust(8),
                             "alt_baro": line['alt_baro'], "gs": line.get('gscp'), "track": line.get('track'),
                             "lat": line['lat'], "lon": line['lon'], "seen_pos": round(age + 0.3, 1),
                             "seen": round(age, 1)})
        yield {"now": now + 0.3, "messages": 1000 + now - t0, "aircraft": aircraft}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("source", nargs="?")
    parser.add_argument("directory", nargs="?")
    parser.add_argument("--every", type=int, default=1)
    parser.add_argument("--seconds", type=int)
    args = parser.parse_args()
    if args.source is None:
        lines = [json.loads(line) for line in open('readsb_20minutes.json')]
        with open('aircraft_json_history.json', 'w') as f:
            for snap in snapshots(lines, 1, 120):
                f.write(json.dumps(snap, separators=(',', ':')) + "\n")
        return
    lines = [json.loads(line) for line in open(args.source)]
    os.makedirs(args.directory, exist_ok=True)
    count = 0
    for k, snap in enumerate(snapshots(lines, args.every, args.seconds)):
        with open(os.path.join(args.directory, f"history_{k}.json"), 'w') as f:
            json.dump(snap, f, separators=(',', ':'))
        count += 1
    print(f"{count} snapshots in {args.directory}")


if __name__ == "__main__":
    main()

import json
# aircraft.json snapshots as readsb writes them once a second, made from the first 120 s
# of readsb_20minutes.json: every aircraft whose last position is at most 30 s old, that
# position with its age (seen_pos), "now" 0.3 s after the second.
lines = [json.loads(l) for l in open('readsb_20minutes.json')]
last, out, i = {}, [], 0
t0 = lines[0]['now']
for now in range(t0, t0 + 120):
    while i < len(lines) and lines[i]['now'] <= now:
        l = lines[i]; i += 1
        if 'hex' in l and 'lat' in l: last[l['hex']] = l
    aircraft = []
    for hexid, l in sorted(last.items()):
        age = now - l['now']
        if age > 30: continue
        a = {"hex": hexid, "type": "adsb_icao", "flight": (l.get('flight') or '').ljust(8), "alt_baro": l['alt_baro'],
             "gs": l.get('gscp'), "track": l.get('track'), "lat": l['lat'], "lon": l['lon'],
             "seen_pos": round(age + 0.3, 1), "seen": round(age, 1)}
        aircraft.append(a)
    out.append({"now": now + 0.3, "messages": 1000 + now - t0, "aircraft": aircraft})
with open('aircraft_json_history.json', 'w') as f:
    for snap in out:
        f.write(json.dumps(snap, separators=(',', ':')) + "\n")
print(len(out), sum(len(s['aircraft']) for s in out), sum(1 for l in lines if 'lat' in l and l['now'] < t0 + 120))

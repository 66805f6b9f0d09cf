import collections, gzip, json
# readsb trace files (trace_full_<hex>.json, the layout of readsb's README-json.md "trace
# jsons", 14 fields a row), one per aircraft, made from the real positions of
# readsb_20minutes.json: the last line of an aircraft in a second is its row; timestamp
# the aircraft's first second; flags 2 on the first row, 1 after 15 s or more without a
# position (as readsb marks them); the object of aircraft.json members on the first row
# and where the callsign changes; source type "adsb_icao". gzip-compressed as readsb
# writes them (mtime 0), but for the first two files by name, left plain.
lines = [json.loads(l) for l in open('readsb_20minutes.json')]
rows = collections.defaultdict(dict)  # hex -> now -> line
for l in lines:
    if 'hex' in l and 'lat' in l:
        rows[l['hex']][l['now']] = l
num = lambda v: 'null' if v is None else json.dumps(v)
for i, hexid in enumerate(sorted(rows)):
    points = [rows[hexid][now] for now in sorted(rows[hexid])]
    timestamp = points[0]['now']
    out, last_now, last_flight = [], None, None
    for l in points:
        flags = 2 if last_now is None else (1 if l['now'] - last_now >= 15 else 0)
        details = 'null'
        if last_now is None or (l.get('flight') and l['flight'] != last_flight):
            d = {"type": "adsb_icao"}
            if l.get('flight'):
                d["flight"] = l['flight'].ljust(8)
                last_flight = l['flight']
            details = json.dumps(d, separators=(',', ':'))
        out.append('[%.2f,%s,%s,%s,%s,%s,%d,null,%s,"adsb_icao",null,null,null,null]' % (
            l['now'] - timestamp, num(l['lat']), num(l['lon']), num(l['alt_baro']), num(l.get('gscp')),
            num(l.get('track')), flags, details))
        last_now = l['now']
    text = '{"icao":"%s",\n"timestamp": %.3f,\n"trace":[ \n%s ]\n }\n' % (hexid, timestamp, ',\n'.join(out))
    name = 'readsb_traces/trace_full_%s.json' % hexid
    data = text.encode() if i < 2 else gzip.compress(text.encode(), 9, mtime=0)
    open(name, 'wb').write(data)
print(len(rows), sum(len(r) for r in rows.values()))

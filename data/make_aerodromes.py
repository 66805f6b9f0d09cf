#!/usr/bin/env python3
"""Writes data/aerodromes.csv, kew's one table of aerodrome positions and elevations, from
OurAirports' open data (public domain: the Unlicense; https://ourairports.com/data/):

    python3 data/make_aerodromes.py runways.csv [--airports airports.csv] \
        [--supplement data/aerodromes-supplement.csv] > data/aerodromes.csv

runways.csv gives the aerodromes and their figures; airports.csv, when given, their
names; the supplement (data/README.md) gives the few aerodromes that kew-gen flies to but
whose runways in runways.csv lack threshold coordinates or elevations. data/README.md
names the snapshot in use.

An aerodrome is every airport ident with an open runway (closed = 0) of at least 500 ft,
or of unknown length, whose thresholds have coordinates and an elevation. Its position is
the mean of its runway thresholds (a runway's two ends, or the one given), its elevation
the highest threshold elevation (the ICAO aerodrome elevation is the highest point of the
landing area, ICAO Annex 14 vol. I, 1.1). Helipads (runway idents beginning with H) are
left out, and so are idents that are not ASCII or hold a double quote. A supplement row
whose ident runways.csv already gives is left out (with a note on stderr): the runways win.

Rows are ordered by latitude, then longitude (both rounded to 0.0001°, about 10 m),
elevation (rounded to 1 ft) and ident: the order is the table's, and where two aerodromes
lie equally near a track the first one sets its lower limit.

Columns (kew/eligibility/aerodrome_csv.hpp reads them): ident (OurAirports' ident: the
ICAO location indicator where there is one), lat_deg and lon_deg (WGS84 degrees, 4
decimals), elevation_ft (feet above mean sea level, an integer), name (airports.csv's
name, or the supplement's; empty without either)."""

import argparse
import csv
import sys

HEADER = ["ident", "lat_deg", "lon_deg", "elevation_ft", "name"]


def thresholds(runways_path):
    """ident -> (threshold positions, threshold elevations) of its usable runways."""
    fields = {}
    with open(runways_path, newline="", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            if r["closed"] != "0" or r["le_ident"].upper().startswith("H"):
                continue
            if r["length_ft"] and float(r["length_ft"]) < 500:
                continue
            points, elevations = [], []
            for end in ("le", "he"):
                lat, lon, elev = r[end + "_latitude_deg"], r[end + "_longitude_deg"], r[end + "_elevation_ft"]
                if lat and lon:
                    points.append((float(lat), float(lon)))
                if elev:
                    elevations.append(float(elev))
            if not points or not elevations:
                continue
            entry = fields.setdefault(r["airport_ident"], ([], []))
            entry[0].extend(points)
            entry[1].extend(elevations)
    return fields


def names(airports_path):
    """ident -> name from airports.csv, white space folded (a row is one line)."""
    if airports_path is None:
        return {}
    with open(airports_path, newline="", encoding="utf-8") as f:
        return {r["ident"]: " ".join(r["name"].split()) for r in csv.DictReader(f)}


def usable(ident, lat, lon):
    return -90 <= lat <= 90 and -180 <= lon <= 180 and ident.isascii() and '"' not in ident


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runways", help="OurAirports' runways.csv")
    parser.add_argument("--airports", help="OurAirports' airports.csv: the names")
    parser.add_argument("--supplement", help="rows of the output's columns for aerodromes runways.csv lacks")
    args = parser.parse_args()

    named = names(args.airports)
    rows = {}  # ident -> (lat, lon, elevation, name)
    for ident, (points, elevations) in thresholds(args.runways).items():
        lat = sum(p[0] for p in points) / len(points)
        lon = sum(p[1] for p in points) / len(points)
        if usable(ident, lat, lon):
            rows[ident] = (round(lat, 4), round(lon, 4), round(max(elevations)), named.get(ident, ""))
    if args.supplement:
        with open(args.supplement, newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                if r["ident"] in rows:
                    print(f"{r['ident']}: runways.csv has it now; its supplement row is left out", file=sys.stderr)
                    continue
                lat, lon = float(r["lat_deg"]), float(r["lon_deg"])
                if not usable(r["ident"], lat, lon):
                    sys.exit(f"{args.supplement}: {r['ident']}: not a usable row")
                rows[r["ident"]] = (round(lat, 4), round(lon, 4), round(float(r["elevation_ft"])),
                                    named.get(r["ident"]) or r["name"])
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(HEADER)
    for ident, (lat, lon, elev, name) in sorted(rows.items(), key=lambda item: (*item[1][:3], item[0])):
        out.writerow([ident, f"{lat:.4f}", f"{lon:.4f}", elev, name])
    print(f"{len(rows)} aerodromes", file=sys.stderr)


if __name__ == "__main__":
    main()

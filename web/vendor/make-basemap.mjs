// Builds web/vendor/naturalearth-50m.json, the map's offline base map, from the pinned npm
// packages world-atlas@2.0.2 (Natural Earth 4.1.0 as TopoJSON, ISC; the data are public
// domain) and topojson-client@3.1.0 (ISC). Run at vendoring time only, never at build or
// run time (web/vendor/README.md):
//   mkdir /tmp/ne && cd /tmp/ne && npm install world-atlas@2.0.2 topojson-client@3.1.0
//   node /path/to/kew/web/vendor/make-basemap.mjs /tmp/ne/node_modules > web/vendor/naturalearth-50m.json
// Output: {"source":…,"land":<GeoJSON MultiPolygon>,"borders":<GeoJSON MultiLineString>}.
// Land polygons carry the coastlines as their outlines; borders are the arcs shared by two
// countries (each drawn once). Coordinates are rounded to 0.001° (about 100 m), far below
// the 1:50m data's own resolution, to keep the file small.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";

const modules = process.argv[2];
if (!modules) {
  console.error("usage: node make-basemap.mjs NODE_MODULES_DIR > naturalearth-50m.json");
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(modules), "noop.js"));
const topojson = require("topojson-client");
const atlas = (name) => JSON.parse(readFileSync(path.join(modules, "world-atlas", name), "utf8"));
const version = (name) => JSON.parse(readFileSync(path.join(modules, name, "package.json"), "utf8")).version;

const land = atlas("land-50m.json");
const countries = atlas("countries-50m.json");

const round = (c) => (Array.isArray(c[0]) ? c.map(round) : [Math.round(c[0] * 1000) / 1000, Math.round(c[1] * 1000) / 1000]);
// Drops points that round onto their predecessor.
const dedupe = (line) => line.filter((p, i) => i === 0 || p[0] !== line[i - 1][0] || p[1] !== line[i - 1][1]);

const landGeometry = topojson.merge(land, land.objects.land.geometries);
const polygons = round(landGeometry.coordinates)
  .map((polygon) => polygon.map(dedupe).filter((ring) => ring.length >= 4))
  .filter((polygon) => polygon.length > 0);
const bordersGeometry = topojson.mesh(countries, countries.objects.countries, (a, b) => a !== b);
const lines = round(bordersGeometry.coordinates).map(dedupe).filter((line) => line.length >= 2);

process.stdout.write(JSON.stringify({
  source: `Natural Earth 1:50m (public domain) via world-atlas@${version("world-atlas")} land-50m.json and ` +
          `countries-50m.json, converted with topojson-client@${version("topojson-client")}`,
  land: { type: "MultiPolygon", coordinates: polygons },
  borders: { type: "MultiLineString", coordinates: lines },
}) + "\n");

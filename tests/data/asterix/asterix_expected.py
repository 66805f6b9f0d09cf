#!/usr/bin/env python3
"""Builds kew's bundled ASTERIX fixtures and their expected values (see SOURCE.md).

    python3 tests/data/asterix/asterix_expected.py [--shared DIR] [--check]

For each fixture this script
  1. copies it (or an excerpt) from the shared recordings into tests/data/asterix/,
  2. wraps its data blocks as UDP datagrams in a pcap (pcap fixtures are used as they are),
  3. decodes that pcap with tshark (-T json; the dissector's default, latest editions),
  4. applies kew's documented acceptance rules (protocol/docs/asterix.md) to tshark's
     decoded fields, independently of kew's C++ code, and
  5. writes expected/<fixture>.txt: counts, rejections by reason, time span, distinct ids
     and a sample of decoded records.
--check regenerates into a temporary directory and compares instead of writing.
The UPC Barcelona CAT048 file has no licence and is never copied: its figures are checked
in the C++ test straight from the shared directory.
"""

import argparse
import json
import math
import shutil
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_SHARED = HERE.parents[2].parent / "shared" / "data" / "recordings"

# fixture path (under tests/data/asterix) -> (shared source, framing, excerpt seconds or None)
FIXTURES = {
    "jade/final_frame_062_first3min.ff": ("jade-cat062-ff/final_frame_062_30min.ff", "ff", 180.0),
    "jade/JADE_final_frame_062_one_packet_sample2.ff": ("jasterix-vectors/JADE_final_frame_062_one_packet_sample2.ff", "ff", None),
    "jade/JADE_NATS_CAT048_119bytes_TCAS.ff": ("jasterix-vectors/JADE_NATS_CAT048_119bytes_TCAS.ff", "ff", None),
    "croatiacontrol/asterix.pcap": ("croatiacontrol-samples/asterix.pcap", "pcap", None),
    "croatiacontrol/cat_034_048.pcap": ("croatiacontrol-samples/cat_034_048.pcap", "pcap", None),
    "croatiacontrol/cat_062_065.pcap": ("croatiacontrol-samples/cat_062_065.pcap", "pcap", None),
    "croatiacontrol/cat_001_002.pcap": ("croatiacontrol-samples/cat_001_002.pcap", "pcap", None),
    "croatiacontrol/cat062cat065.raw": ("croatiacontrol-samples/cat062cat065.raw", "raw", None),
    "croatiacontrol/cat21_re.ast": ("croatiacontrol-samples/cat21_re.ast", "raw", None),
    "croatiacontrol/cat048.raw": ("croatiacontrol-samples/cat048.raw", "raw", None),
    "croatiacontrol/cat034.raw": ("croatiacontrol-samples/cat034.raw", "raw", None),
    "jasterix/cat021ed2.1.bin": ("jasterix-vectors/cat021ed2.1.bin", "raw", None),
    "jasterix/cat021ed0.26.bin": ("jasterix-vectors/cat021ed0.26.bin", "raw", None),
    "jasterix/cat048ed1.15.bin": ("jasterix-vectors/cat048ed1.15.bin", "raw", None),
    "jasterix/cat048ed1.23.bin": ("jasterix-vectors/cat048ed1.23.bin", "raw", None),
    "jasterix/cat062ed1.12.bin": ("jasterix-vectors/cat062ed1.12.bin", "raw", None),
    "jasterix/cat062ed1.16.bin": ("jasterix-vectors/cat062ed1.16.bin", "raw", None),
    "asterix4py/cat062.ast": ("jasterix-vectors/asterix4py_cat062.ast", "raw", None),
}
# Shared recordings checked in place (never copied): only their expected values are written,
# to expected/shared__<name>.txt; the C++ test reads the data from the shared directory and
# skips when it is absent. The UPC Barcelona file has no licence.
SHARED_ONLY = {
    "shared/upc-bcn-cat048": ("upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast", "raw"),
    "shared/jade-cat062-30min": ("jade-cat062-ff/final_frame_062_30min.ff", "ff"),
}
# CAT021 edition 0.26 is not in tshark 4.0.17 (it has 0.23, whose I021/130 is 6 bytes):
# that vector's expected values are decoded by hand in the C++ test.
NO_TSHARK = {"jasterix/cat021ed0.26.bin"}
# The old, non-standard CAT062 edition in croatiacontrol/asterix.pcap (tshark's field
# values are those of a wrong profile) and cat_001_002.pcap (a UDP payload of sub-frames
# with a 6-byte wrapper header each, not plain data blocks): only tshark's block and record
# counts are written; the C++ test checks kew's own counts.
MALFORMED = {"croatiacontrol/asterix.pcap", "croatiacontrol/cat_001_002.pcap"}
# tshark 4.0.17 stops reading I062/340 of this record after its primary subfield and takes
# the rest of the block for a second record (it flags the packet malformed); kew's walk,
# like jASTERIX's, ends exactly at the end of the block with one record. Only tshark's
# first record is used.
RECORDS_PER_BLOCK = {"jasterix/cat062ed1.16.bin": 1}
DECODE_AS = ["-d", "udp.port==20402,asterix", "-d", "udp.port==10001,asterix"] + [
    arg for port in (21111, 21112, 21113, 21114, 21131, 21134, 21135, 22111, 22112, 22113,
                     22114, 22131, 22134, 22135) for arg in ("-d", f"udp.port=={port},asterix")]
SAMPLES = 8


# ---- framing ------------------------------------------------------------------------
def walk_raw(data):
    blocks, i = [], 0
    while i + 3 <= len(data):
        length = (data[i + 1] << 8) | data[i + 2]
        blocks.append(data[i:i + length])
        i += length
    return blocks


def walk_ff(data):
    """Frames (header and trailer included)."""
    frames, i = [], 0
    while i + 2 <= len(data):
        length = (data[i] << 8) | data[i + 1]
        frames.append(data[i:i + length])
        i += length
    return frames


def wrap_as_pcap(payloads, path):
    """One Ethernet/IPv4/UDP (port 8600, tshark's default ASTERIX port) packet per payload."""
    with open(path, "wb") as out:
        out.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
        for n, payload in enumerate(payloads):
            udp = struct.pack(">HHHH", 8600, 8600, 8 + len(payload), 0) + payload
            ip = struct.pack(">BBHHHBBH4s4s", 0x45, 0, 20 + len(udp), n & 0xFFFF, 0, 64, 17, 0,
                             bytes([10, 0, 0, 1]), bytes([10, 0, 0, 2]))
            frame = b"\0" * 12 + b"\x08\x00" + ip + udp
            out.write(struct.pack("<IIII", n, 0, len(frame), len(frame)) + frame)


# ---- tshark ---------------------------------------------------------------------------
def tshark_blocks(pcap):
    """[(capture time, category, [record fields])] per data block, in stream order."""
    text = subprocess.run(["tshark", "-r", str(pcap), "-T", "json", "-J", "frame asterix", *DECODE_AS],
                          capture_output=True, text=True, check=True).stdout
    blocks = []
    for packet in json.loads(text, object_pairs_hook=lambda pairs: pairs):
        layers = dict(dict(packet)["_source"])["layers"]
        capture = float(dict(dict(layers)["frame"])["frame.time_epoch"])
        for name, layer in layers:
            if name != "asterix":
                continue
            records = []
            for key, value in layer:
                if key == "asterix.message":
                    fields = {}
                    flatten(value, fields)
                    records.append(fields)
            blocks.append((capture, int(dict(layer)["asterix.category"]), records))
    return blocks


def flatten(pairs, fields):
    for key, value in pairs:
        if isinstance(value, list):
            flatten(value, fields)
        else:
            fields[key.replace("asterix.", "", 1)] = value


def tshark_version():
    return subprocess.run(["tshark", "--version"], capture_output=True, text=True).stdout.split("\n")[0]


# ---- kew's acceptance rules (protocol/docs/asterix.md), on tshark's fields -------------
class Reject(Exception):
    pass


def utc_of(tod, capture, framing):
    if tod >= 86400:
        raise Reject("asterix_bad_time_of_day")
    if framing != "pcap":
        return tod  # day_start_utc_s = 0 and no rollover in these fixtures
    t = math.floor(capture / 86400) * 86400 + tod
    if t - capture > 43200:
        t -= 86400
    if capture - t > 43200:
        t += 86400
    return t


def source(cat, f, prefix):
    return f"cat{cat:03d}/{int(f[prefix + '_010_SAC'], 16)}.{int(f[prefix + '_010_SIC'], 16)}"


def callsign(text):
    text = (text or "").strip(" ")
    return text if text and all(c.isalnum() or c == " " for c in text) else ""


def velocity(vx, vy):
    gs = math.hypot(vx, vy) * 3600 / 1852
    trk = math.degrees(math.atan2(vx, vy)) % 360.0
    return gs, trk


def check_position(report):
    if not (abs(report["lat"]) <= 90 and abs(report["lon"]) <= 180):
        raise Reject("asterix_position_out_of_range")


def cat062(f, capture, framing):
    g = lambda k: f.get("062_" + k)
    if g("010_SAC") is None:
        raise Reject("asterix_missing_data_source")
    if g("070_VALUE") is None:
        raise Reject("asterix_missing_time")
    if g("080_CNF") == "1":
        raise Reject("asterix_tentative_track")
    if g("080_SIM") == "1":
        raise Reject("asterix_simulated_target")
    if g("105_LAT") is None:
        raise Reject("cat062_cartesian_only" if g("100_X") is not None else "asterix_missing_position")
    if g("136_VALUE") is not None:
        alt = float(g("136_VALUE")) * 100
    elif g("135_CTB") is not None:
        alt = float(g("135_CTB")) * 100
    elif g("130_VALUE") is not None:
        alt = float(g("130_VALUE"))
    else:
        raise Reject("asterix_missing_altitude")
    # The track number is the identity; the address only an attribute.
    if g("040_VALUE") is None:
        raise Reject("asterix_missing_identity")
    r = {"src": source(62, f, "062"), "id": str(int(g("040_VALUE"), 16)),
         "t": utc_of(float(g("070_VALUE")), capture, framing),
         "lat": float(g("105_LAT")), "lon": float(g("105_LON")), "alt_ft": alt, "gnd": 0,
         "coast": int(g("080_CST") == "1"), "end": int(g("080_TSE") == "1")}
    check_position(r)
    if g("380_ADR_VALUE") is not None:
        r["addr"] = "%06X" % int(g("380_ADR_VALUE"), 16)
    if g("185_VX") is not None:
        r["gs_kt"], r["trk_deg"] = velocity(float(g("185_VX")), float(g("185_VY")))
    if g("220_VALUE") is not None:
        r["vr_fpm"] = float(g("220_VALUE"))
    if g("060_MODE3A") is not None:
        r["mode3a"] = int(g("060_MODE3A"))
    r["cs"] = callsign(g("245_CHR")) or callsign(g("380_ID_VALUE")) or callsign(g("390_CS_VALUE"))
    return r


def cat048(f, capture, framing):
    g = lambda k: f.get("048_" + k)
    if g("010_SAC") is None:
        raise Reject("asterix_missing_data_source")
    if g("140_VALUE") is None:
        raise Reject("asterix_missing_time")
    if g("020_SIM") == "1":
        raise Reject("asterix_simulated_target")
    if g("020_TST") == "1":
        raise Reject("asterix_test_target")
    if g("170_CNF") == "1":
        raise Reject("asterix_tentative_track")
    # Every radar of these fixtures is configured by the test (at nominal sites).
    if g("040_RHO") is None:
        raise Reject("asterix_missing_position")
    on_ground = g("230_STAT") in ("1", "3")
    if g("090_FL") is not None and g("090_G") != "1":
        fl = float(g("090_FL"))
        # tshark 4.0.17 shows I048/090 as unsigned; the specification says two's complement.
        alt = (fl - 4096 if fl >= 2048 else fl) * 100
    elif on_ground:
        alt = 0.0
    else:
        raise Reject("asterix_missing_altitude")
    # The track number is the identity, the address an attribute; a plot without a track
    # number is keyed by its address.
    address = "%06X" % int(g("220_VALUE"), 16) if g("220_VALUE") is not None else None
    if g("161_TRN") is not None:
        ident = str(int(g("161_TRN")))
    elif address is not None:
        ident = address
    else:
        raise Reject("asterix_missing_identity")
    r = {"src": source(48, f, "048"), "id": ident, "t": utc_of(float(g("140_VALUE")), capture, framing),
         "rho_nm": float(g("040_RHO")), "theta_deg": float(g("040_THETA")), "alt_ft": alt,
         "gnd": int(on_ground), "coast": 0, "end": int(g("170_TRE") == "1")}
    if address is not None:
        r["addr"] = address
    if g("200_GSP") is not None:
        r["gs_kt"] = float(g("200_GSP")) * 3600
        r["trk_deg"] = float(g("200_HDG"))
    if g("070_MODE3A") is not None:
        r["mode3a"] = int(g("070_MODE3A"))
    r["cs"] = callsign(g("240_VALUE"))
    return r


def cat021(f, capture, framing):
    g = lambda k: f.get("021_" + k)
    if g("040_SIM") == "1":
        raise Reject("asterix_simulated_target")
    if g("040_TST") == "1":
        raise Reject("asterix_test_target")
    on_ground = g("040_GBS") == "1"
    if g("010_SAC") is None:
        raise Reject("asterix_missing_data_source")
    tod = next((g(k + "_VALUE") for k in ("071", "073", "075", "077") if g(k + "_VALUE") is not None), None)
    if tod is None:
        raise Reject("asterix_missing_time")
    if g("131_LAT") is not None:
        lat, lon = float(g("131_LAT")), float(g("131_LON"))
    elif g("130_LAT") is not None:
        lat, lon = float(g("130_LAT")), float(g("130_LON"))
    else:
        raise Reject("asterix_missing_position")
    if g("145_VALUE") is not None:
        alt = float(g("145_VALUE")) * 100
    elif g("140_VALUE") is not None:
        alt = float(g("140_VALUE"))
    elif on_ground:
        alt = 0.0
    else:
        raise Reject("asterix_missing_altitude")
    if g("080_VALUE") is None:
        raise Reject("asterix_missing_identity")
    address = "%06X" % int(g("080_VALUE"), 16)
    r = {"src": source(21, f, "021"), "id": address,
         "t": utc_of(float(tod), capture, framing), "lat": lat, "lon": lon, "alt_ft": alt,
         "gnd": int(on_ground), "coast": 0, "end": 0, "addr": address}
    check_position(r)
    if g("160_GS") is not None:
        r["gs_kt"] = float(g("160_GS")) * 3600
        r["trk_deg"] = float(g("160_TA"))
    rate = g("155_BVR") if g("155_BVR") is not None else g("157_GVR")
    if rate is not None:
        r["vr_fpm"] = float(rate)
    if g("070_MODE3A") is not None:
        r["mode3a"] = int(g("070_MODE3A"))
    r["cs"] = callsign(g("170_VALUE"))
    return r


RULES = {62: cat062, 48: cat048, 21: cat021}


# ---- expected file -------------------------------------------------------------------
def fmt(value):
    return repr(value) if isinstance(value, float) else str(value)


def expected_lines(fixture, framing, blocks):
    reports, rejections, radars = [], {}, set()
    records = 0
    for capture, cat, recs in blocks:
        if cat not in RULES:
            rejections["asterix_category_ignored"] = rejections.get("asterix_category_ignored", 0) + 1
            continue
        for fields in recs[:RECORDS_PER_BLOCK.get(fixture)]:
            records += 1
            if cat == 48:
                radars.add(source(48, fields, "048").split("/")[1])
            if fixture in MALFORMED:
                continue
            try:
                reports.append(RULES[cat](fields, capture, framing))
            except Reject as reason:
                rejections[str(reason)] = rejections.get(str(reason), 0) + 1
    lines = [f"# {fixture}: expected values from {tshark_version()}",
             "# generated by tests/data/asterix/asterix_expected.py; do not edit by hand",
             f"framing {framing}",
             f"tshark_blocks {len(blocks)}",
             f"tshark_records {records}"]
    lines += [f"radar {r}" for r in sorted(radars)]
    if fixture in MALFORMED:
        return lines
    lines.append(f"reports {len(reports)}")
    lines.append(f"distinct_ids {len({(r['src'], r['id']) for r in reports})}")
    lines.append(f"distinct_addresses {len({r['addr'] for r in reports if 'addr' in r})}")
    lines.append(f"coasting {sum(r['coast'] for r in reports)}")
    lines.append(f"track_ends {sum(r['end'] for r in reports)}")
    if reports:
        lines.append(f"t_first {fmt(min(r['t'] for r in reports))}")
        lines.append(f"t_last {fmt(max(r['t'] for r in reports))}")
    lines += [f"reject {reason} {count}" for reason, count in sorted(rejections.items())]
    step = max(1, len(reports) // SAMPLES)
    for r in reports[::step][:SAMPLES]:
        lines.append("sample " + " ".join(f"{k}={fmt(v)}" for k, v in r.items() if k != "cs")
                     + f" cs={r['cs'] or '-'}")
    return lines


def wrapped_pcap(data, framing, tmp):
    """The data as tshark reads it: pcap fixtures as they are, other framings re-wrapped."""
    pcap = Path(tmp) / "wrapped.pcap"
    if framing == "pcap":
        pcap.write_bytes(data)
    elif framing == "ff":
        wrap_as_pcap([frame[8:-4] for frame in walk_ff(data)], pcap)
    else:
        wrap_as_pcap(walk_raw(data), pcap)
    return pcap


def write_expected(out_dir, name, lines):
    expected = out_dir / "expected" / (name.replace("/", "__") + ".txt")
    expected.parent.mkdir(parents=True, exist_ok=True)
    expected.write_text("\n".join(lines) + "\n")


def build(shared, out_dir):
    for fixture, (origin, framing, seconds) in FIXTURES.items():
        data = (shared / origin).read_bytes()
        if seconds is not None:
            data = excerpt_ff(data, seconds)
        target = out_dir / fixture
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
        if fixture in NO_TSHARK:
            continue
        with tempfile.TemporaryDirectory() as tmp:
            lines = expected_lines(fixture, framing, tshark_blocks(wrapped_pcap(data, framing, tmp)))
        write_expected(out_dir, fixture, lines)
    for name, (origin, framing) in SHARED_ONLY.items():
        data = (shared / origin).read_bytes()
        with tempfile.TemporaryDirectory() as tmp:
            lines = expected_lines(name, framing, tshark_blocks(wrapped_pcap(data, framing, tmp)))
        lines.insert(2, f"# data read in place from the shared recordings: {origin} (never copied)")
        write_expected(out_dir, name, lines)


def excerpt_ff(data, seconds):
    """The leading frames whose I062/070 lies within `seconds` of the first one."""
    frames = walk_ff(data)
    with tempfile.TemporaryDirectory() as tmp:
        pcap = Path(tmp) / "all.pcap"
        wrap_as_pcap([frame[8:-4] for frame in frames], pcap)
        out = subprocess.run(["tshark", "-r", str(pcap), "-T", "fields", "-e", "asterix.062_070_VALUE"],
                             capture_output=True, text=True, check=True).stdout.split("\n")
    first = float(out[0])
    keep = next(i for i, tod in enumerate(out) if tod and float(tod) - first > seconds)
    return b"".join(frames[:keep])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--shared", type=Path, default=DEFAULT_SHARED)
    parser.add_argument("--check", action="store_true", help="compare with the checked-in files")
    args = parser.parse_args()
    if not args.check:
        build(args.shared, HERE)
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        build(args.shared, Path(tmp))
        diff = subprocess.run(["diff", "-r", "-x", "*.py", "-x", "*.md", str(HERE), tmp])
        return diff.returncode


if __name__ == "__main__":
    sys.exit(main())

"""A small Mode S extended squitter (DF17) encoder, and the decoder that checks it, for the
tests that feed a real ADS-B decoder (test_dump1090_peer.py). Written from the public
specifications: ICAO Annex 10 Vol. IV and its technical provisions for extended squitter
(the CPR algorithm, the message layouts) as "The 1090 MHz Riddle" (Junzi Sun,
https://mode-s.org/decode/) explains them.

A DF17 frame is 112 bits: DF (5) = 17, CA (3), the 24-bit address AA, the 56-bit message ME
and the 24-bit parity PI. The ME fields encoded here, bit 1 being the first of ME:
- airborne position (type codes 9-18): TC 5, surveillance status 2, single antenna flag 1,
  altitude 12 (Q bit = 1: 25 ft steps), time flag T 1, CPR format F 1 (0 even, 1 odd),
  CPR latitude 17, CPR longitude 17;
- identification (type codes 1-4): TC 5, category 3, eight characters of 6 bits;
- airborne velocity, subtype 1 (ground speed, subsonic): TC 5 = 19, subtype 3 = 1, intent
  change 1, IFR capability 1, NACv 3, east-west sign 1 (1 = west) and speed 10 (kt + 1),
  north-south sign 1 (1 = south) and speed 10 (kt + 1), vertical rate source 1 (0 GNSS,
  1 barometric), sign 1 (1 = down) and rate 9 (64 ft/min steps + 1), 2 reserved,
  GNSS-minus-baro sign 1 (1 = below) and difference 7 (25 ft steps + 1).
A speed, rate or difference field of 0 means "no information".
"""

import math

# The 6-bit character set of the identification: index = code ('#' unused).
CHARSET = "#ABCDEFGHIJKLMNOPQRSTUVWXYZ##### ###############0123456789######"
# The parity generator polynomial: x^24 + the 24 bits 0xFFF409.
GENERATOR = (1 << 24) | 0xFFF409
NZ = 15           # latitude zones between the equator and a pole
CPR_BITS = 17     # airborne CPR resolution
CPR_SCALE = 1 << CPR_BITS


def crc24(data):
    """Remainder of the bits of `data` (bytes) divided by the generator. The parity of a
    message is the remainder of its 88 bits followed by 24 zeros; the remainder of a whole
    DF17 frame is 0, that of a DF20/21 reply its address (the parity is sent XORed with it)."""
    n = int.from_bytes(data, "big")
    for bit in range(len(data) * 8 - 1, 23, -1):
        if n >> bit & 1:
            n ^= GENERATOR << (bit - 24)
    return n


def df17(address, me, ca=5):
    """The 14-byte DF17 frame of a 56-bit ME (an int); CA 5: airborne (level 2+ transponder)."""
    head = bytes([17 << 3 | ca]) + address.to_bytes(3, "big") + me.to_bytes(7, "big")
    return head + crc24(head + b"\0\0\0").to_bytes(3, "big")


def pack(*fields):
    """An int of the (width, value) fields, the first the most significant."""
    n = 0
    for width, value in fields:
        if not 0 <= value < 1 << width:
            raise ValueError(f"{value} does not fit in {width} bits")
        n = n << width | value
    return n


def unpack(n, total, *widths):
    """The fields of the `total`-bit int `n`, of the given widths from its most significant."""
    out, shift = [], total
    for width in widths:
        shift -= width
        out.append(n >> shift & ((1 << width) - 1))
    return out


# --- altitude -------------------------------------------------------------------------

def encode_altitude(alt_ft):
    """The 12-bit altitude field in 25 ft steps (Q bit, the 8th of the field, set): N =
    (alt + 1000) / 25 in 11 bits, split around the Q bit."""
    if alt_ft % 25:
        raise ValueError(f"{alt_ft} ft is not a multiple of 25 ft")
    n = (alt_ft + 1000) // 25
    if not 0 <= n < 1 << 11:
        raise ValueError(f"{alt_ft} ft is out of the 25 ft coding's range")
    return (n >> 4) << 5 | 1 << 4 | (n & 0xF)


def decode_altitude(field):
    if not field & 0x10:
        raise ValueError("altitude in Gillham (100 ft) coding")
    return ((field >> 5) << 4 | (field & 0xF)) * 25 - 1000


# --- CPR ------------------------------------------------------------------------------

def nl(lat):
    """Number of longitude zones at a latitude (the closed form of the NL table)."""
    lat = abs(lat)
    if lat == 0:
        return 4 * NZ - 1
    if lat == 87:
        return 2
    if lat > 87:
        return 1
    a = 1 - math.cos(math.pi / (2 * NZ))
    b = math.cos(math.pi / 180 * lat) ** 2
    return math.floor(2 * math.pi / math.acos(1 - a / b))


def dlat(odd):
    return 360.0 / (4 * NZ - odd)


def dlon(lat, odd):
    return 360.0 / max(nl(lat) - odd, 1)


def encode_cpr(lat, lon, odd):
    """(YZ, XZ): the 17-bit CPR latitude and longitude of a position, even (odd 0) or odd
    (odd 1) format: the position within its zone, rounded to 2^-17 of the zone."""
    odd = int(odd)
    d = dlat(odd)
    yz = math.floor(CPR_SCALE * (lat % d) / d + 0.5)
    rlat = d * (yz / CPR_SCALE + math.floor(lat / d))  # the latitude a decoder will find
    dl = dlon(rlat, odd)
    xz = math.floor(CPR_SCALE * (lon % dl) / dl + 0.5)
    return yz % CPR_SCALE, xz % CPR_SCALE


def decode_cpr_local(ref_lat, ref_lon, yz, xz, odd):
    """The position of one CPR message nearest a reference position (within half a zone)."""
    d = dlat(odd)
    j = math.floor(ref_lat / d) + math.floor(0.5 + (ref_lat % d) / d - yz / CPR_SCALE)
    lat = d * (j + yz / CPR_SCALE)
    dl = dlon(lat, odd)
    m = math.floor(ref_lon / dl) + math.floor(0.5 + (ref_lon % dl) / dl - xz / CPR_SCALE)
    return lat, dl * (m + xz / CPR_SCALE)


def decode_cpr_global(even, odd, latest_odd):
    """The position of an even and an odd CPR message ((YZ, XZ) each) without reference, that
    of the latest one (`latest_odd`); None when the two lie in different longitude zone
    counts (they must be decoded again with a later pair)."""
    (yz0, xz0), (yz1, xz1) = even, odd
    j = math.floor((59 * yz0 - 60 * yz1) / CPR_SCALE + 0.5)
    lat0 = dlat(0) * (j % 60 + yz0 / CPR_SCALE)
    lat1 = dlat(1) * (j % 59 + yz1 / CPR_SCALE)
    lat0 -= 360 if lat0 >= 270 else 0
    lat1 -= 360 if lat1 >= 270 else 0
    if nl(lat0) != nl(lat1):
        return None
    lat, xz = (lat1, xz1) if latest_odd else (lat0, xz0)
    n = nl(lat)
    ni = max(n - int(latest_odd), 1)
    m = math.floor((xz0 * (n - 1) - xz1 * n) / CPR_SCALE + 0.5)
    lon = 360.0 / ni * (m % ni + xz / CPR_SCALE)
    return lat, lon - 360 if lon >= 180 else lon


def cpr_half_cell_deg(lat, odd):
    """Half of a CPR step (latitude, longitude) in degrees at `lat`: how far a decoded
    position lies at most from the encoded one (about 2.6 m in latitude)."""
    return dlat(odd) / CPR_SCALE / 2, dlon(lat, odd) / CPR_SCALE / 2


# --- messages -------------------------------------------------------------------------

def airborne_position(address, lat, lon, alt_ft, odd, tc=11, ss=0, saf=0, t=0, ca=5):
    """DF17 airborne position with barometric altitude (type code 9-18; 11: NUCp 7)."""
    yz, xz = encode_cpr(lat, lon, odd)
    me = pack((5, tc), (2, ss), (1, saf), (12, encode_altitude(alt_ft)), (1, t), (1, int(odd)),
              (17, yz), (17, xz))
    return df17(address, me, ca)


def identification(address, callsign, tc=4, category=0, ca=5):
    """DF17 identification and category (type code 1-4): the callsign padded with spaces."""
    text = callsign.ljust(8)
    if len(text) > 8 or any(c == "#" or c not in CHARSET for c in text):
        raise ValueError(f"{callsign!r} is no callsign")
    return df17(address, pack((5, tc), (3, category), *((6, CHARSET.index(c)) for c in text)), ca)


def airborne_velocity(address, east_kt, north_kt, vr_fpm, vr_baro=True, nacv=0,
                      gnss_minus_baro_ft=None, ca=5, zero_rate_down=False, intent_change=0):
    """DF17 airborne velocity, subtype 1 (IFR capability flag 0): integer east and
    north ground speed components (kt, negative west and south, |v| <= 1021), vertical rate
    in multiples of 64 ft/min (negative down; a rate of 0 may be sent with the sign "down",
    `zero_rate_down`), the GNSS-minus-barometric altitude difference in 25 ft steps or None."""
    if vr_fpm % 64:
        raise ValueError(f"{vr_fpm} ft/min is not a multiple of 64 ft/min")
    if gnss_minus_baro_ft is None:
        dif_sign, dif = 0, 0
    else:
        if gnss_minus_baro_ft % 25:
            raise ValueError(f"{gnss_minus_baro_ft} ft is not a multiple of 25 ft")
        dif_sign, dif = int(gnss_minus_baro_ft < 0), abs(gnss_minus_baro_ft) // 25 + 1
    down = vr_fpm < 0 or (vr_fpm == 0 and zero_rate_down)
    me = pack((5, 19), (3, 1), (1, intent_change), (1, 0), (3, nacv),
              (1, int(east_kt < 0)), (10, abs(east_kt) + 1),
              (1, int(north_kt < 0)), (10, abs(north_kt) + 1),
              (1, int(vr_baro)), (1, int(down)), (9, abs(vr_fpm) // 64 + 1),
              (2, 0), (1, dif_sign), (7, dif))
    return df17(address, me, ca)


def decode(frame):
    """The fields of a DF17 frame (bytes) as the encoders above take them, with "df",
    "ca", "address", "tc", "crc" (the remainder: 0 when the parity is right); the message
    kinds encoded here only."""
    n = int.from_bytes(frame, "big")
    df, ca, address, me, _ = unpack(n, len(frame) * 8, 5, 3, 24, 56, 24)
    out = {"df": df, "ca": ca, "address": address, "crc": crc24(frame), "tc": me >> 51}
    if df != 17 or len(frame) != 14:
        return out
    tc = out["tc"]
    if 1 <= tc <= 4:
        fields = unpack(me, 56, 5, 3, *[6] * 8)
        out.update(category=fields[1], callsign="".join(CHARSET[c] for c in fields[2:]).rstrip())
    elif 9 <= tc <= 18:
        _, ss, saf, alt, t, odd, yz, xz = unpack(me, 56, 5, 2, 1, 12, 1, 1, 17, 17)
        out.update(ss=ss, saf=saf, alt_ft=decode_altitude(alt), t=t, odd=odd, lat_cpr=yz, lon_cpr=xz)
    elif tc == 19:
        (_, subtype, ic, ifr, nacv, ew_sign, ew, ns_sign, ns, vr_src, vr_sign, vr, _, dif_sign,
         dif) = unpack(me, 56, 5, 3, 1, 1, 3, 1, 10, 1, 10, 1, 1, 9, 2, 1, 7)
        out.update(subtype=subtype, ic=ic, ifr=ifr, nacv=nacv, vr_baro=vr_src)
        if subtype == 1:
            out.update(east_kt=None if ew == 0 else (ew - 1) * (-1 if ew_sign else 1),
                       north_kt=None if ns == 0 else (ns - 1) * (-1 if ns_sign else 1))
        out.update(vr_fpm=None if vr == 0 else (vr - 1) * 64 * (-1 if vr_sign else 1),
                   gnss_minus_baro_ft=None if dif == 0 else (dif - 1) * 25 * (-1 if dif_sign else 1))
    return out

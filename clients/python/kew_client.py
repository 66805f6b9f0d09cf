"""A client of kewd's alert stream (TCP, JSON lines, gpsd-style, protocol version 2).

Standard library only, Python >= 3.9: copy this one file next to your program.

    from kew_client import KewClient, Alert

    with KewClient("127.0.0.1", 4747, min_severity="warning") as client:
        for obj in client:
            if isinstance(obj, Alert):
                print(obj.state, obj.severity, obj.a.cs, obj.b.cs if obj.b else obj.volume, obj.t_los_s)

The protocol (every object and member) is documented in kew's docs/protocol.md ("Stream
objects, member by member") and design §5.3. Units are those of the JSON: times in UTC
seconds since the Unix epoch, durations in seconds, horizontal distances in metres,
altitudes and vertical distances in feet, vertical rates in feet per minute, speeds in
knots, angles in degrees. A figure kewd printed as `null` (not finite) reads as NaN, as
kew's own reader does.
"""

import dataclasses
import http.client
import json
import math
import random
import socket
import threading
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Optional

__all__ = [
    "PROTOCOL_VERSION", "SEVERITIES", "KewError", "ProtocolError", "AckError",
    "Party", "Alert", "Alerts", "Ack", "Alive", "Track", "Stats", "Error", "Start", "Version", "Unknown",
    "parse", "KewClient",
]

PROTOCOL_VERSION = 2
SEVERITIES = ("caution", "warning", "loss")


class KewError(Exception):
    """Base of this module's errors."""


class ProtocolError(KewError, ValueError):
    """A line that is not an object of the alert stream, or a server of another protocol."""


class AckError(KewError):
    """kewd refused an acknowledgement (HTTP status and kewd's reason)."""

    def __init__(self, status: int, reason: str):
        super().__init__(f"kewd refused the acknowledgement: HTTP {status}: {reason}")
        self.status = status
        self.reason = reason


# --- reading members -------------------------------------------------------------------

_MISSING = object()


class _Members:
    """Typed access to one JSON object's members, naming the member on a failure."""

    def __init__(self, obj: Any, where: str):
        if not isinstance(obj, dict):
            raise ProtocolError(f"{where} must be an object")
        self.obj = obj
        self.where = where

    def _get(self, key, required):
        value = self.obj.get(key, _MISSING)
        if value is _MISSING and required:
            raise ProtocolError(f"{self.where}: missing member {key!r}")
        return value

    def _fail(self, key, kind):
        raise ProtocolError(f"{self.where}: member {key!r} must be {kind}")

    def number(self, key, required=True) -> Optional[float]:
        value = self._get(key, required)
        if value is _MISSING:
            return None
        if value is None:  # kewd writes a non-finite figure as null
            return math.nan
        # bool is an int in Python, but true is no figure
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self._fail(key, "a number")
        return float(value)

    def integer(self, key, required=True) -> Optional[int]:
        value = self._get(key, required)
        if value is _MISSING:
            return None
        if isinstance(value, bool) or not isinstance(value, int):
            self._fail(key, "an integer")
        return value

    def text(self, key, required=True) -> Optional[str]:
        value = self._get(key, required)
        if value is _MISSING:
            return None
        if not isinstance(value, str):
            self._fail(key, "a string")
        return value

    def flag(self, key, required=True) -> Optional[bool]:
        value = self._get(key, required)
        if value is _MISSING:
            return None
        if not isinstance(value, bool):
            self._fail(key, "true or false")
        return value

    def array(self, key) -> list:
        value = self._get(key, True)
        if not isinstance(value, list):
            self._fail(key, "an array")
        return value

    def members(self, key) -> "_Members":
        """A required member that is an object."""
        value = self._get(key, True)
        if not isinstance(value, dict):
            self._fail(key, "an object")
        return _Members(value, f"{self.where}.{key}")


def _json_number(value: Optional[float]):
    """NaN back to JSON's null, as kewd writes it."""
    return None if value is not None and math.isnan(value) else value


# --- the stream's objects ----------------------------------------------------------------

@dataclass
class Party:
    """One aircraft of an alert: its last reported state, not predicted."""

    id: str
    """Track id: a 24-bit address as 6 hex digits, or a track number."""
    src: Optional[str]
    """Source of the track ("sbs", "cat062/25.100", ...), may be ""; None from servers that omit it."""
    cs: str
    """Callsign, "" when unknown."""
    lat: float
    """Latitude, degrees (WGS84)."""
    lon: float
    """Longitude, degrees (WGS84)."""
    alt_ft: float
    """Altitude, feet."""
    gs_kt: float
    """Ground speed, knots."""
    trk_deg: float
    """True track over ground, degrees clockwise from north, [0, 360)."""
    vr_fpm: float
    """Vertical rate, feet per minute, + climbing."""
    tn: Optional[int]
    """kew's system track number, 0-65535 (CAT004, Modbus); None from servers that omit it."""

    @classmethod
    def from_dict(cls, obj: Any, where: str = "party") -> "Party":
        return cls.from_members(_Members(obj, where))

    @classmethod
    def from_members(cls, m: "_Members") -> "Party":
        return cls(id=m.text("id"), src=m.text("src", False), cs=m.text("cs"), lat=m.number("lat"),
                   lon=m.number("lon"), alt_ft=m.number("alt_ft"), gs_kt=m.number("gs_kt"),
                   trk_deg=m.number("trk_deg"), vr_fpm=m.number("vr_fpm"), tn=m.integer("tn", False))

    def to_dict(self) -> Dict[str, Any]:
        """The JSON object, members in kewd's order; members that were absent left out."""
        out = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is not None:
                out[f.name] = _json_number(value) if isinstance(value, float) else value
        return out


@dataclass
class Alert:
    """One alert event (class ALERT), or an element of an ALERTS snapshot."""

    id: str
    """Deterministic alert id (the pair and the opening time), stable for the alert's life."""
    number: Optional[int]
    """16-bit alert number, as CAT004 I004/040 and the Modbus table."""
    seq: int
    """The event's sequence number in the stream (the same in every stream and the alert log)."""
    state: str
    """"new", "update" or "end"."""
    reason: Optional[str]
    """Only on "end": "cleared", "track_dropped" or "restart"; None otherwise."""
    severity: str
    """"caution", "warning" or "loss" ("none" possible on an end)."""
    t: float
    """Data time of the evaluation that produced the event, UTC seconds."""
    t_open: Optional[float]
    """Data time the alert opened, UTC seconds."""
    a: Party
    """The first aircraft of the pair, ordered by (source, id); an area warning's aircraft."""
    t_los_s: float
    """Seconds from t to loss of separation (an area warning: to entering the volume), 0
    when lost now."""
    kind: str = "stca"
    """"stca" (two aircraft) or "apw" (an aircraft and a volume: b and the pair figures
    are None, volume names it)."""
    b: Optional[Party] = None
    """The second aircraft (None for an area warning)."""
    t_cpa_s: Optional[float] = None
    """Seconds from t to the closest horizontal approach."""
    cpa_h_m: Optional[float] = None
    """Horizontal distance at the closest approach, metres."""
    cpa_v_ft: Optional[float] = None
    """Vertical distance at the closest approach, feet."""
    sep_h_m: Optional[float] = None
    """Current horizontal separation, metres."""
    sep_v_ft: Optional[float] = None
    """Current vertical separation, feet."""
    volume: Optional[str] = None
    """An area warning's volume ([[volume]] name)."""
    volume_kind: Optional[str] = None
    """An area warning's volume kind: "restricted", "danger", "prohibited" or "watch"."""
    hypothesis: str = "linear"
    """The prediction that found the conflict: "linear", "level_off", "turn", "proximity"
    ("linear" from servers before the member existed)."""
    region: Optional[str] = ""
    """The [[region]] whose parameters judged the pair; "" for the defaults, None for an
    area warning."""
    ack: bool = False
    """Acknowledged by an operator before this event."""

    @classmethod
    def from_dict(cls, obj: Any, where: str = "ALERT") -> "Alert":
        m = _Members(obj, where)
        kind = m.text("kind", False) or "stca"  # servers before "kind" knew only pairs
        alert = cls(
            id=m.text("id"), number=m.integer("number", False), seq=m.integer("seq"), state=m.text("state"),
            reason=m.text("reason", False), severity=m.text("severity"), t=m.number("t"),
            t_open=m.number("t_open", False), a=Party.from_members(m.members("a")), t_los_s=m.number("t_los_s"),
            kind=kind)
        if kind == "apw":
            alert.volume, alert.volume_kind, alert.region = m.text("volume"), m.text("volume_kind"), None
        else:
            alert.b = Party.from_members(m.members("b"))
            alert.t_cpa_s, alert.cpa_h_m, alert.cpa_v_ft = m.number("t_cpa_s"), m.number("cpa_h_m"), m.number("cpa_v_ft")
            alert.sep_h_m, alert.sep_v_ft = m.number("sep_h_m"), m.number("sep_v_ft")
        # Optional for servers that predate them: the protocol's defaults stand.
        hypothesis, region, ack = m.text("hypothesis", False), m.text("region", False), m.flag("ack", False)
        if hypothesis is not None:
            alert.hypothesis = hypothesis
        if region is not None:
            alert.region = region
        if ack is not None:
            alert.ack = ack
        return alert

    def to_dict(self) -> Dict[str, Any]:
        """The JSON object as kewd writes it ("class" first; absent members left out)."""
        out: Dict[str, Any] = {"class": "ALERT", "kind": self.kind}
        for f in dataclasses.fields(self):
            if f.name == "kind":
                continue
            value = getattr(self, f.name)
            if isinstance(value, Party):
                out[f.name] = value.to_dict()
            elif value is not None:
                out[f.name] = _json_number(value) if isinstance(value, float) else value
        return out

    @property
    def ended(self) -> bool:
        return self.state == "end"


@dataclass
class Alerts:
    """ALERTS: the snapshot of the active alerts that pass the filter, sent after ?WATCH
    (so again after every reconnection). Each element is the alert's latest event, with
    that event's own seq."""

    seq: int
    alerts: List[Alert]
    t: Optional[float] = None
    """Present in HTTP /api/alerts only: the data time, UTC seconds."""


@dataclass
class Ack:
    """ACK: alerts acknowledged by an operator."""

    seq: int
    """The seq of the last alert event before it."""
    t: float
    """Data time of the acknowledgement, UTC seconds."""
    by: str
    """The interface: "web" (HTTP POST /api/ack, this client's acknowledge()) or "modbus"."""
    client: str
    """The acknowledging client's "HOST:PORT" ("" from servers that omit it)."""
    ids: List[str]
    """The alert ids that were not acknowledged before."""


@dataclass
class Alive:
    """ALIVE: the server's heartbeat, every alive_interval_s (1 s by default)."""

    seq: int
    t: Optional[float]
    """Data time of the latest record processed, UTC seconds; None before the first."""
    tracks: int
    """Live tracks."""
    alerts: int
    """Active alerts."""
    records_per_s: float
    """Input records accepted per second (rates.records_per_s)."""
    updates_per_s: float
    """Track updates applied per second (rates.updates_per_s)."""
    uptime_s: Optional[int]
    """Seconds since the service started."""
    degraded: bool
    """health is not "healthy"."""
    health: str
    """"healthy", "no_data", "feed_stale", "records_refused", "input_dropping", "alert_log_failing",
    "standby" or "feed_unreachable"."""
    release: Optional[str] = None
    revision: Optional[str] = None


@dataclass
class Track:
    """TRACK: one track report (only with tracks=True, and when kewd allows it)."""

    seq: int
    t: float
    """Time of the report, UTC seconds."""
    id: str
    src: str
    cs: str
    lat: float
    """Degrees (WGS84)."""
    lon: float
    """Degrees (WGS84)."""
    alt_ft: float
    """Feet."""
    gs_kt: Optional[float] = None
    """Knots, when reported."""
    trk_deg: Optional[float] = None
    """Degrees, when reported."""
    vr_fpm: Optional[float] = None
    """Feet per minute, when reported."""
    gnd: bool = False
    """On the ground."""


@dataclass
class Stats:
    """STATS: kewd's figures (the answer to ?STATS). Every key is in `data`, as
    documented in docs/protocol.md "STATS"; stats["records"] reads one."""

    seq: int
    data: Dict[str, Any] = field(repr=False)

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def get(self, key: str, default: Any = None) -> Any:
        return self.data.get(key, default)


@dataclass
class Error:
    """ERROR: the last object before kewd closes the connection."""

    seq: int
    message: str


@dataclass
class Start:
    """START: a run of kewd began; another run id than before means kewd restarted and
    ended the alerts it had open (reason "restart")."""

    seq: int
    run: str
    """32 hex digits, random for each run."""
    release: str
    revision: Optional[str]
    t: float
    """Wall-clock time of the start, UTC seconds."""


@dataclass
class Version:
    """VERSION: the first object on a connection."""

    seq: int
    release: str
    revision: Optional[str]
    proto: int
    """The protocol version; this module speaks 1."""


@dataclass
class Unknown:
    """An object of a class this module does not know (a newer server may add some)."""

    cls: str
    seq: int
    data: Dict[str, Any] = field(repr=False)


def _parse_object(obj: Any) -> Any:
    cls = _Members(obj, "line").text("class")
    m = _Members(obj, cls)
    seq = m.integer("seq")
    if cls == "ALERT":
        return Alert.from_dict(obj)
    if cls == "ALERTS":
        alerts = [Alert.from_dict(e, f"ALERTS.alerts[{i}]") for i, e in enumerate(m.array("alerts"))]
        return Alerts(seq=seq, alerts=alerts, t=m.number("t", False))
    if cls == "ACK":
        ids = m.array("ids")
        if not all(isinstance(i, str) for i in ids):
            raise ProtocolError("ACK: member 'ids' must hold strings")
        return Ack(seq=seq, t=m.number("t"), by=m.text("by"), client=m.text("client", False) or "", ids=ids)
    if cls == "ALIVE":
        rates = m.members("rates")
        t = m.number("t", False)
        health = m.text("health", False)
        degraded = m.flag("degraded", False)
        if health is None:  # servers before "health" said only "degraded", a stale feed
            health = "feed_stale" if degraded else "healthy"
        return Alive(seq=seq, t=None if t is not None and math.isnan(t) else t, tracks=m.integer("tracks"),
                     alerts=m.integer("alerts"), records_per_s=rates.number("records_per_s"),
                     updates_per_s=rates.number("updates_per_s"), uptime_s=m.integer("uptime_s", False),
                     degraded=bool(degraded) if degraded is not None else health != "healthy", health=health,
                     release=m.text("release", False), revision=m.text("revision", False))
    if cls == "TRACK":
        return Track(seq=seq, t=m.number("t"), id=m.text("id"), src=m.text("src", False) or "",
                     cs=m.text("cs", False) or "", lat=m.number("lat"), lon=m.number("lon"),
                     alt_ft=m.number("alt_ft"), gs_kt=m.number("gs_kt", False),
                     trk_deg=m.number("trk_deg", False), vr_fpm=m.number("vr_fpm", False),
                     gnd=bool(m.flag("gnd", False)))
    if cls == "STATS":
        return Stats(seq=seq, data=obj)
    if cls == "ERROR":
        return Error(seq=seq, message=m.text("message"))
    if cls == "START":
        return Start(seq=seq, run=m.text("run"), release=m.text("release"), revision=m.text("revision", False),
                     t=m.number("t"))
    if cls == "VERSION":
        return Version(seq=seq, release=m.text("release"), revision=m.text("revision", False), proto=m.integer("proto"))
    return Unknown(cls=cls, seq=seq, data=obj)


def parse(line) -> Any:
    """One line of the stream (str or bytes, a trailing newline allowed) as its object:
    Version, Start, Alerts, Alert, Ack, Alive, Track, Stats, Error, or Unknown for a
    class this module does not know. Members it does not know are ignored. Raises
    ProtocolError for a line that is not JSON, not an object, or lacks a required member
    or has one of the wrong type."""
    if isinstance(line, (bytes, bytearray)):
        try:
            line = line.decode("utf-8")
        except UnicodeDecodeError as e:
            raise ProtocolError(f"not UTF-8: {e}") from None
    try:
        obj = json.loads(line)
    except ValueError as e:
        raise ProtocolError(f"not JSON: {e}: {line[:200]!r}") from None
    return _parse_object(obj)


# --- the client ---------------------------------------------------------------------------

def _host_text(host: str, port: int) -> str:
    return f"[{host}]:{port}" if ":" in host else f"{host}:{port}"


class KewClient:
    """A subscriber of kewd's alert stream.

    Iterating (`for obj in client:`) connects, sends ?WATCH and yields the stream's objects
    as they come: Version and Start, then an Alerts snapshot of the active alerts, then
    Alert events, Alive heartbeats, Ack objects (and Track ones with tracks=True). When the
    connection is lost (kewd restarting, the network, an Error from kewd) and reconnect is
    true, the client waits, with exponential back-off from backoff_min_s up to
    backoff_max_s, connects again and sends ?WATCH again; the new Start and Alerts tell
    what happened meanwhile (a new run id: kewd restarted). Without reconnect, the
    iteration ends with the connection (and a first connection that fails raises
    OSError). close(), from any thread, ends it for good. A line that is not the protocol,
    or a VERSION of another protocol version, raises ProtocolError.

    One iteration at a time per client; acknowledge(), stats() and close() may be called
    from other threads while it runs.
    """

    def __init__(self, host: str = "127.0.0.1", port: int = 4747, min_severity: str = "caution",
                 tracks: bool = False, http_port: int = 8747, reconnect: bool = True,
                 backoff_min_s: float = 0.5, backoff_max_s: float = 30, *, timeout_s: float = 10.0):
        """host, port: kewd's alert stream ([service] alert_listen). min_severity: the
        least severe alerts to receive ("caution", "warning", "loss"; the end of an
        alert this client was sent arrives whatever its severity). tracks: receive TRACK objects too. http_port:
        kewd's HTTP server ([http] listen), for acknowledge(). backoff_min_s,
        backoff_max_s: the first and the longest wait between reconnection attempts,
        seconds. timeout_s: connecting, and each HTTP or ?STATS exchange, seconds."""
        if min_severity not in SEVERITIES:
            raise ValueError(f"min_severity must be one of {', '.join(SEVERITIES)}, not {min_severity!r}")
        if not 0 < backoff_min_s <= backoff_max_s:
            raise ValueError("0 < backoff_min_s <= backoff_max_s is required")
        self.host = host
        self.port = port
        self.http_port = http_port
        self.min_severity = min_severity
        self.tracks = tracks
        self.reconnect = reconnect
        self.backoff_min_s = backoff_min_s
        self.backoff_max_s = backoff_max_s
        self.timeout_s = timeout_s
        self.connections = 0
        """Connections made so far that sent ?WATCH (1 after the first, 2 after a reconnection...)."""
        self._closed = threading.Event()
        self._lock = threading.Lock()
        self._sock: Optional[socket.socket] = None

    def __enter__(self) -> "KewClient":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Ends the iteration (from any thread) and closes the connection."""
        self._closed.set()
        with self._lock:
            sock = self._sock
        if sock is not None:
            try:
                # Wakes a reader blocked in recv() in another thread; close() alone would not.
                sock.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass

    def close_after(self, seconds: float) -> None:
        """Closes the client `seconds` from now (> 0), from a timer thread."""
        timer = threading.Timer(seconds, self.close)
        timer.daemon = True
        timer.start()

    @property
    def closed(self) -> bool:
        return self._closed.is_set()

    def _watch_request(self) -> bytes:
        request = {"enable": True, "min_severity": self.min_severity, "tracks": self.tracks}
        return b"?WATCH=" + json.dumps(request, separators=(",", ":")).encode() + b"\n"

    def _connect(self) -> socket.socket:
        sock = socket.create_connection((self.host, self.port), timeout=self.timeout_s)
        # kewd writes an ALIVE every second, but a peer that vanished without a FIN
        # (power, network) would leave recv() waiting for ever: keepalive probes notice.
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_KEEPALIVE, 1)
        for name, value in (("TCP_KEEPIDLE", 10), ("TCP_KEEPINTVL", 5), ("TCP_KEEPCNT", 3)):
            if hasattr(socket, name):
                sock.setsockopt(socket.IPPROTO_TCP, getattr(socket, name), value)
        sock.settimeout(None)  # the stream may be quiet for long; keepalive judges the peer
        return sock

    def _lines(self, sock: socket.socket) -> Iterator[bytes]:
        reader = sock.makefile("rb")
        try:
            while True:
                line = reader.readline()
                # A line without its newline was cut by the connection's loss: not an object.
                if not line.endswith(b"\n"):
                    return
                yield line
        finally:
            reader.close()

    def _wait(self, delay_s: float) -> bool:
        """Sleeps before a reconnection; False when close() came meanwhile."""
        # Jitter, so that the clients of a restarted kewd do not all come back at once.
        return not self._closed.wait(delay_s * random.uniform(0.75, 1.0))

    def __iter__(self) -> Iterator[Any]:
        delay = self.backoff_min_s
        while not self._closed.is_set():
            try:
                sock = self._connect()
            except OSError:
                if not self.reconnect:
                    raise
                if not self._wait(delay):
                    return
                delay = min(delay * 2, self.backoff_max_s)
                continue
            with self._lock:
                self._sock = sock
            if self._closed.is_set():  # close() ran before the socket was visible to it
                sock.close()
                return
            try:
                sock.sendall(self._watch_request())
                self.connections += 1
                for line in self._lines(sock):
                    obj = parse(line)
                    if isinstance(obj, Version) and obj.proto != PROTOCOL_VERSION:
                        raise ProtocolError(f"kewd speaks protocol {obj.proto}, this client {PROTOCOL_VERSION}")
                    if isinstance(obj, Alerts):
                        # The watch was accepted: the next loss starts the back-off afresh.
                        # (Not on connecting: a server that accepts and then refuses,
                        # e.g. with too many subscribers, must not be hammered.)
                        delay = self.backoff_min_s
                    yield obj
            except OSError:
                pass  # the connection was lost: as end of stream
            finally:
                with self._lock:
                    self._sock = None
                sock.close()
            if self._closed.is_set() or not self.reconnect:
                return
            if not self._wait(delay):
                return
            delay = min(delay * 2, self.backoff_max_s)

    def stats(self) -> Stats:
        """kewd's figures (?STATS), on a connection of its own so that the iteration's
        stream is left as it is."""
        with socket.create_connection((self.host, self.port), timeout=self.timeout_s) as sock:
            sock.sendall(b"?STATS\n")
            for line in self._lines(sock):
                obj = parse(line)
                if isinstance(obj, Stats):
                    return obj
                if isinstance(obj, Error):
                    raise KewError(f"kewd refused ?STATS: {obj.message}")
        raise KewError("kewd closed the connection before answering ?STATS")

    def acknowledge(self, alert_id: Optional[str] = None) -> List[str]:
        """Acknowledges one alert (by its id) or, with None, every active alert, through
        kewd's HTTP server (POST /api/ack; the alert stream takes no acknowledgement).
        Returns the ids that were not acknowledged before (possibly none); an Ack object
        naming them follows on the stream ("by": "web"). Raises AckError when kewd refuses
        (403: the host is not one kewd answers to as itself, see [http] host_names), and
        OSError when it cannot be reached."""
        body = json.dumps({"all": True} if alert_id is None else {"id": alert_id}).encode()
        host = _host_text(self.host, self.http_port)
        connection = http.client.HTTPConnection(self.host, self.http_port, timeout=self.timeout_s)
        try:
            connection.putrequest("POST", "/api/ack", skip_host=True, skip_accept_encoding=True)
            # kewd accepts a write only from a page of its own origin (against cross-site
            # requests from a browser): Origin must be http:// + Host, and X-Kew-Ack set.
            for key, value in (("Host", host), ("Origin", "http://" + host),
                               ("Content-Type", "application/json"), ("X-Kew-Ack", "1"),
                               ("Content-Length", str(len(body)))):
                connection.putheader(key, value)
            connection.endheaders(body)
            response = connection.getresponse()
            data = response.read()
        finally:
            connection.close()
        if response.status != 200:
            raise AckError(response.status, data.decode("utf-8", "replace").strip())
        try:
            ids = json.loads(data)["acknowledged"]
        except (ValueError, KeyError, TypeError):
            raise ProtocolError(f"unexpected reply to POST /api/ack: {data[:200]!r}") from None
        return list(ids)

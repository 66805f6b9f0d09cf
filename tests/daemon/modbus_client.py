#!/usr/bin/python3
"""Modbus TCP client for kew's alarm register map (design §5.5, README.md, "Modbus TCP alarm map").

A small command-line tool over pymodbus (written for Debian 12's python3-pymodbus
3.0.0, whose API is ModbusTcpClient(host, port, timeout=whole seconds)), used by the
integration tests of the Modbus server and by the kewd end-to-end tests. It prints one
JSON object on stdout and exits with:
  0  the request succeeded          {"ok": true, "values": [...]}  (writes: no "values")
                                    with "client": its own "HOST:PORT", as the server sees it
  2  the server answered an exception {"ok": false, "exception_code": N}
  1  no usable answer (connection refused or closed, timeout, pymodbus missing)
                                    {"ok": false, "error": "..."}

Usage:
  modbus_client.py [--host H] --port P [--unit U] [--timeout S] COMMAND ARGS...
  COMMAND:
    read-coils START COUNT
    read-discrete-inputs START COUNT      (alias read-inputs)
    read-input-registers START COUNT      (alias read-registers)
    read-holding-registers START COUNT
    write-coil ADDRESS 0|1                (coil 0 = 1 acknowledges every alert)
    write-register ADDRESS VALUE          (kew refuses every register write)
    read-map [--entries N]                the whole map decoded: {"ok": true, "map": {...}};
                                          reads up to N table rows (fewer when the
                                          server's table is shorter), each with its
                                          "kind" (0 STCA, 1 APW) from registers 9-12
Addresses are PDU addresses (0-based), as in the documentation's tables.
"""

import argparse
import json
import logging
import sys

DISCRETE_INPUTS = ["any_alert", "caution", "warning", "loss", "feed_healthy", "degraded"]
STATUS_REGISTERS = ["map_version", "active_alerts", "highest_severity", "live_tracks",
                    "seconds_since_last_record", "heartbeat", "uptime_high", "uptime_low",
                    "unacknowledged"]
TABLE_COLUMNS = ["alert_number", "severity", "track_a", "track_b", "t_los_s",
                 "cpa_h_10m", "cpa_v_10ft", "state"]
TABLE_START = 16
ROW_KINDS = 9  # registers 9-12: bit r % 16 of register 9 + r // 16 is row r's kind (1 APW)
ILLEGAL_DATA_ADDRESS = 2


class ModbusFailure(Exception):
    """The request got no usable answer."""


class ModbusExceptionAnswer(Exception):
    """The server answered with a Modbus exception."""

    def __init__(self, code):
        super().__init__(f"exception code {code}")
        self.code = code


def checked(response):
    """The response, or the exception it stands for."""
    if response is None:
        raise ModbusFailure("no response")
    if response.isError():
        code = getattr(response, "exception_code", None)
        if code is None:
            raise ModbusFailure(str(response))
        raise ModbusExceptionAnswer(code)
    return response


class Client:
    def __init__(self, host, port, unit, timeout):
        from pymodbus.client import ModbusTcpClient
        from pymodbus.exceptions import ModbusException as PymodbusError
        self.error_type = PymodbusError
        self.unit = unit
        self.client = ModbusTcpClient(host, port=port, timeout=timeout, retries=0,
                                      retry_on_empty=False)
        if not self.client.connect():
            raise ModbusFailure(f"cannot connect to {host}:{port}")

    def close(self):
        self.client.close()

    def local_address(self):
        """The client's own "HOST:PORT" (IPv6 in brackets): what kewd names in an ACK."""
        host, port = self.client.socket.getsockname()[:2]
        return f"[{host}]:{port}" if ":" in host else f"{host}:{port}"

    def call(self, method, *args):
        try:
            return checked(getattr(self.client, method)(*args, slave=self.unit))
        except self.error_type as error:  # connection lost, timeout
            raise ModbusFailure(str(error)) from error

    def bits(self, method, start, count):
        return [int(b) for b in self.call(method, start, count).bits[:count]]

    def registers(self, method, start, count):
        return list(self.call(method, start, count).registers)


def read_map(client, entries):
    inputs = client.bits("read_discrete_inputs", 0, len(DISCRETE_INPUTS))
    status = client.registers("read_input_registers", 0, TABLE_START)
    decoded = {
        "discrete_inputs": dict(zip(DISCRETE_INPUTS, inputs)),
        "registers": dict(zip(STATUS_REGISTERS, status)),
        "table": [],
    }
    decoded["registers"]["uptime_s"] = (status[6] << 16) | status[7]
    width = len(TABLE_COLUMNS)
    for row in range(entries):
        try:
            values = client.registers("read_input_registers", TABLE_START + row * width, width)
        except ModbusExceptionAnswer as answer:
            if answer.code == ILLEGAL_DATA_ADDRESS:  # the server's table is shorter
                break
            raise
        if values[-1] == 0:  # state 0: an empty row, and every later row is empty too
            break
        entry = dict(zip(TABLE_COLUMNS, values))
        entry["kind"] = (status[ROW_KINDS + row // 16] >> (row % 16)) & 1
        decoded["table"].append(entry)
    return decoded


def run(args):
    client = Client(args.host, args.port, args.unit, args.timeout)
    try:
        return {"client": client.local_address(), **request(client, args)}
    finally:
        client.close()


def request(client, args):
    """Sends the request of `args`; its result."""
    if args.command == "read-coils":
        return {"values": client.bits("read_coils", args.start, args.count)}
    if args.command in ("read-discrete-inputs", "read-inputs"):
        return {"values": client.bits("read_discrete_inputs", args.start, args.count)}
    if args.command in ("read-input-registers", "read-registers"):
        return {"values": client.registers("read_input_registers", args.start, args.count)}
    if args.command == "read-holding-registers":
        return {"values": client.registers("read_holding_registers", args.start, args.count)}
    if args.command == "write-coil":
        client.call("write_coil", args.address, bool(args.value))
        return {}
    if args.command == "write-register":
        client.call("write_register", args.address, args.value)
        return {}
    if args.command == "read-map":
        return {"map": read_map(client, args.entries)}
    raise ModbusFailure(f"unknown command {args.command}")


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, required=True)
    parser.add_argument("--unit", type=int, default=1, help="unit id (default 1)")
    parser.add_argument("--timeout", type=int, default=2, help="whole seconds (default 2)")
    commands = parser.add_subparsers(dest="command", required=True)
    for name, aliases in (("read-coils", []), ("read-discrete-inputs", ["read-inputs"]),
                          ("read-input-registers", ["read-registers"]),
                          ("read-holding-registers", [])):
        read = commands.add_parser(name, aliases=aliases)
        read.add_argument("start", type=int)
        read.add_argument("count", type=int)
    for name in ("write-coil", "write-register"):
        write = commands.add_parser(name)
        write.add_argument("address", type=int)
        write.add_argument("value", type=int)
    whole = commands.add_parser("read-map")
    whole.add_argument("--entries", type=int, default=8, help="table rows to read (default 8)")
    return parser.parse_args(argv)


def main(argv):
    args = parse_arguments(argv)
    # The JSON line is the report; pymodbus' own error log would only repeat it.
    logging.getLogger("pymodbus").setLevel(logging.CRITICAL)
    try:
        result = {"ok": True, **run(args)}
        status = 0
    except ModbusExceptionAnswer as answer:
        result, status = {"ok": False, "exception_code": answer.code}, 2
    except (ModbusFailure, ImportError, OSError) as error:
        result, status = {"ok": False, "error": str(error)}, 1
    print(json.dumps(result, sort_keys=True))
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

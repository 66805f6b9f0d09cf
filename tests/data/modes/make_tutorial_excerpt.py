"""Cuts tutorial_0934-0938.jsonl.gz out of the shared recording traffic-opensky/tutorial.jsonl.gz:
every line (every Mode S frame, whatever its type or aircraft) whose "timestamp" lies in
[2024-06-06 09:34:00, 09:38:00) UTC, copied byte for byte, gzip level 9 with no name or time
in its header (the same bytes on every run).

  python3 make_tutorial_excerpt.py [../../../../shared/data/recordings/traffic-opensky/tutorial.jsonl.gz]
"""
import gzip
import json
import os
import sys

START, END = 1717666440, 1717666680  # 2024-06-06 09:34:00 and 09:38:00 UTC
HERE = os.path.dirname(os.path.abspath(__file__))
source = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    HERE, "..", "..", "..", "..", "shared", "data", "recordings", "traffic-opensky", "tutorial.jsonl.gz")
with gzip.open(source, "rb") as f:
    lines = [line for line in f.read().split(b"\n") if line]
kept = [line for line in lines if START <= json.loads(line)["timestamp"] < END]
with open(os.path.join(HERE, "tutorial_0934-0938.jsonl.gz"), "wb") as f:
    f.write(gzip.compress(b"".join(line + b"\n" for line in kept), 9, mtime=0))
print(f"{len(kept)} of {len(lines)} lines")

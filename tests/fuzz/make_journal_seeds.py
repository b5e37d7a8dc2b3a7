#!/usr/bin/env python3
"""Seed corpus of fuzz_sweep_journal: journals of the identity the target opens with (so the
fuzzer starts from files whose point records are decoded), one whole, one torn, one of another
sweep. Layout as sim/sweep_journal.h; run from tests/fuzz/ to rewrite corpus/sweep_journal/."""
import struct, zlib

IDENTITY = b"ar = 3.9\nshard = 1/1\n"
MAGIC = b"dimerlab sweep journal 2\n"

def record(payload):
    return struct.pack("<I", len(payload)) + payload + struct.pack("<I", zlib.crc32(payload))

def string(s):
    return struct.pack("<I", len(s)) + s

def point(index, mode, bouncing, speed, impact):
    p = struct.pack("<q", index) + string(mode) + struct.pack("<b", bouncing)
    p += struct.pack("<4d", speed, 1e-5, speed * 25 / 9.81, 1e-5 * 25 / 9.81)
    p += struct.pack("<b", 1) + struct.pack("<d", 18.0)
    p += struct.pack("<2d", 0.0, 1.0) + struct.pack("<2d", 0.6, 0.0)
    p += string(impact) + struct.pack("<d", 1.0) + struct.pack("<b", 1) + string(b"")
    return p

whole = MAGIC + record(IDENTITY) + record(point(0, b"drift", 1, 0.02, b"continuous_slide"))
whole += record(point(1, b"rest", -1, 0.0, b"none"))
open("corpus/sweep_journal/whole", "wb").write(whole)
open("corpus/sweep_journal/torn", "wb").write(whole[:-5])
open("corpus/sweep_journal/other_sweep", "wb").write(MAGIC + record(b"ar = 6.1\nshard = 1/1\n"))

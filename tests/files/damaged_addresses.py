#!/usr/bin/python3
"""A trace in h5py's format (no checksums) whose root object header continues in a block of impossible
length or address: the HDF5 library then asks for a metadata image of 4 GiB or 1 TiB (libFuzzer found
the second). granwave must refuse each with exit 2 naming the file, whether the allocation succeeds and
the read fails (glibc) or the allocation fails (a sanitizer's allocator).

usage: damaged_addresses.py GRANWAVE WORKDIR
"""
from __future__ import annotations

import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fuzz_files  # noqa: E402


def root_continuation(data: bytes) -> int:
    """Byte offset of the body (address, then length) of the continuation message in the root group's
    object header, read from a version-0 superblock and the version-1 object header it points to."""
    if data[:8] != b"\x89HDF\r\n\x1a\n" or data[8] != 0 or data[13] != 8 or data[14] != 8:
        sys.exit("damaged_addresses: the legacy trace no longer has a version-0 superblock with 8-byte offsets")
    header = struct.unpack_from("<Q", data, 64)[0]  # the root symbol-table entry's object header address
    if data[header] != 1:
        sys.exit("damaged_addresses: the root object header is not version 1")
    size = struct.unpack_from("<I", data, header + 8)[0]
    at, end = header + 16, header + 16 + size
    while at + 8 <= end:
        kind, length = struct.unpack_from("<HH", data, at)
        if kind == 0x10:
            return at + 8
        at += 8 + length
    sys.exit("damaged_addresses: no continuation message in the root object header's first block")


def main(argv) -> int:
    gw, work = argv[1], argv[2]
    os.makedirs(work, exist_ok=True)
    trace, legacy = os.path.join(work, "trace.h5"), os.path.join(work, "legacy.h5")
    fuzz_files.must([gw, "run", fuzz_files.CASE, "-o", trace, "--quiet"])
    fuzz_files.legacy_copy(trace, legacy)
    data = open(legacy, "rb").read()
    body = root_continuation(data)
    length = struct.unpack_from("<Q", data, body + 8)[0]
    damages = {
        "length_4GiB": (body + 8, 0xFFFFFFFF),
        "length_1TiB": (body + 8, (length & 0xFF) | 0xFFFFFFFF00),
        "address_1TiB": (body, 0xFFFFFFFF00),
    }
    failures = 0
    for name, (offset, value) in damages.items():
        path = os.path.join(work, name + ".h5")
        damaged = bytearray(data)
        struct.pack_into("<Q", damaged, offset, value)
        open(path, "wb").write(damaged)
        r = subprocess.run([gw, "analyze", path, "--json"], capture_output=True, text=True, timeout=60)
        named = path in r.stderr and ("not a readable HDF5 file" in r.stderr or "damaged" in r.stderr)
        ok = r.returncode == 2 and named
        print("%-20s exit %d  %s" % (name, r.returncode, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ""))
        if not ok:
            failures += 1
            print("  expected exit 2 and a message naming %s as unreadable or damaged" % path)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

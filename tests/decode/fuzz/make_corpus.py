#!/usr/bin/env python3
"""Writes the small committed seed corpus for the decode fuzz targets (synthetic files only: the real Lytro files
stay in ../shared/data and are mutated at test time by replay_main --derive-from). Deterministic; rerun to
regenerate: python3 tests/decode/fuzz/make_corpus.py"""
import hashlib
import json
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
FILE_MAGIC = b"\x89LFP\r\n\x1a\n\x00\x00\x00\x01"


def section(kind, payload):
    sha = ("sha1-" + hashlib.sha1(payload).hexdigest()).encode()
    header = b"\x89LF" + kind + b"\r\n\x1a\n" + b"\x00" * 4 + struct.pack(">I", len(payload)) + sha + b"\x00" * 35
    body = header + payload
    return body + b"\x00" * (-len(body) % 16)


def ref(payload):
    return "sha1-" + hashlib.sha1(payload).hexdigest()


def container(sections):
    return FILE_MAGIC + struct.pack(">I", 0) + b"".join(sections)


def write(folder, name, data):
    with open(os.path.join(HERE, "corpus", folder, name), "wb") as f:
        f.write(data)


def main():
    rng = random.Random(7)
    f01_meta = {"image": {"width": 4, "height": 3, "rawDetails": {
        "pixelPacking": {"endianness": "big", "bitsPerPixel": 12},
        "pixelFormat": {"rightShift": 0, "black": {"r": 168, "gr": 168, "gb": 168, "b": 168},
                        "white": {"r": 4095, "gr": 4095, "gb": 4095, "b": 4095}},
        "mosaic": {"tile": "r,gr:gb,b", "upperLeftPixel": "b"}}},
        "devices": {"lens": {"zoomStep": 981, "focusStep": 582},
                    "mla": {"lensPitch": 1.39e-5, "rotation": 0.0019}, "sensor": {"pixelPitch": 1.4e-6}},
        "camera": {"model": "F01"}}
    raw = bytes(rng.randrange(256) for _ in range(18))  # 4x3 px, 12-bit
    meta = json.dumps(f01_meta, indent="\t").encode()
    toc = json.dumps({"picture": {"frameArray": [{"frame": {"metadataRef": ref(meta), "imageRef": ref(raw)},
                                                  "parameters": {"vendorContent": {"com.lytro.tags": {
                                                      "modulationFrame": False}}}}],
                                  "accelerationArray": [{"vendorContent": {"depthLut": {
                                      "width": 2, "height": 2, "imageRef": ref(b"\x00" * 16)}}}]}}).encode()
    f01 = container([section(b"M", toc), section(b"C", meta), section(b"C", raw), section(b"C", b"\x00" * 16)])
    write("container", "f01_small.lfp", f01)

    illum_meta = {"image": {"width": 5, "height": 2, "pixelPacking": {"endianness": "little", "bitsPerPixel": 10},
                            "pixelFormat": {"black": {"r": 64, "gr": 64, "gb": 64, "b": 64},
                                            "white": {"r": 1023, "gr": 1023, "gb": 1023, "b": 1023}},
                            "mosaic": {"tile": "r,gr:gb,b", "upperLeftPixel": "gr"}},
                  "camera": {"model": "ILLUM"}}
    raw10 = bytes(rng.randrange(256) for _ in range(15))  # 10 px -> 3 groups of 5 bytes
    toc2 = json.dumps({"frames": [{"frame": {"metadata": illum_meta, "imageRef": ref(raw10),
                                             "privateMetadata": {"camera": {"serialNumber": "B5000"}}}}],
                       "thumbnails": [{"imageRef": ref(b"\xff\xd8\xff\xd9")}]}).encode()
    illum = container([section(b"C", raw10), section(b"C", b"\xff\xd8\xff\xd9"), section(b"M", toc2)])
    write("container", "illum_small.lfr", illum)

    archive_toc = json.dumps({"files": [{"name": "C:\\T1CALIB\\MOD_0000.RAW", "dataRef": ref(b"abc")}],
                              "nextFile": "data.C.1"}).encode()
    write("container", "archive.C.0", container([section(b"M", archive_toc), section(b"C", b"abc")]))
    # Damaged seeds: bad SHA-1, length past the end, wrong section magic, truncated header.
    bad = bytearray(f01)
    bad[16 + 96 + 2] ^= 1
    write("container", "sha1_mismatch.lfp", bytes(bad))
    bad = bytearray(f01)
    bad[28:32] = struct.pack(">I", 0x7FFFFFF0)
    write("container", "length_past_end.lfp", bytes(bad))
    bad = bytearray(f01)
    bad[19] = ord("Z")
    write("container", "section_magic.lfp", bytes(bad))
    write("container", "truncated.lfp", f01[:70])

    for name, (packing, count) in {"f01_12bit": (0, 6), "illum_10bit": (1, 8), "le_16bit": (2, 5),
                                   "odd_10bit": (1, 7), "wrong_size": (0, 9)}.items():
        size = {0: (count + 1) // 2 * 3, 1: (count + 3) // 4 * 5, 2: count * 2}[packing]
        if name == "wrong_size":
            size -= 1
        write("raw", name + ".bin", bytes([packing, count & 0xFF, count >> 8]) +
              bytes(rng.randrange(256) for _ in range(size)))

    white_txt = {"master": {"picture": {"frameArray": [{"frame": {
        "metadata": f01_meta, "privateMetadata": {"camera": {"serialNumber": "A1"}}},
        "parameters": {"vendorContent": {"com.lytro.tags": {"modulationFrame": True}}}}]}}}
    write("metadata", "white.TXT", json.dumps(white_txt, indent="\t").encode() + b"\x00\x00\x1a")
    write("metadata", "frame.json", json.dumps(f01_meta).encode())
    write("metadata", "toc_inline.json", toc2)
    write("metadata", "broken.json", b'{"image": {"width": "wide", "height": [1], "rawDetails": 3}')


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Writes the committed seeds of the views-folder fuzz target (tests/core/fuzz/corpus/views_folder): small folders of
views in each naming FindViewsLayout detects, packed in the format of fuzz_folder.h ("@@ NAME\\n" then the file's
bytes). Views are tiny PNGs and TIFFs written here, so a seed stays near 1 KB (replay_main mutates the first KB).
Deterministic; rerun to regenerate: python3 tests/core/fuzz/make_folder_corpus.py"""
import os
import random
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png(width, height, channels, bits, rng):
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    sample_bytes = bits // 8
    rows = b"".join(b"\x00" + bytes(rng.randrange(256) for _ in range(width * channels * sample_bytes))
                    for _ in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", width, height, bits, colour_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def tiff(width, height, bits, rng):
    """A little-endian, uncompressed, one-strip greyscale TIFF."""
    pixels = bytes(rng.randrange(256) for _ in range(width * height * bits // 8))
    entries = [(256, 3, 1, width), (257, 3, 1, height), (258, 3, 1, bits), (259, 3, 1, 1), (262, 3, 1, 1),
               (273, 4, 1, 0), (277, 3, 1, 1), (278, 3, 1, height), (279, 4, 1, len(pixels))]
    ifd_size = 2 + 12 * len(entries) + 4
    data_offset = 8 + ifd_size
    ifd = struct.pack("<H", len(entries))
    for tag, kind, count, value in entries:
        if tag == 273:
            value = data_offset
        ifd += struct.pack("<HHI", tag, kind, count) + (struct.pack("<HH", value, 0) if kind == 3 else
                                                         struct.pack("<I", value))
    return b"II*\x00" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + pixels


def pfm(width, height, rng):
    values = b"".join(struct.pack("<f", rng.uniform(-2.0, 2.0)) for _ in range(width * height))
    return b"Pf\n%d %d\n-1.0\n" % (width, height) + values


def folder(files):
    return b"\n".join(b"@@ " + name.encode() + b"\n" + data for name, data in files)


def write(name, files):
    path = os.path.join(HERE, "corpus", "views_folder", name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(folder(files))


def main():
    rng = random.Random(11)
    # HCI naming, square: 2x2 RGB views, no parameters.cfg.
    write("hci_2x2.lf", [("input_Cam%03d.png" % c, png(4, 3, 3, 8, rng)) for c in range(4)])
    # HCI naming with parameters.cfg (3x1, linear transfer, a disparity range), weights and a disparity map.
    config = (b"[extrinsics]\nnum_cams_x = 3\nnum_cams_y = 1\n\n[meta]\ndisp_min = -1.5\ndisp_max = 2\n\n"
              b"[lfsp]\ntransfer = linear\n")
    write("hci_config_weights.lf", [("parameters.cfg", config)] +
          [("input_Cam%03d.png" % c, png(3, 2, 1, 8, rng)) for c in range(3)] +
          [("weight_Cam%03d.png" % c, png(3, 2, 1, 16, rng)) for c in range(3)] +
          [("disparity.pfm", pfm(3, 2, rng))])
    # <row>_<col> naming from 1, beside a smaller family of depth maps.
    write("row_col.lf", [("view_%d_%d.png" % (r, c), png(3, 3, 1, 8, rng)) for r in (1, 2) for c in (1, 2)] +
          [("depth_%d_%d.png" % (r, c), png(3, 3, 1, 8, rng)) for r in (1,) for c in (1, 2)])
    # LFToolbox naming: <name>_<index>_<a>_<b> with a the column.
    write("lftoolbox.lf", [("IMG_0001_%d_%d_%d.png" % (1 + b * 2 + a, a + 1, b + 1), png(3, 2, 2, 8, rng))
                           for b in range(2) for a in range(2)])
    # --views-pattern (the entry views_pattern) over names no detector knows.
    write("pattern.lf", [("views_pattern", b"cam{col}-{index}-{row}.png")] +
          [("cam%d-%d-%d.png" % (c, 3 * r + c, r), png(2, 2, 4, 8, rng)) for r in range(2) for c in range(3)])
    # 16-bit TIFF views, 1 x 2.
    write("tiff_16bit.lf", [("%d_%d.tif" % (0, c), tiff(3, 2, 16, rng)) for c in range(2)])
    # Damaged: one view of another size; a missing camera; weights numbered from 1.
    write("size_mismatch.lf", [("%d_%d.png" % (r, c), png(3 if (r, c) != (1, 1) else 4, 2, 1, 8, rng))
                               for r in range(2) for c in range(2)])
    write("hci_missing_camera.lf", [("input_Cam%03d.png" % c, png(2, 2, 1, 8, rng)) for c in (0, 1, 3, 4)])
    write("hci_weights_from_1.lf", [("input_Cam%03d.png" % c, png(2, 2, 1, 8, rng)) for c in range(4)] +
          [("weight_Cam%03d.png" % (c + 1), png(2, 2, 1, 8, rng)) for c in range(4)])
    # Fuzz finding: a parameters.cfg value that is not UTF-8 (nlohmann's dump of it threw type_error 316).
    write("parameters_not_utf8.lf", [("parameters.cfg", b"[extrinsics]\nnum_cams_x = \x87\nnum_cams_y = 2\n")] +
          [("input_Cam%03d.png" % c, png(2, 2, 1, 8, rng)) for c in range(4)])


if __name__ == "__main__":
    main()

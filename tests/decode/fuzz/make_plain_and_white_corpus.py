#!/usr/bin/env python3
"""Writes the committed seeds of two decode fuzz targets (synthetic files only):
  corpus/plain_raw     plain raw images: one option byte (plain_raw_fuzz.cc) then a PNG, TIFF or JPEG mosaic;
  corpus/white_folder  white-image folders packed as in tests/core/fuzz/fuzz_folder.h: MOD_####.TXT + .RAW pairs in
                       camera subfolders, a calibration archive data.C.0, a whites.json beside them.
Images come from tests/core/fuzz/make_folder_corpus.py's writers, JPEGs from corpus/jpeg, containers from
make_corpus.py's. Deterministic; rerun to regenerate: python3 tests/decode/fuzz/make_plain_and_white_corpus.py"""
import json
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "core", "fuzz"))
import make_corpus  # noqa: E402
from make_folder_corpus import folder, png, tiff  # noqa: E402


def write(corpus, name, data):
    path = os.path.join(HERE, "corpus", corpus, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def option(extension, camera=0, scene=False, bayer=False, levels=0):
    return bytes([extension | camera << 2 | (0x10 if scene else 0) | (0x20 if bayer else 0) | levels << 6])


PNG, TIF, JPG, TIFF = 0, 1, 2, 3
F01, ILLUM = 1, 2


def plain_raw(rng):
    with open(os.path.join(HERE, "corpus", "jpeg", "mosaic_40x24_q75.jpg"), "rb") as f:
        jpeg = f.read()
    with open(os.path.join(HERE, "corpus", "jpeg", "colour_8.jpg"), "rb") as f:
        colour_jpeg = f.read()
    write("plain_raw", "grey8.png.bin", option(PNG) + png(8, 6, 1, 8, rng))
    write("plain_raw", "grey16_f01_levels.png.bin", option(PNG, F01, levels=2) + png(6, 4, 1, 16, rng))
    write("plain_raw", "grey16_illum.tif.bin", option(TIF, ILLUM, bayer=True) + tiff(6, 4, 16, rng))
    write("plain_raw", "grey8_given_levels.tiff.bin", option(TIFF, levels=1) + tiff(4, 4, 8, rng))
    write("plain_raw", "refused_levels.png.bin", option(PNG, F01, levels=3) + png(4, 2, 1, 8, rng))
    # Three equal channels are one; different ones are a colour picture.
    grey = png(4, 4, 1, 8, random.Random(3))
    write("plain_raw", "grey_as_rgb.png.bin", option(PNG) + png(4, 4, 3, 8, rng))
    write("plain_raw", "grey_alpha.png.bin", option(PNG, ILLUM) + png(4, 4, 2, 8, rng))
    write("plain_raw", "one_row.png.bin", option(PNG) + png(5, 1, 1, 8, rng))
    # Greyscale JPEG mosaics: restored with a camera's grey, the scene's, and without a camera (scene refused).
    write("plain_raw", "mosaic_f01.jpg.bin", option(JPG, F01) + jpeg)
    write("plain_raw", "mosaic_illum_scene.jpg.bin", option(JPG, ILLUM, scene=True) + jpeg)
    write("plain_raw", "mosaic_scene_no_camera.jpg.bin", option(JPG, scene=True) + jpeg)
    write("plain_raw", "colour.jpg.bin", option(JPG, F01) + colour_jpeg)
    # A PNG named .jpg, and a JPEG named .png.
    write("plain_raw", "png_named_jpg.bin", option(JPG, F01) + grey)
    write("plain_raw", "jpeg_named_png.bin", option(PNG) + jpeg)


def white_txt(width, height, bits, serial, zoom, focus, exposure, dark=False, indent=None):
    packing = {12: "big", 10: "little", 16: "little"}[bits]
    top = (1 << bits) - 1
    metadata = {"image": {"width": width, "height": height, "rawDetails": {
        "pixelPacking": {"endianness": packing, "bitsPerPixel": bits},
        "pixelFormat": {"black": {"r": 64, "gr": 64, "gb": 64, "b": 64},
                        "white": {"r": top, "gr": top, "gb": top, "b": top}},
        "mosaic": {"tile": "r,gr:gb,b", "upperLeftPixel": "gr"}}},
        "devices": {"lens": {"zoomStep": zoom, "focusStep": focus}, "shutter": {"frameExposureDuration": exposure}}}
    frame = {"frame": {"metadata": metadata, "privateMetadata": {"camera": {"serialNumber": serial}}}}
    if dark:
        frame["parameters"] = {"vendorContent": {"com.lytro.tags": {"darkFrame": True}}}
    return json.dumps({"master": {"picture": {"frameArray": [frame]}}}, indent=indent).encode()


def packed(width, height, bits, level):
    """`level` at every pixel, packed as the TXT says (12-bit big-endian, 10-bit Illum, 16-bit little-endian)."""
    count = width * height
    if bits == 12:
        pair = bytes([level >> 4, (level & 15) << 4 | level >> 8, level & 255])
        return pair * ((count + 1) // 2)
    if bits == 10:
        group = bytes([level >> 2] * 4 + [sum((level & 3) << (2 * i) for i in range(4))])
        return group * ((count + 3) // 4)
    return bytes([level & 255, level >> 8]) * count


def white_folder():
    a = "Cameras/A100/"
    pair = [(a + "MOD_0000.TXT", white_txt(4, 2, 12, "A100", 100, 800, 0.01)),
            (a + "MOD_0000.RAW", packed(4, 2, 12, 3000))]
    write("white_folder", "pair_12bit.wf", folder(pair))
    two = pair + [(a + "MOD_0001.TXT", white_txt(4, 2, 10, "A100", 120, 820, 0.02)),
                  (a + "MOD_0001.raw", packed(4, 2, 10, 900)),
                  (a + "MOD_0002.TXT", white_txt(2, 2, 16, "A100", 120, 820, 0.03, dark=True)),
                  (a + "MOD_0002.RAW", packed(2, 2, 16, 70)),
                  ("Cameras/B200/MOD_0000.TXT", white_txt(4, 2, 12, "B200", 100, 800, 0.01)),
                  ("Cameras/B200/MOD_0000.RAW", packed(4, 2, 12, 3000) + b"\x00")]  # one byte too many: skipped
    write("white_folder", "pairs_and_dark.wf", folder(two))
    write("white_folder", "txt_without_raw.wf", folder([("MOD_0007.TXT", white_txt(4, 2, 12, "C3", 1, 2, 0.01))]))
    # A calibration archive: the TXT and RAW members in two volumes.
    txt = white_txt(4, 2, 10, "D400", 200, 600, 0.01)
    raw = packed(4, 2, 10, 800)
    c, m = make_corpus.container, make_corpus.section
    toc0 = json.dumps({"files": [{"name": "C:\\T1CALIB\\MOD_0000.TXT", "dataRef": make_corpus.ref(txt)}],
                       "nextFile": "data.C.1"}).encode()
    toc1 = json.dumps({"files": [{"name": "C:\\T1CALIB\\MOD_0000.RAW", "dataRef": make_corpus.ref(raw)}]}).encode()
    write("white_folder", "archive_two_volumes.wf",
          folder([("data.C.0", c([m(b"M", toc0), m(b"C", txt)])), ("data.C.1", c([m(b"M", toc1), m(b"C", raw)]))]))
    # A cached database beside the pair it indexes (read instead of the pair when it is as new).
    cache = {"lfsp_white_image_database": 1, "entries": [{
        "name": "MOD_0000", "raw": "Cameras/A100/MOD_0000.RAW", "metadata": "Cameras/A100/MOD_0000.TXT",
        "serial": "A100", "zoom_step": 100, "focus_step": 800, "exposure_s": 0.01, "width": 4, "height": 2,
        "bits_per_pixel": 12, "mean_level": 0.7, "dark": False}], "skipped": []}
    write("white_folder", "cached.wf", folder(pair + [("whites.json", json.dumps(cache).encode())]))


def main():
    plain_raw(random.Random(5))
    white_folder()


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Writes the committed seeds of the plain_raw fuzz target (synthetic files only): plain raw images, one option byte
(plain_raw_fuzz.cc) then a PNG, TIFF or JPEG mosaic. Images come from tests/core/fuzz/make_folder_corpus.py's
writers, JPEGs from corpus/jpeg. Deterministic; rerun to regenerate:
python3 tests/decode/fuzz/make_plain_and_white_corpus.py"""
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "core", "fuzz"))
from make_folder_corpus import png, tiff  # noqa: E402


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


def main():
    plain_raw(random.Random(5))


if __name__ == "__main__":
    main()

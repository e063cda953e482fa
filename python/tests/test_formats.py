"""lfsp.read / lfsp.write: every format the command line reads and writes, round trips and real files."""

import os

import numpy
import pytest

import lfsp
from conftest import ANTINOUS, IDEAL_SAMPLE, SHARED_DATA, require, run_cli


@pytest.fixture(scope="module")
def ideal():
    return lfsp.read(IDEAL_SAMPLE)


def test_bundle_round_trip_is_exact(ideal, tmp_path):
    lfsp.write(ideal, tmp_path / "copy.h5")
    again = lfsp.read(tmp_path / "copy.h5")
    numpy.testing.assert_array_equal(again.samples, ideal.samples)
    numpy.testing.assert_array_equal(again.disparity, ideal.disparity)
    numpy.testing.assert_array_equal(again.labels, ideal.labels)
    assert again.transfer == ideal.transfer


@pytest.mark.parametrize(
    "name,options,step",
    [
        ("eslf8.png", {"bit_depth": 8}, 1 / 255),
        ("eslf16.png", {"bit_depth": 16}, 1 / 65535),
        ("views8", {"bit_depth": 8}, 1 / 255),
        ("views16", {"bit_depth": 16}, 1 / 65535),
        ("views_tif", {"bit_depth": 16, "view_format": "tif"}, 1 / 65535),
        ("lftoolbox.mat", {}, 1e-7),
    ],
)
def test_round_trip_within_the_formats_precision(ideal, tmp_path, name, options, step):
    lfsp.write(ideal, tmp_path / name, **options)
    again = lfsp.read(tmp_path / name)
    assert again.shape == ideal.shape
    # Within half a quantisation step of the stored precision (plus float rounding).
    numpy.testing.assert_allclose(again.samples, ideal.samples, rtol=0, atol=step / 2 + 1e-6)


def test_python_and_command_line_read_a_file_alike(ideal, tmp_path):
    # The command line converts the bundle to a views folder; Python reads that folder: the same samples as Python
    # writing it itself.
    run_cli("convert", IDEAL_SAMPLE, tmp_path / "by_cli", "--bit-depth", "16")
    lfsp.write(ideal, tmp_path / "by_python", bit_depth=16)
    by_cli = lfsp.read(tmp_path / "by_cli")
    by_python = lfsp.read(tmp_path / "by_python")
    numpy.testing.assert_array_equal(by_cli.samples, by_python.samples)


def test_reads_the_real_hci_scene():
    lf = lfsp.read(require(ANTINOUS))
    assert lf.shape == (9, 9, 512, 512, 3)
    assert lf.disparity.shape == (512, 512)
    assert lf.metadata["meta"]["disp_min"] < lf.metadata["meta"]["disp_max"]


@pytest.mark.parametrize(
    "folder,shape",
    [("illum_field", (9, 9)), ("f01_lftoolbox/IMG_0001", None), ("f01_checkerboard", (7, 7))],
)
def test_reads_other_tools_real_view_folders(folder, shape):
    lf = lfsp.read(require(os.path.join(SHARED_DATA, "lytro_views", *folder.split("/"))))
    if shape is not None:
        assert lf.shape[:2] == shape
    assert lf.samples.mean() > 0.05  # real pictures, not blank


def test_a_views_pattern_reads_what_detection_would_not(ideal, tmp_path):
    folder = tmp_path / "custom"
    lfsp.write(ideal, folder)
    for name in os.listdir(folder):
        if name.startswith("input_Cam"):
            index = int(name[len("input_Cam") : len("input_Cam") + 3])
            os.rename(folder / name, folder / f"shot_{index // 7}-{index % 7}.png")
    with pytest.raises(lfsp.Error):
        lfsp.read(folder)
    again = lfsp.read(folder, views_pattern="shot_{row}-{col}.png")
    assert again.shape == ideal.shape


def test_disparity_round_trip(ideal, tmp_path):
    lfsp.write_disparity(ideal.disparity, tmp_path / "d.pfm")
    numpy.testing.assert_array_equal(lfsp.read_disparity(tmp_path / "d.pfm"), ideal.disparity)

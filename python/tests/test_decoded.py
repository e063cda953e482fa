"""A decoded lenslet capture through Python: the same light field as `lfsp decode`, and the stages on its well-lit
central views, as the commands choose them."""

import os

import numpy
import pytest

import lfsp
from conftest import MINI_ILLUM, run_cli


@pytest.fixture(scope="module")
def decoded():
    return lfsp.decode(os.path.join(MINI_ILLUM, "capture.LFR"))


def test_decode_gives_the_command_lines_light_field(decoded, tmp_path):
    run_cli("decode", os.path.join(MINI_ILLUM, "capture.LFR"), "--out", tmp_path / "cli.h5")
    by_cli = lfsp.read(tmp_path / "cli.h5")
    numpy.testing.assert_array_equal(decoded.samples, by_cli.samples)
    numpy.testing.assert_array_equal(decoded.weights, by_cli.weights)
    assert decoded.transfer == by_cli.transfer
    assert decoded.metadata["decode"] == by_cli.metadata["decode"]


def test_stages_run_on_the_well_lit_views(decoded):
    assert decoded.shape[:2] == (15, 15)
    disparity, _ = lfsp.depth(decoded)
    labels = lfsp.segment(decoded, disparity, size=12)
    assert labels.shape == (9, 9, 60, 80)  # the Illum's well-lit 9 x 9, as `lfsp segment` chooses them
    scores = lfsp.evaluate_segmentation(labels, light_field=decoded, disparity=disparity, refocus_levels=[0.5],
                                        size=12)
    assert scores["lfsp"]["elr"] > 0.9
    assert len(scores["refocus"]) == 1
    edited = lfsp.recolor(decoded, labels=labels, at=[(40, 30)], hue=150)
    assert edited.shape[:2] == (9, 9)
    assert not numpy.array_equal(edited.samples, decoded.samples[3:12, 3:12])


def test_decode_options_are_the_command_lines(tmp_path):
    capture = os.path.join(MINI_ILLUM, "capture.LFR")
    linear = lfsp.decode(capture, colour="linear", dehex=0.0, no_hot_pixels=True)
    run_cli("decode", capture, "--colour", "linear", "--dehex", "0", "--no-hot-pixels", "--out", tmp_path / "l.h5")
    numpy.testing.assert_array_equal(linear.samples, lfsp.read(tmp_path / "l.h5").samples)
    assert linear.transfer == "linear"
    with pytest.raises(lfsp.Error, match="dehex"):
        lfsp.decode(capture, dehex=0.5)

"""Python and the command line give the same results on the same input: depth, segment, evaluate, recolor."""

import json

import numpy
import pytest

import lfsp
from conftest import IDEAL_SAMPLE, run_cli


@pytest.fixture(scope="module")
def ideal():
    return lfsp.read(IDEAL_SAMPLE)


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory):
    """The command line's depth, segmentation and scores of the bundled ideal sample."""
    folder = tmp_path_factory.mktemp("cli")
    run_cli("depth", IDEAL_SAMPLE, "--out", folder / "d.pfm", "--labels", "48")
    run_cli("segment", IDEAL_SAMPLE, "--disparity", folder / "d.pfm", "--size", "12", "--out", folder / "s.h5")
    scores = run_cli("evaluate", "segmentation", folder / "s.h5", "--gt-labels", IDEAL_SAMPLE).stdout
    return folder, json.loads(scores)


def cli_numbers(cli_scores):
    """The command line's report without where its inputs came from (which Python calls do not have)."""
    return {k: v for k, v in cli_scores.items() if k not in ("input", "gt_labels", "self_similarity_disparity")}


def without_timings(report):
    """The report without its wall times, which differ from run to run."""
    if isinstance(report, dict):
        return {key: without_timings(value) for key, value in report.items() if key != "seconds"}
    if isinstance(report, list):
        return [without_timings(value) for value in report]
    return report


def test_depth_is_identical(ideal, cli_run):
    folder, _ = cli_run
    disparity, confidence = lfsp.depth(ideal, labels=48)
    numpy.testing.assert_array_equal(disparity, lfsp.read_disparity(folder / "d.pfm"))
    numpy.testing.assert_array_equal(confidence, lfsp.read_disparity(folder / "d_confidence.pfm"))


def test_segment_is_identical(ideal, cli_run):
    folder, _ = cli_run
    labels = lfsp.segment(ideal, lfsp.read_disparity(folder / "d.pfm"), size=12)
    numpy.testing.assert_array_equal(labels, lfsp.read(folder / "s.h5").labels)


def test_evaluate_segmentation_gives_the_same_numbers(ideal, cli_run):
    folder, cli_scores = cli_run
    segmentation = lfsp.read(folder / "s.h5")
    scores = lfsp.evaluate_segmentation(
        segmentation.labels,
        light_field=segmentation,
        disparity=segmentation.disparity,
        gt_labels=ideal.labels,
        gt_disparity=ideal.disparity,
    )
    # Every number is the same.
    assert without_timings(scores) == without_timings(cli_numbers(cli_scores))
    assert "refocus" in json.dumps(scores)  # the sweep ran (light field and disparity given)


def test_explicit_lfsp_keywords_are_what_the_sweep_reruns_with(ideal, cli_run):
    folder, cli_scores = cli_run
    labels = lfsp.read(folder / "s.h5").labels
    disparity = lfsp.read_disparity(folder / "d.pfm")
    # A plain light field records no parameters: with size=12 the sweep re-runs as `lfsp segment --size 12` did.
    scores = lfsp.evaluate_segmentation(labels, light_field=ideal, disparity=disparity, gt_labels=ideal.labels,
                                        gt_disparity=ideal.disparity, size=12)
    assert without_timings(scores) == without_timings(cli_numbers(cli_scores))
    default_size = lfsp.evaluate_segmentation(labels, light_field=ideal, disparity=disparity,
                                              gt_labels=ideal.labels, gt_disparity=ideal.disparity)
    # Size 20 re-runs differ: the keyword is used, not ignored.
    assert without_timings(default_size["refocus"]) != without_timings(scores["refocus"])


def test_evaluate_depth_gives_the_same_numbers(ideal, cli_run, tmp_path):
    folder, _ = cli_run
    lfsp.write_disparity(ideal.disparity, tmp_path / "gt.pfm")
    cli = json.loads(run_cli("evaluate", "depth", folder / "d.pfm", "--gt", tmp_path / "gt.pfm").stdout)
    # The command scores the confidence `lfsp depth` wrote beside the map (d_confidence.pfm).
    confidence = lfsp.read_disparity(folder / "d_confidence.pfm")
    ours = lfsp.evaluate_depth(lfsp.read_disparity(folder / "d.pfm"), ideal.disparity, confidence=confidence)
    for key in ("algo", "gt", "confidence"):
        cli.pop(key)
    assert ours == cli
    assert 0.0 <= ours["sparsification"]["oracle_area_mse_x100"] <= ours["sparsification"]["area_mse_x100"]
    assert 0.0 < ours["all"]["mse_x100"] < 5.0  # a real estimate, not an empty score


def test_recolor_gives_the_same_bytes(ideal, cli_run, tmp_path):
    folder, _ = cli_run
    segmentation = lfsp.read(folder / "s.h5")
    run_cli("recolor", folder / "s.h5", "--label-ids", "3,17", "--hue", "120", "--feather", "2",
            "--out", tmp_path / "cli.h5")
    ours = lfsp.recolor(segmentation, label_ids=[3, 17], hue=120.0, feather=2)
    lfsp.write(ours, tmp_path / "python.h5")
    by_cli, by_python = lfsp.read(tmp_path / "cli.h5"), lfsp.read(tmp_path / "python.h5")
    numpy.testing.assert_array_equal(by_python.samples, by_cli.samples)
    changed = numpy.any(by_python.samples != segmentation.samples, axis=-1)
    assert changed.any()  # the edit did something ...
    assert changed[numpy.isin(segmentation.labels, [3, 17])].mean() > 0.5  # ... to the selected superpixels
    numpy.testing.assert_array_equal(segmentation.samples, lfsp.read(folder / "s.h5").samples)  # input untouched


def test_recolor_by_points_and_mask_select_like_the_command_line(cli_run):
    folder, _ = cli_run
    segmentation = lfsp.read(folder / "s.h5")
    centre = segmentation.labels[3, 3]
    by_point = lfsp.recolor(segmentation, at=[(40, 60)], value=0.5)
    by_text = lfsp.recolor(segmentation, at=["40,60"], value=0.5)
    by_id = lfsp.recolor(segmentation, label_ids=[int(centre[60, 40])], value=0.5)
    by_mask = lfsp.recolor(segmentation, mask=centre == centre[60, 40], value=0.5)
    for other in (by_text, by_id, by_mask):
        numpy.testing.assert_array_equal(other.samples, by_point.samples)


def test_refocus_shear_and_all_in_focus_match_the_command_line(ideal, tmp_path):
    run_cli("refocus", IDEAL_SAMPLE, "--disparities", "0.5", "--shear", "0.5", "--out-lf", tmp_path / "sheared.h5",
            "--out", tmp_path / "refocus")
    sheared = lfsp.shear(ideal, 0.5)
    numpy.testing.assert_array_equal(sheared.samples, lfsp.read(tmp_path / "sheared.h5").samples)
    image = lfsp.refocus(ideal, 0.5)
    assert image.shape == (128, 128, 3) and image.dtype == numpy.float32
    stack = lfsp.refocus(ideal, [0.5, -0.5])
    numpy.testing.assert_array_equal(stack[0], image)
    assert not numpy.array_equal(stack[1], image)
    sharp = lfsp.all_in_focus(ideal)
    assert sharp.shape == (128, 128, 3)

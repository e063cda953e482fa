"""A light field held in another tool's layout runs through depth and segment once it is a numpy array."""

import h5py
import numpy

import lfsp
from conftest import IDEAL_SAMPLE

MATLAB_V73_HEADER = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed Dec  2 12:00:00 2026 HDF5 schema 1.00 ."


def write_v73_mat(path, lf_uvhwc: numpy.ndarray) -> None:
    """A MATLAB v7.3 .mat with variable LF of MATLAB size [U, V, H, W, 3] (BasicLFSR and others): HDF5 behind a
    512-byte header, the dataset's shape MATLAB's reversed because MATLAB is column-major."""
    with h5py.File(path, "w", userblock_size=512) as f:
        f.create_dataset("LF", data=lf_uvhwc.transpose(4, 3, 2, 1, 0))
        f["LF"].attrs["MATLAB_class"] = numpy.bytes_("uint8")
    with open(path, "r+b") as f:
        f.write(MATLAB_V73_HEADER.ljust(116, b" ") + bytes(8) + b"\x00\x02IM")


def test_a_v73_mat_read_with_h5py_runs_through_depth_and_segment(tmp_path):
    ideal = lfsp.read(IDEAL_SAMPLE)
    as_uint8 = numpy.round(ideal.samples * 255).astype(numpy.uint8)
    write_v73_mat(tmp_path / "scene.mat", as_uint8)

    # What a researcher does with such a file: h5py, then the transpose back to MATLAB's index order.
    with h5py.File(tmp_path / "scene.mat", "r") as f:
        stored = f["LF"][()]
    assert stored.shape == (3, 128, 128, 7, 7)
    lf = lfsp.LightField(stored.transpose(4, 3, 2, 1, 0), metadata={"meta": {"disp_min": -1.3, "disp_max": 1.1}})
    numpy.testing.assert_array_equal(lf.samples, as_uint8 / numpy.float32(255))

    disparity, confidence = lfsp.depth(lf)
    assert disparity.shape == confidence.shape == (128, 128)
    scores = lfsp.evaluate_depth(disparity, ideal.disparity)
    # The scene's depth, found from the other tool's array (the command line on the float bundle: MSE x100 2.3).
    assert scores["all"]["mse_x100"] < 5.0

    labels = lfsp.segment(lf, disparity, size=12)
    assert labels.shape == (7, 7, 128, 128)
    assert labels.min() >= 0 and 50 < labels.max() < 400

    # lfsp reads the same file itself, to the same samples.
    numpy.testing.assert_array_equal(lfsp.read(tmp_path / "scene.mat").samples, lf.samples)


def test_transposed_views_of_one_array_give_the_same_depth_as_a_contiguous_copy():
    ideal = lfsp.read(IDEAL_SAMPLE)
    flipped = numpy.ascontiguousarray(ideal.samples.transpose(1, 0, 2, 3, 4)).transpose(1, 0, 2, 3, 4)
    assert not flipped.flags.c_contiguous
    meta = ideal.metadata
    a, _ = lfsp.depth(lfsp.LightField(flipped, metadata=meta))
    b, _ = lfsp.depth(lfsp.LightField(numpy.ascontiguousarray(flipped), metadata=meta))
    numpy.testing.assert_array_equal(a, b)

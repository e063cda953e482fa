"""lfsp.LightField: numpy in and out, zero-copy views, what is copied and what is refused."""

import numpy
import pytest

import lfsp
from conftest import IDEAL_SAMPLE


def random_samples(shape=(3, 4, 5, 6, 3), dtype=numpy.float32, seed=1):
    rng = numpy.random.default_rng(seed)
    if dtype == numpy.uint8:
        return rng.integers(0, 256, size=shape, dtype=numpy.uint8)
    if dtype == numpy.uint16:
        return rng.integers(0, 65536, size=shape, dtype=numpy.uint16)
    return rng.random(shape).astype(dtype)


def test_samples_are_a_view_of_the_light_fields_own_memory():
    lf = lfsp.read(IDEAL_SAMPLE)
    samples = lf.samples
    assert samples.dtype == numpy.float32
    assert samples.shape == lf.shape == (7, 7, 128, 128, 3)
    assert samples.base is lf  # the array keeps the light field alive and owns nothing itself
    assert not samples.flags.owndata
    pointer = samples.__array_interface__["data"][0]
    assert lf.samples.__array_interface__["data"][0] == pointer  # every access, the same memory
    assert numpy.asarray(lf).__array_interface__["data"][0] == pointer
    assert numpy.shares_memory(numpy.asarray(lf), samples)


def test_writing_through_the_array_changes_the_light_field(tmp_path):
    lf = lfsp.read(IDEAL_SAMPLE)
    lf.samples[3, 3, 10, 20] = (0.25, 0.5, 0.75)
    lfsp.write(lf, tmp_path / "changed.h5")
    again = lfsp.read(tmp_path / "changed.h5")
    assert tuple(again.samples[3, 3, 10, 20]) == (0.25, 0.5, 0.75)


def test_arrays_outlive_the_python_name_of_their_light_field():
    samples = lfsp.read(IDEAL_SAMPLE).samples
    disparity = lfsp.read(IDEAL_SAMPLE).disparity
    expected = lfsp.read(IDEAL_SAMPLE)
    numpy.testing.assert_array_equal(samples, expected.samples)
    numpy.testing.assert_array_equal(disparity, expected.disparity)


def test_weights_disparity_and_labels_are_views_too():
    lf = lfsp.LightField(random_samples(), weights=numpy.ones((3, 4, 5, 6)), disparity=numpy.zeros((5, 6)),
                         labels=numpy.zeros((3, 4, 5, 6), dtype=numpy.int64))
    for array in (lf.weights, lf.disparity, lf.labels):
        assert array.base is lf
    lf.disparity[2, 3] = 1.5
    assert lf.disparity[2, 3] == 1.5
    assert lf.labels.dtype == numpy.int32


@pytest.mark.parametrize("dtype,scale", [(numpy.float32, 1.0), (numpy.float64, 1.0), (numpy.uint8, 255.0),
                                         (numpy.uint16, 65535.0)])
def test_construction_converts_samples_to_float32(dtype, scale):
    samples = random_samples(dtype=dtype)
    lf = lfsp.LightField(samples)
    numpy.testing.assert_allclose(lf.samples, samples.astype(numpy.float64) / scale, rtol=0, atol=1e-7)
    assert lf.transfer == "srgb"


def test_construction_copies_from_any_memory_layout():
    # [U, V, H, W, 3] as other tools keep it, transposed to lfsp's (nv, nu, H, W, 3) without a copy first.
    other_tool = random_samples(shape=(4, 3, 5, 6, 3))
    transposed = other_tool.transpose(1, 0, 2, 3, 4)
    assert not transposed.flags.c_contiguous
    lf = lfsp.LightField(transposed)
    numpy.testing.assert_array_equal(lf.samples, transposed)
    assert not numpy.shares_memory(lf.samples, other_tool)  # a copy: changing the source leaves it alone
    other_tool[0, 0, 0, 0, 0] = 7.0
    assert lf.samples[0, 0, 0, 0, 0] != 7.0


def test_metadata_and_transfer_round_trip():
    lf = lfsp.LightField(random_samples(), transfer="linear", metadata={"meta": {"disp_min": -1.5, "disp_max": 2}})
    assert lf.transfer == "linear"
    assert lf.metadata == {"meta": {"disp_min": -1.5, "disp_max": 2}}
    lf.metadata = {"note": ["a", 1, None]}
    assert lf.metadata == {"note": ["a", 1, None]}
    assert "linear" in repr(lf)


@pytest.mark.parametrize(
    "samples,message",
    [
        (numpy.zeros((3, 4, 5, 6)), "samples: expected a 5-D array (nv, nu, H, W, channels), got shape (3, 4, 5, 6)"),
        (numpy.zeros((3, 4, 5, 6, 2)), "samples: expected 3 colour channels (RGB)"),
        (numpy.zeros((3, 4, 5, 6, 3), dtype=numpy.int32), "samples: expected float, uint8 or uint16 samples"),
        (numpy.zeros((0, 4, 5, 6, 3)), "samples: the light field is empty"),
    ],
)
def test_bad_arrays_raise_lfsp_error(samples, message):
    with pytest.raises(lfsp.Error) as raised:
        lfsp.LightField(samples)
    assert message in str(raised.value)
    assert isinstance(raised.value, ValueError)


def test_non_finite_samples_are_refused_naming_the_ray():
    samples = random_samples()
    samples[1, 2, 3, 4, 0] = numpy.nan
    with pytest.raises(lfsp.Error, match=r"non-finite sample .* view \(u 2, v 1\) at x 4, y 3"):
        lfsp.LightField(samples)


def test_mismatched_parts_are_refused():
    with pytest.raises(lfsp.Error, match="weights: shape"):
        lfsp.LightField(random_samples(), weights=numpy.ones((3, 4, 5, 7)))
    with pytest.raises(lfsp.Error, match="disparity"):
        lfsp.LightField(random_samples(), disparity=numpy.zeros((6, 5)))
    with pytest.raises(lfsp.Error, match="labels"):
        lfsp.LightField(random_samples(), labels=numpy.zeros((3, 4, 5, 6), dtype=numpy.float32))

# Type hints of the lfsp package (the extension's functions take the command line's options as keywords).
import os
from typing import Any, Callable, NamedTuple, Optional, Sequence, Union, overload

import numpy
import numpy.typing as npt

PathLike = Union[str, os.PathLike[str]]
FloatArray = npt.NDArray[numpy.float32]
LabelArray = npt.NDArray[numpy.int32]

__version__: str

class Error(ValueError): ...

class LightField:
    def __init__(
        self,
        samples: npt.ArrayLike,
        weights: Optional[npt.ArrayLike] = ...,
        transfer: str = ...,
        metadata: Optional[dict] = ...,
        disparity: Optional[npt.ArrayLike] = ...,
        labels: Optional[npt.ArrayLike] = ...,
    ) -> None: ...
    @property
    def samples(self) -> FloatArray: ...
    @property
    def weights(self) -> Optional[FloatArray]: ...
    disparity: Optional[FloatArray]
    labels: Optional[LabelArray]
    transfer: str
    metadata: dict
    @property
    def shape(self) -> tuple[int, int, int, int, int]: ...
    def __array__(self, dtype: Any = ...) -> numpy.ndarray: ...

class Simulation(NamedTuple):
    light_field: Optional[LightField]
    disparity: Optional[FloatArray]
    labels: Optional[LabelArray]
    summary: dict
    out: Optional[str]

def read(path: PathLike, *, views_pattern: str = ..., eslf_nu: int = ..., eslf_nv: int = ...) -> LightField: ...
def write(light_field: LightField, path: PathLike, *, bit_depth: int = ..., view_format: str = ...) -> None: ...
def read_disparity(path: PathLike) -> FloatArray: ...
def write_disparity(disparity: npt.ArrayLike, path: PathLike) -> None: ...
def decode(capture: PathLike, **options: Any) -> LightField: ...
def grid(input: PathLike, **options: Any) -> dict: ...
def depth(light_field: LightField, **options: Any) -> tuple[FloatArray, FloatArray]: ...
def segment(light_field: LightField, disparity: Optional[npt.ArrayLike] = ..., **params: Any) -> LabelArray: ...
def evaluate_segmentation(
    labels: npt.ArrayLike,
    *,
    light_field: Optional[LightField] = ...,
    disparity: Optional[npt.ArrayLike] = ...,
    gt_disparity: Optional[npt.ArrayLike] = ...,
    gt_labels: Optional[npt.ArrayLike] = ...,
    **options: Any,
) -> dict: ...
def evaluate_depth(
    disparity: npt.ArrayLike,
    gt_disparity: npt.ArrayLike,
    *,
    confidence: Optional[npt.ArrayLike] = ...,
    masks: str = ...,
    **options: Any,
) -> dict: ...
def recolor(
    light_field: LightField,
    *,
    labels: Optional[npt.ArrayLike] = ...,
    label_ids: Optional[Sequence[int]] = ...,
    at: Optional[Sequence[Union[str, tuple[int, int]]]] = ...,
    mask: Optional[npt.ArrayLike] = ...,
    **options: Any,
) -> LightField: ...
@overload
def refocus(light_field: LightField, disparity: float, **options: Any) -> FloatArray: ...
@overload
def refocus(light_field: LightField, disparity: Sequence[float], **options: Any) -> list[FloatArray]: ...
def all_in_focus(
    light_field: LightField,
    disparity: Optional[npt.ArrayLike] = ...,
    *,
    no_occlusion: bool = ...,
    no_weights: bool = ...,
    views: int = ...,
) -> FloatArray: ...
def shear(light_field: LightField, disparity: float, *, interpolation: str = ...) -> LightField: ...
def simulate(out: Optional[PathLike] = ..., **options: Any) -> Simulation: ...
def set_progress(callback: Optional[Callable[[str, int, int], Any]]) -> None: ...
def set_log_level(level: str) -> None: ...

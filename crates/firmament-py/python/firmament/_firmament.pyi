"""Type stubs of firmament's extension module (the package's engine; use ``firmament``'s API)."""

import os
from typing import Any, Mapping, Optional, Union

import numpy as np

class FirmamentError(Exception):
    """A scene, an argument, the GPU or an output failed; the message names the key, flag or rule."""

def render(
    scene: Union[str, os.PathLike[str], Mapping[str, Any], None] = None,
    *,
    preset: Optional[str] = None,
    overrides: list[str] = ...,
    width: Optional[int] = None,
    height: Optional[int] = None,
    hdr: bool = False,
    backend_name: str = "auto",
) -> np.ndarray: ...
def envmap(
    scene: Union[str, os.PathLike[str], Mapping[str, Any], None] = None,
    *,
    preset: Optional[str] = None,
    overrides: list[str] = ...,
    width: int = 1024,
    sun: bool = True,
    backend_name: str = "auto",
) -> np.ndarray: ...
def report(args: list[str]) -> str: ...
def scene_toml(scene: Union[str, Mapping[str, Any]]) -> str: ...

"""firmament for Python: physically based skies as numpy arrays.

Renders firmament's scenes — atmospheres around ellipsoid planets lit by several suns, the sky at
a real date and place, the night sky, classic lit objects — on the GPU (Mesa's llvmpipe where
there is none), and reports the sun's position and the f64 reference's sky values.

Scenes are given as TOML text (``str``), a file (``pathlib.Path``), a ``dict`` with the same keys
as a scene file, or nothing (``preset=...`` or the default scene), with ``overrides`` in the
command line's ``--set`` form (``"camera.fov_y=75"``). They are checked by the same rules as scene
files: every failure raises :class:`FirmamentError` with the command line's message, naming the
key, the value and the rule.

    >>> import firmament
    >>> sky = firmament.render(preset="earth-sunset", width=64, height=36, hdr=True)
    >>> sky.shape, sky.dtype
    ((36, 64, 4), dtype('float32'))

Units: ``render(hdr=True)`` gives linear RGB radiance (scene-referred, what ``firmament render -o
sky.exr`` writes); ``hdr=False`` the display image (exposure, tone curve, sRGB; what the PNG holds).
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Mapping, Sequence
from typing import Any, Optional, Union

import numpy as np

from . import _firmament
from ._firmament import FirmamentError

__all__ = ["FirmamentError", "envmap", "render", "sky_sample", "sun_position"]

SceneLike = Union[str, "os.PathLike[str]", Mapping[str, Any], None]
"""A scene: TOML text, a scene file's path, a dict of a scene file's keys, or None."""


def render(
    scene: SceneLike = None,
    *,
    preset: Optional[str] = None,
    overrides: Sequence[str] = (),
    width: Optional[int] = None,
    height: Optional[int] = None,
    hdr: bool = False,
    backend: str = "auto",
) -> np.ndarray:
    """Render a scene on the GPU and return its image, ``(height, width, 4)``, top row first.

    Args:
        scene: TOML text, a scene file's path (``pathlib.Path``; its relative asset paths resolve
            against its folder), a dict of a scene file's keys, or None for ``preset`` (default:
            the built-in default scene). Text and dicts resolve asset paths against the working
            directory.
        preset: the built-in preset to start from (see ``firmament presets``); with a scene it
            replaces the scene's own ``preset`` key.
        overrides: ``"key.path=value"`` strings, applied in order, as ``--set`` does.
        width, height: the image's size in pixels (``render.width``, ``render.height``).
        hdr: True for ``float32`` linear RGB radiance (W·m⁻²·sr⁻¹ per the scene's units, alpha
            1); False for ``uint8`` display sRGB after exposure and the tone curve.
        backend: ``"auto"``, ``"vulkan"``, ``"gl"``, ``"metal"`` or ``"dx12"``.

    Raises:
        FirmamentError: a bad scene or argument, or a GPU failure.
    """
    return _firmament.render(
        _scene_arg(scene),
        preset=preset,
        overrides=list(overrides),
        width=width,
        height=height,
        hdr=hdr,
        backend_name=backend,
    )


def envmap(
    scene: SceneLike = None,
    *,
    preset: Optional[str] = None,
    overrides: Sequence[str] = (),
    width: int = 1024,
    sun: bool = True,
    backend: str = "auto",
) -> np.ndarray:
    """Render the sphere of directions around the scene's camera as an equirectangular map.

    Returns ``float32`` linear radiance, ``(width // 2, width, 4)``: zenith on the top row,
    north a quarter of the way across, east in the middle, west at the seam (docs/ENVMAP.md has
    the orientation of Blender, Unreal, Unity and three.js). ``firmament envmap``'s map.

    Args:
        scene, preset, overrides: as :func:`render`.
        width: even, 4 to 16384 pixels.
        sun: False leaves the suns' discs out (light the scene with a directional light instead;
            ``firmament envmap --no-sun`` writes each sun's direction and irradiance).
        backend: as :func:`render`.

    Raises:
        FirmamentError: a bad scene or argument, or a GPU failure.
    """
    return _firmament.envmap(
        _scene_arg(scene),
        preset=preset,
        overrides=list(overrides),
        width=width,
        sun=sun,
        backend_name=backend,
    )


def sky_sample(
    scene: SceneLike = None,
    *,
    altitude_m: float,
    sun_zenith_deg: float,
    view_zenith_deg: float,
    view_azimuth_deg: float = 0.0,
    preset: Optional[str] = None,
    overrides: Sequence[str] = (),
    reference: bool = True,
    gpu: bool = True,
    paths: int = 4096,
    line_samples: int = 0,
    second_order: bool = False,
    backend: str = "auto",
) -> dict:
    """Sample one view ray of an atmosphere: ``firmament sky-sample --json`` as a dict.

    The scene's planet, medium and first sun (whose direction is set by ``sun_zenith_deg``; its
    azimuth is 0, north) are sampled from ``altitude_m`` metres above the ground, looking
    ``view_zenith_deg`` from the zenith and ``view_azimuth_deg`` from the sun's azimuth.

    Returns:
        A dict with ``wavelengths_nm``, ``units`` and, for each method asked for, ``reference``
        (the f64 reference integrator) and ``gpu`` (the LUT path): ``radiance`` (per
        wavelength), ``radiance_by_order``, ``radiance_via_ground``, ``radiance_standard_error``,
        ``luminance`` (cd/m²), ``linear_srgb``, ``transmittance`` (to space),
        ``sky_irradiance`` and ``sun_irradiance`` (on the ground, W·m⁻²·nm⁻¹).

    Raises:
        FirmamentError: a bad scene or argument, or a GPU failure.
    """
    if not (reference or gpu):
        raise FirmamentError("sky_sample: ask for the reference, the GPU or both")
    args = [
        "sky-sample",
        "--json",
        f"--altitude={altitude_m!r}",
        f"--sun-zenith={sun_zenith_deg!r}",
        f"--view-zenith={view_zenith_deg!r}",
        f"--view-azimuth={view_azimuth_deg!r}",
        f"--paths={paths}",
        f"--line-samples={line_samples}",
        f"--backend={backend}",
    ]
    if not gpu:
        args.append("--reference")
    if not reference:
        args.append("--gpu")
    if second_order:
        args.append("--second-order")
    return _report(args, scene, preset, overrides)


def sun_position(
    time: str,
    latitude_deg: float,
    longitude_deg: float,
    *,
    elevation_m: float = 0.0,
    pressure_mbar: float = 1010.0,
    temperature_c: float = 10.0,
    delta_t_s: Optional[float] = None,
) -> dict:
    """The sun's position by NREL's SPA, and that day's sunrise, solar noon and sunset.

    ``firmament sun --json`` as a dict: ``zenith_deg``, ``azimuth_deg`` (eastward from north),
    ``elevation_deg`` (refracted; ``..._no_refraction_deg`` without), ``declination_deg``,
    ``right_ascension_deg``, ``hour_angle_deg``, ``equation_of_time_min``, ``sunrise``,
    ``solar_noon``, ``sunset`` (``HH:MM:SS`` on the clock of ``time``; None in polar day or
    night) and their hours (``sunrise_h``, ...).

    Args:
        time: ISO 8601 (``"2003-10-17T12:30:30-07:00"``; without an offset, UTC).
        latitude_deg: degrees north, [-90, 90]. longitude_deg: degrees east, [-180, 180].
        elevation_m, pressure_mbar, temperature_c: the observer and the refraction's air.
        delta_t_s: TT − UT in seconds (default: Espenak & Meeus's estimate for the date).

    Raises:
        FirmamentError: a value outside SPA's rules, named with its rule.
    """
    args = [
        "sun",
        "--json",
        f"--time={time}",
        f"--lat={latitude_deg!r}",
        f"--lon={longitude_deg!r}",
        f"--elevation={elevation_m!r}",
        f"--pressure={pressure_mbar!r}",
        f"--temperature={temperature_c!r}",
    ]
    if delta_t_s is not None:
        args.append(f"--delta-t={delta_t_s!r}")
    return json.loads(_firmament.report(args))


def _scene_arg(scene: SceneLike) -> Any:
    """``scene`` as the extension's render functions take it: a path as it is, else :func:`_plain`."""
    return scene if isinstance(scene, os.PathLike) else _plain(scene)


def _plain(scene: SceneLike) -> Any:
    """``scene`` as the extension takes it: None, TOML text or a dict."""
    if scene is None or isinstance(scene, str):
        return scene
    if isinstance(scene, Mapping):
        return dict(scene)
    raise FirmamentError(
        f"scene: a {type(scene).__name__}; expected TOML text (str), a dict, a path (pathlib.Path) or None"
    )


def _report(args: list, scene: SceneLike, preset: Optional[str], overrides: Sequence[str]) -> dict:
    """Run a report on ``scene``: a file as it is, text or a dict through a temporary file."""
    if preset is not None:
        args.append(f"--preset={preset}")
    args.extend(f"--set={item}" for item in overrides)
    if scene is None:
        return json.loads(_firmament.report(args))
    if isinstance(scene, os.PathLike):
        return json.loads(_firmament.report(args + [os.fspath(scene)]))
    text = _firmament.scene_toml(_plain(scene))
    with tempfile.TemporaryDirectory(prefix="firmament-") as folder:
        path = os.path.join(folder, "scene.toml")
        with open(path, "w", encoding="utf-8") as file:
            file.write(text)
        return json.loads(_firmament.report(args + [path]))

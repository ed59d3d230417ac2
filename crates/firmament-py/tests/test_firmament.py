"""The Python package against the command line and independent values (tiny images)."""

import pathlib
import subprocess

import numpy as np
import pytest

import firmament


def test_render_gives_display_and_linear_images():
    ldr = firmament.render(preset="earth-sunset", width=32, height=18)
    assert ldr.shape == (18, 32, 4) and ldr.dtype == np.uint8
    hdr = firmament.render(preset="earth-sunset", width=32, height=18, hdr=True)
    assert hdr.shape == (18, 32, 4) and hdr.dtype == np.float32
    assert np.isfinite(hdr).all() and (hdr[..., :3] >= 0).all() and hdr[..., :3].max() > 0
    # Sunset light is redder than noon's (red over blue, the whole image).
    noon = firmament.render(preset="earth-noon", width=32, height=18, hdr=True)
    ratio = lambda image: image[..., 0].mean() / image[..., 2].mean()  # noqa: E731
    assert ratio(hdr) > ratio(noon)


def test_a_scene_is_the_same_as_text_dict_and_file(tmp_path):
    text = 'preset = "earth-noon"\n[camera]\nfov_y = 50.0\n[render]\nwidth = 24\nheight = 16\n'
    as_dict = {"preset": "earth-noon", "camera": {"fov_y": 50.0}, "render": {"width": 24, "height": 16}}
    path = tmp_path / "scene.toml"
    path.write_text(text)
    images = [firmament.render(s, hdr=True) for s in (text, as_dict, path)]
    for image in images[1:]:
        np.testing.assert_array_equal(image, images[0])
    overridden = firmament.render(text, overrides=["camera.fov_y=50"], hdr=True)
    np.testing.assert_array_equal(overridden, images[0])


def test_the_png_of_the_command_line_matches_the_display_image(tmp_path):
    firmament_bin = pathlib.Path(__file__).resolve().parents[3] / "target" / "debug" / "firmament"
    if not firmament_bin.exists():
        pytest.fail(f"{firmament_bin} is missing: run `cargo build -p firmament` first")
    out = tmp_path / "x.png"
    args = [str(firmament_bin), "-q", "render", "--preset", "dawn", "--width", "20", "--height", "12", "-o", str(out)]
    subprocess.run(args, check=True)
    import zlib

    # The PNG's pixels, decoded here without a library: 8-bit RGB, filter bytes per row.
    data = out.read_bytes()
    chunks, i = [], 8
    while i < len(data):
        length = int.from_bytes(data[i : i + 4], "big")
        kind = data[i + 4 : i + 8]
        if kind == b"IDAT":
            chunks.append(data[i + 8 : i + 8 + length])
        i += 12 + length
    raw = zlib.decompress(b"".join(chunks))
    width, height, stride = 20, 12, 20 * 3
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - 3] if x >= 3 else 0
            up, up_left = previous[x], previous[x - 3] if x >= 3 else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                pred = left if pa <= pb and pa <= pc else (up if pb <= pc else up_left)
                line[x] = (line[x] + pred) & 255
        rows.append(bytes(line))
        previous = line
    png = np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 3)
    ldr = firmament.render(preset="dawn", width=width, height=height)
    np.testing.assert_array_equal(ldr[..., :3], png)


def test_bad_scenes_raise_with_the_command_lines_message():
    with pytest.raises(firmament.FirmamentError, match=r"camera\.fov_y = 0: "):
        firmament.render(preset="earth-noon", overrides=["camera.fov_y=0"])
    with pytest.raises(firmament.FirmamentError, match=r"unknown preset `nope`"):
        firmament.render(preset="nope")
    with pytest.raises(firmament.FirmamentError, match=r"camera\.fov_yy: unknown key"):
        firmament.render({"camera": {"fov_yy": 3.0}})
    with pytest.raises(firmament.FirmamentError, match=r"render\.width: a set has no TOML form"):
        firmament.render({"render": {"width": {1}}})
    with pytest.raises(firmament.FirmamentError, match=r"scene: a int"):
        firmament.render(3)
    with pytest.raises(firmament.FirmamentError, match=r"--lat"):
        firmament.sun_position("2003-10-17T12:30:30-07:00", 91.0, 0.0)


def test_the_sun_is_where_nrels_spa_puts_it():
    # NREL SPA's own example (Reda & Andreas 2008, table A4.1): zenith 50.11162°, azimuth 194.34024°.
    sun = firmament.sun_position(
        "2003-10-17T12:30:30-07:00",
        39.742476,
        -105.1786,
        elevation_m=1830.14,
        pressure_mbar=820.0,
        temperature_c=11.0,
        delta_t_s=67.0,
    )
    assert abs(sun["zenith_deg"] - 50.11162) < 1e-4
    assert abs(sun["azimuth_deg"] - 194.34024) < 1e-4
    assert sun["sunrise"] == "06:12:43" and sun["sunset"] == "17:20:19"


def test_sky_sample_reports_the_reference_and_the_gpu():
    out = firmament.sky_sample(
        preset="earth-noon", altitude_m=0.0, sun_zenith_deg=30.0, view_zenith_deg=60.0, view_azimuth_deg=90.0, paths=256
    )
    assert len(out["wavelengths_nm"]) == 3
    reference, gpu = out["reference"], out["gpu"]
    for method in (reference, gpu):
        assert all(v > 0 for v in method["radiance"])
        assert all(0 < t < 1 for t in method["transmittance"])
    # The GPU agrees with the reference on the sun's light on the ground (a closed form's worth:
    # transmittance times the cosine), and on the sky within the reference's noise and a few %.
    for r, g in zip(reference["sun_irradiance"], gpu["sun_irradiance"]):
        assert abs(g / r - 1) < 0.01
    for r, g in zip(reference["radiance"], gpu["radiance"]):
        assert abs(g / r - 1) < 0.1
    only_reference = firmament.sky_sample(
        {"preset": "earth-noon"}, altitude_m=0.0, sun_zenith_deg=30.0, view_zenith_deg=60.0, gpu=False, paths=64
    )
    assert only_reference["gpu"] is None and only_reference["reference"] is not None


def test_an_envmap_is_the_sphere_with_the_sun_apart():
    with_sun = firmament.envmap(preset="earth-noon", width=64)
    without = firmament.envmap(preset="earth-noon", width=64, sun=False)
    assert with_sun.shape == (32, 64, 4) and with_sun.dtype == np.float32
    assert np.isfinite(without).all() and (without[:16, :, :3] > 0).all()
    # The disc adds energy in a few pixels only (its irradiance is checked by the Rust tests).
    added = (with_sun - without)[..., :3].sum(axis=2)
    assert (added >= 0).all() and 0 < (added > 0).sum() <= 16

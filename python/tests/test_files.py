"""Scenes by name or path and images to files: render() and compare() take a built-in scene's name
or a glTF file's path as well as a loaded Scene; write_exr() and write_png() save what render()
returns as `tripath render --out/--png` does. Run by CTest (Python.Module) with
PYTHONPATH=build/python and TRIPATH_BINARY set to the command line."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import tripath

TRIPATH = os.environ.get("TRIPATH_BINARY", "")
SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"
SMALL = dict(spp=2, width=12, height=8)


def test_render_takes_a_builtin_name_or_a_gltf_path(cornell):
    loaded = tripath.render(cornell, "pt", **SMALL)["image"]
    assert np.array_equal(tripath.render("cornell", "pt", **SMALL)["image"], loaded)
    gltf = SCENES / "door-ajar.gltf"
    from_file = tripath.render(tripath.load(str(gltf)), "pt", **SMALL)["image"]
    for path in (gltf, str(gltf)):  # os.PathLike or str
        assert np.array_equal(tripath.render(path, "pt", **SMALL)["image"], from_file)
    # The comparison can fail: another scene gives another image.
    assert not np.array_equal(from_file, loaded)


def test_compare_takes_a_builtin_name():
    r = tripath.compare("cornell", 0.05, integrators=["pt"], reference_seconds=0.1, width=12, height=8)
    assert r["images"]["pt"].shape == (8, 12, 3)


def test_a_scene_of_another_type_is_a_one_line_type_error():
    with pytest.raises(TypeError) as e:
        tripath.render(42, "pt")
    assert str(e.value) == ("scene must be a tripath.Scene (from load()), a built-in scene's name or a glTF file's "
                            "path, not int")
    with pytest.raises(ValueError, match="^unknown scene 'no-such-scene'"):
        tripath.render("no-such-scene", "pt")


def test_write_exr_round_trips_the_image_and_its_metadata(cornell, tmp_path):
    r = tripath.render(cornell, "bdpt", **SMALL)
    path = tmp_path / "out.exr"
    tripath.write_exr(path, r["image"], r["metadata"])
    image, metadata = tripath.read_exr(path)
    assert np.array_equal(image, r["image"])
    assert metadata == r["metadata"] and metadata["tripath:integrator"] == "bdpt"
    tripath.write_exr(str(path), r["image"] * 2)  # no metadata; str path; replaces the file
    assert np.array_equal(tripath.read_exr(str(path))[0], r["image"] * 2)


def test_write_exr_refuses_bad_input(tmp_path):
    with pytest.raises(ValueError, match="shape"):
        tripath.write_exr(tmp_path / "x.exr", np.zeros((4, 4)))
    with pytest.raises(TypeError, match="^metadata keys must be str, not int$"):
        tripath.write_exr(tmp_path / "x.exr", np.zeros((4, 4, 3)), {1: "one"})
    with pytest.raises(ValueError, match="missing"):
        tripath.write_exr(tmp_path / "missing" / "x.exr", np.zeros((4, 4, 3)))


def test_write_png_exposes_from_the_image_unless_given_stops(tmp_path):
    # A uniform grey of luminance 4: its 98th percentile is 4, so the automatic exposure is -2
    # stops exactly.
    grey = np.full((4, 6, 3), 4.0, dtype=np.float32)
    assert tripath.write_png(tmp_path / "auto.png", grey) == -2.0
    assert tripath.write_png(tmp_path / "given.png", grey, exposure=-3) == -3.0
    assert tripath.write_png(tmp_path / "black.png", np.zeros((4, 6, 3))) == 0.0  # black stays at 0 stops
    with pytest.raises(ValueError, match="finite"):
        tripath.write_png(tmp_path / "nan.png", grey, exposure=float("nan"))


def test_write_png_is_the_command_lines_preview(tmp_path):
    exr, png = tmp_path / "cli.exr", tmp_path / "cli.png"
    subprocess.run([TRIPATH, "render", "--scene", "cornell", "--spp", "2", "--width", "24", "--height", "16",
                    "--out", str(exr), "--png", str(png)], check=True, capture_output=True)
    image, _ = tripath.read_exr(exr)
    stops = tripath.write_png(tmp_path / "python.png", image)
    assert stops != 0  # else the two exposures could not be told apart
    assert (tmp_path / "python.png").read_bytes() == png.read_bytes()
    tripath.write_png(tmp_path / "zero.png", image, exposure=0)
    assert (tmp_path / "zero.png").read_bytes() != png.read_bytes()

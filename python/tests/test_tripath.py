"""The Python module against the library's promises: every integrator renders, the white furnace
reads its analytic radiance, bad input is a ValueError with the command line's message, Python and
`tripath render` give the same bits, the image is the film's memory without a copy, Ctrl-C returns
the partial image. Run by CTest (Python.Module) with PYTHONPATH=build/python and TRIPATH_BINARY
set to the command line."""
import base64
import gc
import json
import math
import os
import pathlib
import signal
import struct
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import tripath

TRIPATH = os.environ.get("TRIPATH_BINARY", "")
INTEGRATORS = ["pt", "lt", "bdpt", "vcm", "bpm", "ppm", "mlt", "auto"]


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_every_integrator_renders_a_builtin(cornell, integrator):
    r = tripath.render(cornell, integrator, spp=2, width=20, height=12)
    image = r["image"]
    assert image.shape == (12, 20, 3) and image.dtype == np.float32
    assert np.isfinite(image).all() and image.mean() > 0.01
    assert r["spp"] == 2 and r["dropped_samples"] == 0 and not r["interrupted"]
    assert r["metadata"]["tripath:integrator"] == integrator
    # Every sample of every method casts at least one closest-hit ray (its camera ray or its light
    # path's first): catches counters not taken from this render.
    assert r["counters"]["closest_hit_rays"] >= 2 * 20 * 12


def test_white_furnace_reads_its_analytic_radiance():
    # Albedo 0.5, emission 1 inside a closed sphere: the radiance is 1 / (1 - 0.5) = 2 everywhere.
    # Eight independent renders; their means scatter with the standard error, so 4 of it is a
    # sound bound, and the error itself must be small for the test to mean anything.
    furnace = tripath.load("furnace")
    means = [tripath.render(furnace, "pt", spp=16, width=8, height=8, seed=s, max_depth=1000)["image"].mean()
             for s in range(1, 9)]
    mean, stderr = np.mean(means), np.std(means, ddof=1) / math.sqrt(len(means))
    assert stderr < 0.02 * 2
    assert abs(mean - 2) < 4 * stderr, (mean, stderr)


def test_bad_input_is_a_value_error_with_the_command_lines_message(tmp_path, cornell, cli_error):
    missing = str(tmp_path / "missing.gltf")
    with pytest.raises(ValueError) as e:
        tripath.load(missing)
    assert str(e.value) == cli_error("render", "--scene", missing, "--out", str(tmp_path / "x.exr"))
    with pytest.raises(ValueError, match="unknown scene"):
        tripath.load("no-such-scene")
    with pytest.raises(ValueError, match="^spp must be between 1 and 1000000"):
        tripath.render(cornell, "pt", spp=0)
    with pytest.raises(ValueError, match="^max_depth must be"):
        tripath.render(cornell, "pt", max_depth=0)
    with pytest.raises(ValueError, match="magic"):
        tripath.render(cornell, "magic")
    with pytest.raises(ValueError, match="unknown option 'radious'"):
        tripath.render(cornell, "vcm", radious=0.1)
    with pytest.raises(ValueError, match="exclude each other"):
        tripath.render(cornell, "pt", spp=1, seconds=1)
    with pytest.raises(ValueError, match="^strategy_images needs an integrator with more than one strategy per path length"):
        tripath.render(cornell, "lt", strategy_images=2)
    with pytest.raises(ValueError, match="^light_paths must be between 1 and"):
        tripath.render(cornell, "vcm", light_paths=0)


def test_a_render_over_its_memory_limit_is_a_value_error_before_it_starts(cornell):
    # As `tripath render --memory-limit`: the estimate, the limit and what to lower, in Python's
    # spelling, before any pass (progress is never called); with the limit raised it renders and
    # records its estimate. Fails if the keyword is not read or the check not made.
    passes = []
    with pytest.raises(ValueError, match=r"^the render needs an estimated .* but memory_limit is 64.0 MiB: .*"
                                         r"or raise memory_limit$"):
        tripath.render(cornell, "vcm", spp=100, width=64, height=64, memory_limit="64M",
                       progress=lambda p, s: passes.append(p))
    assert passes == []
    r = tripath.render(cornell, "vcm", spp=1, width=64, height=64, memory_limit=64 << 30)
    assert int(r["metadata"]["tripath:memory-estimate"]) > 140 << 20
    with pytest.raises(ValueError, match=r"^memory_limit must be a size above 0 such as 8G, 512M or 1.5T \(got '8X'\)$"):
        tripath.render(cornell, "pt", memory_limit="8X")
    with pytest.raises(ValueError, match="^memory_limit must be a size above 0"):
        tripath.render(cornell, "pt", memory_limit=0)
    with pytest.raises(TypeError, match="^memory_limit must be a number of bytes or a size"):
        tripath.render(cornell, "pt", memory_limit=1.5)


FUZZ_FINDS = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "fuzz"


@pytest.mark.parametrize("find", ["extras-nested-16000-deep.gltf", "extras-number-beyond-double.gltf"])
def test_hostile_json_is_a_value_error_with_the_command_lines_message(tmp_path, find, cli_error):
    # Arrays nested 16000 deep overflowed the stack in the loader, killing the interpreter.
    path = str(FUZZ_FINDS / find)
    with pytest.raises(ValueError) as e:
        tripath.load(path)
    assert str(e.value) == cli_error("render", "--scene", path, "--out", str(tmp_path / "x.exr"))
    assert str(e.value).startswith(path + ": ")


def test_every_keyword_option_the_error_names_is_taken(cornell):
    # The unknown-option error lists the keyword options from the parameter table; each must be one
    # that render() takes (pt refuses the ones it does not use, in other words). Catches a
    # parameter added to the table but not to the keywords render() reads.
    with pytest.raises(ValueError) as e:
        tripath.render(cornell, "pt", radious=0.1)
    names = str(e.value).split("the integrator options are ")[1].rstrip(")").split(", ")
    assert len(names) >= 9 and "rr_depth" in names and "large_step" in names
    for name in names:
        try:
            tripath.render(cornell, "pt", spp=1, width=4, height=4, **{name: 1})
        except ValueError as refused:
            assert "unknown option" not in str(refused), name


def write_gltf_with_degenerate_triangle(path):
    """A quad light facing a floor, plus one zero-area triangle the loader drops with a warning."""
    positions = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1),  # floor
                 (-0.2, 1, -0.2), (0.2, 1, -0.2), (0.2, 1, 0.2), (-0.2, 1, 0.2),  # light, facing down
                 (0, 0.5, 0), (0, 0.5, 0), (1, 0.5, 0)]  # degenerate
    indices = [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 8, 9, 10]
    data = b"".join(struct.pack("<3f", *p) for p in positions) + b"".join(struct.pack("<H", i) for i in indices)
    data += b"\0" * (-len(data) % 4)
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * len(positions)},
                        {"buffer": 0, "byteOffset": 12 * len(positions), "byteLength": 2 * len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                       "min": [-1, 0, -1], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0}},
                      {"emissiveFactor": [1, 1, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
    }
    # The light's two triangles get the emissive material: split the index range in three primitives.
    gltf["accessors"][1]["count"] = 6
    gltf["accessors"].append({"bufferView": 1, "byteOffset": 12, "componentType": 5123, "count": 6, "type": "SCALAR"})
    gltf["accessors"].append({"bufferView": 1, "byteOffset": 24, "componentType": 5123, "count": 3, "type": "SCALAR"})
    gltf["meshes"][0]["primitives"] += [{"attributes": {"POSITION": 0}, "indices": 2, "material": 1},
                                        {"attributes": {"POSITION": 0}, "indices": 3, "material": 0}]
    path.write_text(json.dumps(gltf))


def test_loader_warnings_are_python_warnings(tmp_path):
    path = tmp_path / "degenerate.gltf"
    write_gltf_with_degenerate_triangle(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = tripath.load(str(path))
    messages = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
    assert any("dropped 1 degenerate" in m for m in messages), messages
    assert scene.triangles == 4


def test_python_and_the_command_line_give_the_same_bits(tmp_path):
    out = tmp_path / "cli.exr"
    args = ["--scene", "cornell-spheres", "--integrator", "bdpt", "--spp", "3", "--width", "24", "--height", "16",
            "--seed", "5", "--max-depth", "8"]
    subprocess.run([TRIPATH, "render", *args, "--out", str(out)], check=True, capture_output=True)
    cli, meta = tripath.read_exr(str(out))
    scene = tripath.load("cornell-spheres")
    for threads in (1, 0):
        r = tripath.render(scene, "bdpt", spp=3, width=24, height=16, seed=5, max_depth=8, threads=threads)
        assert np.array_equal(r["image"], cli), threads
    assert meta["tripath:seed"] == "5" and meta["tripath:spp"] == "3"
    # A different seed differs: the comparison can fail.
    other = tripath.render(scene, "bdpt", spp=3, width=24, height=16, seed=6, max_depth=8)["image"]
    assert not np.array_equal(other, cli)


def test_an_environment_gives_the_command_lines_bits_and_is_recorded(tmp_path):
    # The Cornell box is open toward the camera: rays that leave it read the sky, and the sky lights
    # the box through the opening, so the environment changes the image (the comparison can fail).
    out = tmp_path / "cli.exr"
    args = ["--scene", "cornell", "--integrator", "bdpt", "--spp", "2", "--width", "24", "--height", "16",
            "--environment", "0.5,1,2", "--environment-scale", "3"]
    subprocess.run([TRIPATH, "render", *args, "--out", str(out)], check=True, capture_output=True)
    cli, meta = tripath.read_exr(str(out))
    scene = tripath.load("cornell", environment="0.5,1,2", environment_scale=3)
    r = tripath.render(scene, "bdpt", spp=2, width=24, height=16)
    assert np.array_equal(r["image"], cli)
    assert meta["tripath:environment"] == "0.5,1,2" and meta["tripath:environment-scale"] == "3"
    assert r["metadata"]["tripath:environment"] == "0.5,1,2"
    plain = tripath.render(tripath.load("cornell"), "bdpt", spp=2, width=24, height=16)
    assert not np.array_equal(plain["image"], cli)
    assert "tripath:environment" not in plain["metadata"]
    with pytest.raises(ValueError, match="environment_scale"):
        tripath.load("cornell", environment_scale=2)
    # An empty environment is a mistake, as on the command line, not a way to say none.
    with pytest.raises(ValueError, match="^environment is empty: give a map's path or a radiance R,G,B$"):
        tripath.load("cornell", environment="")


def test_light_paths_give_the_command_lines_bits_and_are_recorded(tmp_path):
    out = tmp_path / "cli.exr"
    args = ["--scene", "cornell-spheres", "--integrator", "vcm", "--spp", "2", "--width", "24", "--height", "16",
            "--light-paths", "1000"]
    subprocess.run([TRIPATH, "render", *args, "--out", str(out)], check=True, capture_output=True)
    cli, meta = tripath.read_exr(str(out))
    assert meta["tripath:light-paths-per-pass"] == "1000"
    r = tripath.render(tripath.load("cornell-spheres"), "vcm", spp=2, width=24, height=16, light_paths=1000)
    assert np.array_equal(r["image"], cli)
    assert r["metadata"]["tripath:light-paths-per-pass"] == "1000"
    default = tripath.render(tripath.load("cornell-spheres"), "vcm", spp=2, width=24, height=16)
    assert default["metadata"]["tripath:light-paths-per-pass"] == str(24 * 16)
    assert not np.array_equal(default["image"], cli)


def test_mlt_gives_the_command_lines_bits_and_records_its_chains(tmp_path):
    out = tmp_path / "cli.exr"
    args = ["--scene", "cornell-spheres", "--integrator", "mlt", "--spp", "2", "--width", "24", "--height", "16",
            "--bootstrap", "5000", "--chains", "40", "--large-step", "0.5"]
    subprocess.run([TRIPATH, "render", *args, "--out", str(out)], check=True, capture_output=True)
    cli, meta = tripath.read_exr(str(out))
    r = tripath.render(tripath.load("cornell-spheres"), "mlt", spp=2, width=24, height=16, bootstrap=5000, chains=40,
                       large_step=0.5)
    assert np.array_equal(r["image"], cli)
    for key in ["tripath:bootstrap", "tripath:chains", "tripath:large-step", "tripath:mlt-normalisation",
                "tripath:mlt-acceptance"]:
        assert r["metadata"][key] == meta[key], key
    assert (meta["tripath:bootstrap"], meta["tripath:chains"], meta["tripath:large-step"]) == ("5000", "40", "0.5")
    assert r["counters"]["mutations"] >= 2 * 24 * 16 and r["counters"]["accepted_mutations"] > 0
    with pytest.raises(ValueError, match="^chains needs mlt: bdpt does not"):
        tripath.render(tripath.load("cornell-spheres"), "bdpt", spp=1, chains=4)


def test_one_loaded_scene_renders_at_any_size(cornell):
    small = tripath.render(cornell, "pt", spp=1, width=8, height=6)["image"]
    large = tripath.render(cornell, "pt", spp=1, width=16, height=12)["image"]
    assert small.shape == (6, 8, 3) and large.shape == (12, 16, 3)
    again = tripath.render(cornell, "pt", spp=1, width=8, height=6)["image"]
    assert np.array_equal(small, again)


def test_threads_render_one_scene_at_two_sizes_at_once():
    # The GIL is released while rendering, so the second thread asks for another size while the
    # first renders: each must keep the scene it renders (catches a rebuild under a running render).
    import threading
    scene = tripath.load("cornell-spheres")
    sizes = [(48, 40), (16, 8)]
    alone = [tripath.render(scene, "bdpt", spp=6, width=w, height=h, threads=1)["image"] for w, h in sizes]
    together = [None, None]

    def run(i):
        w, h = sizes[i]
        together[i] = tripath.render(scene, "bdpt", spp=6, width=w, height=h, threads=1)["image"]

    threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, together):
        assert np.array_equal(a, b)


def test_the_image_is_the_films_memory_without_a_copy(cornell):
    r = tripath.render(cornell, "pt", spp=1, width=16, height=8, depth_images=True, max_depth=3)
    image = r["image"]
    # A view over memory the module handed over (its base owns it), not an array NumPy allocated.
    assert not image.flags.owndata and image.base is not None and image.flags.c_contiguous
    kept = image.copy()
    del r
    gc.collect()
    assert np.array_equal(image, kept)  # the array keeps its memory alive on its own


def test_depth_layers_add_up_to_a_render_without_them(cornell):
    # Layers k = 1..3 of one render against other renders of the same samples (same seed), made
    # without depth layers: their sum is the image of a render that never computed a layer, and
    # layer 1 is the image at max_depth 1 (the camera rays' first hits on the light, the same rays
    # at any max_depth). Catches layers that lose or double some contributions, an image that
    # depth layers change, and layers filed under another k or handed over in another order (both
    # keep the sum). Only layer 1 is exact: pt draws its next-event samples after the camera walk,
    # whose length depends on max_depth, so other layers match other renders only on average.
    size = dict(spp=2, width=16, height=8, seed=4)
    r = tripath.render(cornell, "pt", depth_images=True, max_depth=3, **size)
    assert len(r["depth"]) == 3 and all(layer.mean() > 0.005 for layer in r["depth"])
    alone = tripath.render(cornell, "pt", max_depth=3, **size)
    assert "depth" not in alone
    assert np.allclose(sum(r["depth"]), alone["image"], rtol=1e-5, atol=1e-6)
    direct = tripath.render(cornell, "pt", max_depth=1, **size)["image"]
    assert direct.mean() > 0.005
    assert np.array_equal(r["depth"][0], direct)


def test_strategy_layers_are_keyed_by_s_t_and_technique(cornell):
    r = tripath.render(cornell, "vcm", spp=1, width=16, height=8, strategy_images=3)
    keys = set(r["strategies"])
    assert (0, 2, "connect") in keys and (1, 2, "connect") in keys and (2, 2, "merge") in keys
    assert all(set(v) == {"weighted", "unweighted"} for v in r["strategies"].values())


def test_progress_is_called_after_each_pass_and_its_exception_stops_the_render(cornell):
    seen = []
    tripath.render(cornell, "pt", spp=5, width=8, height=8, progress=lambda p, s: seen.append(p))
    assert seen == [1, 2, 3, 4, 5]

    def fail(passes, seconds):
        if passes == 2:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        tripath.render(cornell, "pt", spp=50, width=8, height=8, progress=fail)


def test_ctrl_c_inside_the_progress_callback_returns_the_partial_image_too(cornell):
    # Python raises KeyboardInterrupt wherever its code runs when Ctrl-C comes: here, in the callback.
    def interrupted_at_two(passes, seconds):
        if passes == 2:
            raise KeyboardInterrupt

    r = tripath.render(cornell, "pt", spp=50, width=8, height=8, progress=interrupted_at_two)
    assert r["interrupted"] and r["spp"] == 2 and r["image"].mean() > 0


def test_ctrl_c_stops_at_the_next_pass_and_returns_the_partial_image():
    script = textwrap.dedent("""
        import sys, tripath
        scene = tripath.load("cornell")
        def started(passes, seconds):
            if passes == 1:
                print("started", flush=True)
        r = tripath.render(scene, "bdpt", seconds=120, width=64, height=64, threads=1, progress=started)
        print("interrupted" if r["interrupted"] else "finished", r["spp"], float(r["image"].mean()), flush=True)
    """)
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=os.environ)
    assert p.stdout.readline().strip() == "started"
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    assert p.returncode == 0
    word, spp, mean = out.split()
    assert word == "interrupted" and int(spp) >= 1 and float(mean) > 0


def test_metrics_on_hand_made_images():
    reference = np.ones((4, 5, 3), np.float32)
    assert tripath.metrics.relmse(reference, reference) == 0
    assert tripath.metrics.hdr_flip(reference, reference) == 0
    off = reference + np.float32(0.1)
    # (0.1)^2 / (1^2 + 0.01) in every pixel and channel.
    assert tripath.metrics.relmse(off, reference) == pytest.approx(0.01 / 1.01, rel=1e-5)
    assert tripath.metrics.mse(off, reference) == pytest.approx(0.01, rel=1e-5)
    assert tripath.metrics.mae(off, reference) == pytest.approx(0.1, rel=1e-5)
    one = reference.copy()
    one[2, 3] += 1  # one pixel of 20 carries all the error: the worst 0.1 % (one pixel) has all of it
    assert tripath.metrics.tail_share(one, reference) == pytest.approx(1)
    assert tripath.metrics.relmse_without_tail(one, reference) == 0
    assert tripath.metrics.hdr_flip(one, reference) > 0
    with pytest.raises(ValueError, match="shape"):
        tripath.metrics.relmse(np.ones((4, 5)), reference)

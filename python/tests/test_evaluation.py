"""tripath.compare and tripath.benchmark: the library's comparison and benchmark (the same code as
`tripath compare` and `tripath benchmark`) with their tables as lists of dicts. The tests measure
the returned images again (relMSE in NumPy, HDR-FLIP with tripath.metrics), read the files the
report writes, and hold the error messages to the command line's."""
import csv
import struct
import zlib

import numpy as np
import pytest

import tripath

SIZE = dict(width=24, height=16, threads=1)


def relmse(image, reference, epsilon=0.01):
    """relMSE as src/evaluation/metrics.h defines it, in double precision."""
    x, r = image.astype(np.float64), reference.astype(np.float64)
    return np.mean((x - r) ** 2 / (r ** 2 + epsilon))


@pytest.fixture(scope="module")
def reference(cornell):
    # A reference from other samples than any run's (the runs use seeds 1, 2, ... in the render streams).
    return tripath.render(cornell, "bdpt", spp=256, seed=1000, **SIZE)["image"]


def test_compare_measures_the_images_it_returns(cornell, reference):
    r = tripath.compare(cornell, 0.2, integrators=["pt", "bdpt"], reference=reference, **SIZE)
    assert [row["integrator"] for row in r["summary"]] == ["pt", "bdpt"]
    assert r["reference"].shape == (16, 24, 3) and np.array_equal(r["reference"], reference)
    assert r["report"] is None
    for row in r["summary"]:
        image = r["images"][row["integrator"]]
        assert image.shape == (16, 24, 3) and image.mean() > 0.01
        # One run: the summary is run 0's finished render, measured against the given reference.
        # Catches an image measured against another reference, rows matched to the wrong method,
        # and a relMSE computed otherwise than documented (the mean over pixels and channels of
        # (x - r)^2 / (r^2 + 0.01)): the expected value is NumPy's, not the library's metric.
        assert row["relmse"] == pytest.approx(relmse(image, reference), rel=1e-5)
        assert row["hdr_flip"] == pytest.approx(tripath.metrics.hdr_flip(image, reference), rel=1e-5)
        assert row["relmse_x_spp"] == pytest.approx(row["relmse"] * row["spp"], rel=1e-6)
        assert row["seconds"] >= 0.2 and row["spp"] >= 1 and row["relmse_sd"] == 0
        mine = [c for c in r["checkpoints"] if c["integrator"] == row["integrator"]]
        assert [c["seconds"] for c in mine] == sorted(c["seconds"] for c in mine)
        assert mine[-1]["relmse"] == row["relmse"] and mine[-1]["spp"] == row["spp"]
        assert mine[-1]["hdr_flip"] == row["hdr_flip"] and all(c["hdr_flip"] is None for c in mine[:-1])
    counters = {run["integrator"]: run["counters"] for run in r["runs"]}
    assert counters["pt"]["closest_hit_rays"] >= 24 * 16 and counters["bdpt"]["shadow_rays"] > 0


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def test_compare_with_a_directory_writes_the_command_lines_report(cornell, tmp_path):
    out = tmp_path / "report"
    r = tripath.compare(cornell, 0.1, integrators=["pt", "lt"], runs=2, reference_seconds=0.4, out=str(out), **SIZE)
    assert r["report"] == str(out / "index.html")
    for name in ["index.html", "summary.md", "error-vs-time.svg", "reference.exr", "pt.exr", "lt.png", "counters.csv"]:
        assert (out / name).is_file(), name
    assert r["reference_description"].startswith("vcm, ")
    # The rendered reference is the one on disk, and every row of error.csv is a checkpoint returned.
    assert np.array_equal(tripath.read_exr(str(out / "reference.exr"))[0], r["reference"])
    rows = read_rows(out / "error.csv")
    assert len(rows) == len(r["checkpoints"])
    for row, c in zip(rows, r["checkpoints"]):
        assert (row["integrator"], int(row["run"]), int(row["spp"])) == (c["integrator"], c["run"], c["spp"])
        assert float(row["relmse"]) == pytest.approx(c["relmse"], rel=1e-6)
    assert {c["run"] for c in r["checkpoints"]} == {0, 1}
    assert all(row["relmse_sd"] > 0 for row in r["summary"])  # two independent runs differ


def png_size_and_first_pixel(path):
    """An 8-bit RGB PNG's width, height and top-left pixel: whatever a row's filter, the first pixel
    of the first row is stored as it is (its left and upper neighbours count as 0)."""
    data = path.read_bytes()
    width, height = struct.unpack(">II", data[16:24])
    idat, at = b"", 8
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        if kind == b"IDAT":
            idat += data[at + 8:at + 8 + length]
        at += 12 + length
    return width, height, tuple(zlib.decompress(idat)[1:4])


def test_compare_writes_a_papers_figure(cornell, reference, tmp_path):
    # theme, labels and formats reach the sheet as the command line's --theme, --no-labels and
    # --formats do: on white, without the title rows, and as a PDF too. 24x16 panels are shown 11x
    # (264 x 176) and the 8x8 crop 22x; each of the two rows of panels (images, error maps) is
    # 8 + 176 + 8 + 176 + 8 high, over the 56-pixel colour bar. Catches a keyword taken and dropped.
    out = tmp_path / "figure"
    tripath.compare(cornell, 0.05, integrators=["pt"], reference=reference, out=str(out), crop=(8, 4, 8, 8),
                    theme="light", labels=False, formats=["pdf"], **SIZE)
    assert png_size_and_first_pixel(out / "side-by-side.png") == (8 + 2 * (264 + 8), 2 * 376 + 56, (255, 255, 255))
    assert (out / "side-by-side.pdf").read_bytes().startswith(b"%PDF-")
    assert png_size_and_first_pixel(out / "pt-crop.png")[:2] == (512, 512)
    with pytest.raises(ValueError, match="^theme must be dark or light"):
        tripath.compare(cornell, 0.05, integrators=["pt"], reference=reference, theme="sepia", **SIZE)
    with pytest.raises(ValueError, match="^formats takes png, pdf and svg"):
        tripath.compare(cornell, 0.05, integrators=["pt"], reference=reference, formats=["gif"], **SIZE)


def test_compare_refuses_bad_input_as_the_command_line_does(cornell, reference, tmp_path, cli_error):
    out = str(tmp_path / "x")
    with pytest.raises(ValueError) as e:
        tripath.compare(cornell, 1, runs=0, **SIZE)
    # The same check and words, in each front end's spelling of the parameter.
    assert str(e.value) == cli_error("compare", "--scene", "cornell", "--time", "1", "--runs", "0", "--out", out).replace(
        "--runs", "runs")
    with pytest.raises(ValueError, match="^integrators lists 'pt' twice"):
        tripath.compare(cornell, 1, integrators=["pt", "pt"], reference=reference, **SIZE)
    with pytest.raises(ValueError, match="magic"):
        tripath.compare(cornell, 1, integrators=["pt", "magic"], reference=reference, **SIZE)
    with pytest.raises(ValueError, match="^seconds must be"):
        tripath.compare(cornell, 0, reference=reference, **SIZE)
    with pytest.raises(ValueError, match="the reference is 24x16, the renders 32x16"):
        tripath.compare(cornell, 1, reference=reference, width=32, height=16)
    with pytest.raises(ValueError, match="^crop 20,0,8,8 is not inside the 24x16 image"):
        tripath.compare(cornell, 1, reference=reference, crop=(20, 0, 8, 8), **SIZE)
    with pytest.raises(ValueError, match="cannot read reference"):
        tripath.compare(cornell, 1, reference=str(tmp_path / "missing.exr"), **SIZE)


def test_compare_stops_on_ctrl_c_and_on_the_callbacks_error(cornell, reference):
    labels = []

    def interrupt(label, passes, seconds):
        labels.append(label)
        if passes == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        tripath.compare(cornell, 30, integrators=["pt", "bdpt"], reference=reference, progress=interrupt, **SIZE)
    assert labels[0] == "pt run 1/1" and len(labels) == 2  # stopped at the second pass, nothing more started

    def fail(label, passes, seconds):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        tripath.compare(cornell, 30, reference=reference, progress=fail, **SIZE)


def test_benchmark_returns_the_rows_of_results_csv_and_reuses_its_reference(tmp_path):
    out = tmp_path / "bench"
    settings = dict(integrators=["pt", "bdpt"], runs=2, reference_integrator="bdpt", reference_seconds=0.5,
                    width=16, height=16, threads=1)
    rows = tripath.benchmark(["cornell"], 0.1, str(out), **settings)
    assert [(r["scene"], r["integrator"]) for r in rows] == [("cornell", "pt"), ("cornell", "bdpt")]
    written = read_rows(out / "results.csv")
    for row, w in zip(rows, written):
        assert (w["scene"], w["integrator"]) == (row["scene"], row["integrator"])
        # As many digits as the CSV keeps: 6 significant, 4 for the speed-up.
        for key, digits in [("relmse", 6), ("relmse_without_tail", 6), ("hdr_flip", 6), ("speedup", 4)]:
            assert float(w[key]) == pytest.approx(row[key], rel=10.0 ** (1 - digits)), key
        assert int(w["blocks"]) == row["blocks"] and row["counters"]["closest_hit_rays"] > 0
    assert rows[0]["speedup"] == pytest.approx(1)  # the baseline is the first integrator
    assert rows[1]["blocks"] == 0  # bdpt is the bias reference itself: not tested against itself
    assert rows[0]["blocks"] > 0 and 0 <= rows[0]["biased_blocks"] <= rows[0]["blocks"]
    (cached,) = list((out / "references").glob("*.exr"))
    stamp = cached.stat().st_mtime_ns
    tripath.benchmark(["cornell"], 0.1, str(out), **settings)
    assert cached.stat().st_mtime_ns == stamp  # the same settings: the cached reference is reused
    with pytest.raises(ValueError, match="^runs must be between 2 and 100"):
        tripath.benchmark(["cornell"], 0.1, str(out), **{**settings, "runs": 1})
    with pytest.raises(ValueError, match="^baseline 'vcm' is not one of integrators"):
        tripath.benchmark(["cornell"], 0.1, str(out), baseline="vcm", **settings)
    with pytest.raises(ValueError, match="^environment is empty: give a map's path or a radiance R,G,B$"):
        tripath.benchmark(["cornell"], 0.1, str(out), environment="", **settings)

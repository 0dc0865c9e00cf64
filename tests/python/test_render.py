"""prism.render(): the arrays and provenance it returns, bit for bit the EXR `prism render` writes
for the same options (read with OpenImageIO's own Python module, python3-openimageio)."""

import os
import pathlib
import signal
import threading
import time

import numpy as np
import pytest

import prism

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "data"
CORNELL = SCENES / "cornell_spheres.json"
# Small and quick, with every feature of the film.
SMALL = dict(resolution=(40, 30), spp=4, seed=5, max_depth=3)

AOV_CHANNELS = {"albedo": ["albedo.R", "albedo.G", "albedo.B"],
                "normal": ["N.X", "N.Y", "N.Z"],
                "depth": ["Z"],
                "sample_count": ["sampleCount.Y"],
                "variance": ["variance.R", "variance.G", "variance.B"]}
# Provenance that differs from run to run.
TIMINGS = {"prism:build_ms", "prism:render_ms", "prism:samples_per_second",
           "prism:command_line"}


def same_bits(a, b):
    a, b = np.ascontiguousarray(a, np.float32), np.ascontiguousarray(b, np.float32)
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))


def read_exr(path):
    """(channels by name as H x W float32 arrays, header attributes) of an EXR."""
    oiio = pytest.importorskip("OpenImageIO")
    image = oiio.ImageInput.open(str(path))
    assert image, oiio.geterror()
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    channels = {name: pixels[:, :, i] for i, name in enumerate(spec.channelnames)}
    attributes = {a.name: a.value for a in spec.extra_attribs}
    return channels, attributes


@pytest.fixture(scope="module")
def small():
    return prism.render(CORNELL, **SMALL)


def test_render_returns_the_documented_arrays(small):
    assert set(small) == {"image", "aovs", "provenance", "window", "resolution"}
    image = small["image"]
    assert image.shape == (30, 40, 3) and image.dtype == np.float32
    assert image.flags["C_CONTIGUOUS"]
    assert np.isfinite(image).all() and image.max() > 0
    shapes = {"albedo": (30, 40, 3), "normal": (30, 40, 3), "depth": (30, 40),
              "sample_count": (30, 40), "variance": (30, 40, 3)}
    assert {name: a.shape for name, a in small["aovs"].items()} == shapes
    assert all(a.dtype == np.float32 for a in small["aovs"].values())
    assert np.all(small["aovs"]["sample_count"] == 4)
    assert small["window"] == (0, 0, 40, 30)
    assert small["resolution"] == (40, 30)


def test_provenance_is_the_exrs(small):
    provenance = small["provenance"]
    assert provenance["prism:scene"] == str(CORNELL)
    assert provenance["prism:accelerator"] == "bvh"
    assert provenance["prism:spp"] == "4"
    assert provenance["prism:seed"] == "5"
    assert provenance["prism:max_depth"] == "3"
    assert provenance["prism:resolution"] == "40x30"
    assert provenance["prism:passes"] == "1 of 1"  # passes of at least 4 samples
    assert provenance["prism:stoppedBy"] == "-"
    assert provenance["prism:version"] == prism.__version__
    assert provenance["prism:command_line"].startswith("prism.render(")
    assert "spp=4" in provenance["prism:command_line"]
    for key in ["prism:integrator", "prism:sampler", "prism:build_ms", "prism:render_ms",
                "prism:params", "prism:camera_samples", "prism:colorSpace",
                "prism:workingSpace", "prism:ocioConfig", "prism:ocioConfigHash"]:
        assert key in provenance, key
    assert all(isinstance(v, str) for v in provenance.values())


def test_render_equals_the_command_lines_exr_bit_for_bit(small, run_prism, tmp_path):
    out = tmp_path / "a.exr"
    result = run_prism("render", CORNELL, "-r", 40, 30, "-s", 4, "--seed", 5, "-m", 3,
                       "--exr-type", "float", "-q", "-f", out)
    assert result.returncode == 0, result.stderr
    channels, attributes = read_exr(out)
    for i, name in enumerate("RGB"):
        assert same_bits(small["image"][:, :, i], channels[name]), name
    for aov, names in AOV_CHANNELS.items():
        array = small["aovs"][aov]
        for i, name in enumerate(names):
            assert same_bits(array if array.ndim == 2 else array[:, :, i], channels[name]), name
    for key, value in small["provenance"].items():
        # (EXR headers keep no empty strings: prism:params is "" without --set.)
        assert key in attributes or value == "", key
        if key not in TIMINGS:
            assert str(attributes.get(key, "")) == value, key


def test_threads_and_exact_backends_do_not_change_the_pixels(small):
    # bvh returns brute force's hits bit for bit (Embree may differ at ties).
    for kwargs in [dict(threads=1), dict(accel="brute")]:
        other = prism.render(CORNELL, **SMALL, **kwargs)
        assert same_bits(other["image"], small["image"]), kwargs
        assert same_bits(other["aovs"]["depth"], small["aovs"]["depth"]), kwargs


def test_a_crop_is_the_full_images_window(small):
    crop = prism.render(CORNELL, **SMALL, crop=(8, 4, 30, 20))
    assert crop["window"] == (8, 4, 30, 20)
    assert crop["resolution"] == (40, 30)
    assert crop["image"].shape == (16, 22, 3)
    assert same_bits(crop["image"], small["image"][4:20, 8:30])
    assert crop["provenance"]["prism:crop"] == "8 4 30 20"


def test_set_as_dict_or_list_and_options_reach_the_render():
    a = prism.render(CORNELL, resolution=(16, 12), spp=2, set={"bvh.max_leaf_size": 2,
                                                               "path.mis": False})
    b = prism.render(CORNELL, resolution=(16, 12), spp=2,
                     set=["bvh.max_leaf_size=2", "path.mis=false"])
    assert same_bits(a["image"], b["image"])
    assert "bvh.max_leaf_size=2" in a["provenance"]["prism:params"]
    assert "path.mis=false" in a["provenance"]["prism:params"]
    depth = prism.render(CORNELL, resolution=(16, 12), spp=1, integrator="depth")
    assert depth["provenance"]["prism:integrator"] == "depth"
    samples = prism.render(CORNELL, resolution=(16, 12), spp=8, samples=(2, 5))
    assert np.all(samples["aovs"]["sample_count"] == 3)
    adaptive = prism.render(CORNELL, resolution=(16, 12), spp=64, adaptive=(8, 0.5))
    assert adaptive["aovs"]["sample_count"].min() < 64


def test_the_default_scene_renders():
    result = prism.render(resolution=(8, 6), spp=1)
    assert result["image"].shape == (6, 8, 3)
    assert result["provenance"]["prism:scene"].endswith("cornell_spheres.json")


def test_render_in_a_thread_while_python_runs(small):
    # The GIL is released while rendering: the main thread keeps running Python meanwhile.
    results = {}
    thread = threading.Thread(target=lambda: results.update(prism.render(CORNELL, **SMALL)))
    thread.start()
    count = 0
    while thread.is_alive() and count < 10**8:
        count += 1
    thread.join(timeout=300)
    assert not thread.is_alive()
    assert count > 0
    assert same_bits(results["image"], small["image"])


def test_ctrl_c_stops_the_render_between_passes():
    # A render of many seconds, interrupted after a moment by SIGINT, raises KeyboardInterrupt
    # (the signal is checked between passes) and leaves the module usable.
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    finished = False
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            prism.render(CORNELL, resolution=(32, 24), spp=1 << 16)
            finished = True
            time.sleep(10)  # should the render end first, the signal arrives here
    finally:
        timer.cancel()
    assert not finished
    assert time.monotonic() - start < 60
    assert prism.render(CORNELL, resolution=(4, 3), spp=1)["image"].shape == (3, 4, 3)

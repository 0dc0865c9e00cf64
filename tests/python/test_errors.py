"""Failures arrive as prism.Error carrying the one line `prism` prints after "prism: error: ", its
kind and exit code; bad arrays are ValueError or TypeError."""

import pathlib

import numpy as np
import pytest

import prism

CORNELL = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "data" / "cornell_spheres.json"


def cli_error(run_prism, *args):
    """The one-line message and exit code of a failing `prism` run."""
    result = run_prism(*args)
    assert result.returncode != 0, result.stdout
    lines = [line for line in result.stderr.splitlines() if line.startswith("prism: error: ")]
    assert len(lines) == 1, result.stderr
    return lines[0][len("prism: error: "):], result.returncode


@pytest.mark.parametrize("cli_args, kwargs", [
    # A scene that does not exist.
    (["render", "no/such/scene.json"], {"scene": "no/such/scene.json"}),
    # An unknown accelerator.
    (["render", CORNELL, "--accel", "bhv"], {"scene": CORNELL, "accel": "bhv"}),
    # A --set key nobody reads, as a dict and as a list.
    (["render", CORNELL, "--set", "bvh.leaf=3"], {"scene": CORNELL, "set": {"bvh.leaf": 3}}),
    (["render", CORNELL, "--set", "bvh.leaf=3"], {"scene": CORNELL, "set": ["bvh.leaf=3"]}),
    (["render", CORNELL, "--set", "leaf=3"], {"scene": CORNELL, "set": {"leaf": 3}}),
    # Option values out of range.
    (["render", CORNELL, "-s", "0"], {"scene": CORNELL, "spp": 0}),
    (["render", CORNELL, "--seed", "-1"], {"scene": CORNELL, "seed": -1}),
    (["render", CORNELL, "--crop", "0", "0", "900", "10"],
     {"scene": CORNELL, "crop": (0, 0, 900, 10)}),
    (["render", CORNELL, "--integrator", "pathh"], {"scene": CORNELL, "integrator": "pathh"}),
])
def test_render_errors_are_the_command_lines(run_prism, tmp_path, cli_args, kwargs):
    message, code = cli_error(run_prism, *cli_args, "-f", tmp_path / "out.exr")
    with pytest.raises(prism.Error) as caught:
        prism.render(**kwargs)
    error = caught.value
    assert str(error) == message
    assert error.exit_code == code
    assert isinstance(error, RuntimeError)
    assert error.kind in ("usage", "input")
    assert error.detail in message


def test_errors_carry_their_location(tmp_path):
    scene = tmp_path / "broken.json"
    scene.write_text('{"materials": [], "objects": [')
    with pytest.raises(prism.Error) as caught:
        prism.load_scene(scene)
    error = caught.value
    assert error.kind == "input" and error.exit_code == 2
    assert error.file == str(scene)
    assert str(error).startswith(str(scene))
    assert "\n" not in str(error)


def test_scene_and_info_errors_are_the_command_lines(run_prism):
    message, code = cli_error(run_prism, "info", "no/such/scene.dae")
    with pytest.raises(prism.Error, match="no/such/scene.dae") as caught:
        prism.load_scene("no/such/scene.dae")
    assert str(caught.value) == message and caught.value.exit_code == code
    with pytest.raises(prism.Error) as caught:
        prism.info("no/such/scene.dae")
    assert str(caught.value) == message

    message, _ = cli_error(run_prism, "info", CORNELL, "--accel", "bvh", "--set", "bvh.nope=1")
    with pytest.raises(prism.Error) as caught:
        prism.info(CORNELL, accel="bvh", set={"bvh.nope": 1})
    assert str(caught.value) == message


def test_accelerator_errors_are_the_command_lines(run_prism):
    vertices = np.zeros((3, 3), dtype=np.float32)
    indices = np.array([[0, 1, 2]])
    message, _ = cli_error(run_prism, "info", CORNELL, "--accel", "bhv")
    with pytest.raises(prism.Error) as caught:
        prism.Accelerator("bhv", vertices, indices)
    assert str(caught.value) == message
    assert caught.value.kind == "usage"

    message, _ = cli_error(run_prism, "info", CORNELL, "--accel", "bvh", "--set",
                           "bvh.max_leaf=4")
    with pytest.raises(prism.Error) as caught:
        prism.Accelerator("bvh", vertices, indices, max_leaf=4)
    assert str(caught.value) == message

    message, _ = cli_error(run_prism, "info", CORNELL, "--accel", "bvh", "--set",
                           "bvh.max_leaf_size=many")
    with pytest.raises(prism.Error) as caught:
        prism.Accelerator("bvh", vertices, indices, max_leaf_size="many")
    assert str(caught.value) == message

    message, _ = cli_error(run_prism, "info", CORNELL, "-t", "-2")
    with pytest.raises(prism.Error) as caught:
        prism.Accelerator("bvh", vertices, indices, threads=-2)
    assert str(caught.value) == message


def test_bad_geometry_is_an_input_error():
    vertices = np.zeros((3, 3), dtype=np.float32)
    with pytest.raises(prism.Error, match="index out of range") as caught:
        prism.Accelerator("embree", vertices, np.array([[0, 1, 3]]))
    assert caught.value.kind == "input"
    with pytest.raises(prism.Error, match="not finite"):
        prism.Accelerator("bvh", np.full((3, 3), np.nan), np.array([[0, 1, 2]]))
    with pytest.raises(prism.Error, match="positive radius"):
        prism.Accelerator("brute", vertices, np.array([[0, 1, 2]]), spheres=[[0, 0, 0, -1]])


def test_bad_arrays_are_value_and_type_errors():
    vertices = np.eye(3, dtype=np.float32)
    indices = np.array([[0, 1, 2]])
    with pytest.raises(ValueError, match=r"vertices must have shape \(N, 3\), got \(3, 2\)"):
        prism.Accelerator("bvh", vertices[:, :2], indices)
    with pytest.raises(ValueError, match=r"indices must have shape \(N, 3\), got \(3,\)"):
        prism.Accelerator("bvh", vertices, indices[0])
    with pytest.raises(TypeError, match="indices must hold integers"):
        prism.Accelerator("bvh", vertices, indices.astype(np.float32))
    with pytest.raises(ValueError, match=r"indices must be in \[0, 2\^32\)"):
        prism.Accelerator("bvh", vertices, -indices)
    with pytest.raises(TypeError, match="vertices must hold real numbers"):
        prism.Accelerator("bvh", np.array([["a", "b", "c"]]), indices)

    accel = prism.Accelerator("bvh", vertices, indices)
    rays = np.zeros((4, 3), dtype=np.float32)
    with pytest.raises(ValueError, match=r"origins must have shape \(N, 3\), got \(4, 4\)"):
        accel.intersect(np.zeros((4, 4)), rays)
    with pytest.raises(ValueError, match="origins and directions must have the same shape"):
        accel.intersect(rays, rays[:3])
    with pytest.raises(ValueError, match=r"tmax must be a number or have shape \(4,\)"):
        accel.intersect(rays, rays, 0.0, np.ones(3))
    with pytest.raises(ValueError, match=r"tmin must be a number or have shape \(4,\)"):
        accel.occluded(rays, rays, np.ones((4, 1)))
    with pytest.raises(TypeError, match="tmin must be a number"):
        accel.occluded(rays, rays, "near")


def test_bad_set_types_are_type_errors():
    with pytest.raises(TypeError, match="set must be a dict"):
        prism.render(CORNELL, set="bvh.max_leaf_size=3")
    with pytest.raises(TypeError, match="seed must be an int"):
        prism.render(CORNELL, seed=1.5)

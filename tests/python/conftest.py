"""Shared fixtures of the Python module's tests (tests/python/, run by ctest; README "Python").

The module is imported from $PYTHONPATH (build/python, as ctest sets it) or else from
$PRISM_BUILD_DIR/python (default: build/ of this checkout); the `prism` program the tests compare
with is $PRISM_BINARY, else the one in that build folder.
"""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("PRISM_BUILD_DIR", ROOT / "build"))
# After $PYTHONPATH's entries, so that an explicit setting wins.
sys.path.append(str(BUILD / "python"))

import prism  # noqa: E402

SCENES = ROOT / "scenes" / "data"


@pytest.fixture(scope="session")
def prism_binary():
    """Path of the `prism` program."""
    path = pathlib.Path(os.environ.get("PRISM_BINARY", BUILD / "prism"))
    if not path.is_file():
        pytest.fail(f"no prism program at {path}: build it (scripts/build) or set PRISM_BINARY")
    return path


@pytest.fixture(scope="session")
def run_prism(prism_binary):
    """Runs `prism ARGS...`; returns the CompletedProcess (text stdout and stderr)."""

    def run(*args):
        return subprocess.run([str(prism_binary), *map(str, args)], capture_output=True,
                              text=True, check=False)

    return run


@pytest.fixture(scope="session")
def cornell_mesh():
    """The bundled Cornell box of meshes (scenes/data/cornell_mesh.json) as one mesh:
    (vertices N x 3 float32, indices M x 3 uint32)."""
    geometry = prism.load_scene(SCENES / "cornell_mesh.json")["geometry"]
    vertices, indices, offset = [], [], 0
    for mesh in geometry["meshes"]:
        vertices.append(mesh["vertices"])
        indices.append(mesh["indices"] + np.uint32(offset))
        offset += len(mesh["vertices"])
    return np.concatenate(vertices), np.concatenate(indices)


@pytest.fixture(scope="session")
def random_rays():
    """random_rays(count, lower, upper, seed): `count` rays from points uniform in the box
    [lower, upper] in uniform directions, as (origins, directions), float32 K x 3."""

    def make(count, lower, upper, seed):
        rng = np.random.default_rng(seed)
        origins = rng.uniform(lower, upper, size=(count, 3)).astype(np.float32)
        directions = rng.normal(size=(count, 3)).astype(np.float32)
        return origins, directions

    return make

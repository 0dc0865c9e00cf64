"""prism.load_scene() and prism.info(): what `prism info` prints, as dicts."""

import pathlib

import numpy as np

import prism

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "data"


def info_lines(run_prism, *args):
    """`prism info ARGS` as {first word(s): rest of the line}, and its whole output."""
    result = run_prism("info", *args)
    assert result.returncode == 0, result.stderr
    lines = {}
    for line in result.stdout.splitlines():
        if line.startswith("  "):
            continue
        key, _, value = line.partition("  ")
        lines[key.strip()] = value.strip()
    return lines, result.stdout


def test_load_scene_counts_what_prism_info_prints(run_prism):
    for name in ["cornell_mesh.json", "cornell_spheres.json"]:
        path = SCENES / name
        scene = prism.load_scene(path)
        lines, output = info_lines(run_prism, path, "--accel", "brute")
        assert scene["source"] == lines["scene"] == str(path)
        assert str(scene["triangles"]) == lines["triangles"]
        assert str(scene["meshes"]) == lines["meshes"]
        assert str(scene["spheres"]) == lines["spheres"]
        assert str(scene["emissive_meshes"]) == lines["emissive meshes"]
        materials = ", ".join(f"{k} {v}" for k, v in scene["materials"].items())
        assert lines["materials"] == f"{sum(scene['materials'].values())} ({materials})"
        assert lines["lights"].split()[0] == str(sum(scene["lights"].values()))
        lower, upper = scene["bounds"]
        assert lines["bounds"].startswith(f"({lower[0]:.4g}, {lower[1]:.4g}, {lower[2]:.4g})")
        camera = scene["camera"]
        assert lines["camera"].startswith("position ({:.4g}, {:.4g}, {:.4g})".format(
            *camera["position"]))
        assert f"hfov {camera['hfov_deg']:.4g} deg" in output
        assert set(camera) == {"position", "target", "up", "hfov_deg", "vfov_deg",
                               "lens_radius", "focal_distance"}
        assert set(scene["settings"]) == {"resolution", "spp", "max_depth", "integrator", "seed"}


def test_load_scene_geometry_is_the_scenes():
    scene = prism.load_scene(SCENES / "cornell_spheres.json")
    geometry = scene["geometry"]
    assert len(geometry["meshes"]) == scene["meshes"]
    assert sum(len(m["indices"]) for m in geometry["meshes"]) == scene["triangles"]
    for mesh in geometry["meshes"]:
        assert mesh["vertices"].dtype == np.float32 and mesh["vertices"].shape[1] == 3
        assert mesh["indices"].dtype == np.uint32 and mesh["indices"].shape[1] == 3
        assert mesh["indices"].max() < len(mesh["vertices"])
        assert isinstance(mesh["name"], str) and isinstance(mesh["material"], str)
    spheres = geometry["spheres"]
    assert spheres.shape == (scene["spheres"], 4) and spheres.dtype == np.float32
    assert np.all(spheres[:, 3] > 0)
    lower, upper = np.array(scene["bounds"])
    for mesh in geometry["meshes"]:
        assert np.all(mesh["vertices"] >= lower) and np.all(mesh["vertices"] <= upper)


def test_info_adds_the_build_statistics(run_prism):
    path = SCENES / "cornell_mesh.json"
    info = prism.info(path, accel=["bvh", "embree"], set={"bvh.layout": "bvh4"}, threads=1)
    assert list(info["accelerators"]) == ["bvh", "embree"]
    assert info["threads"] == 1
    assert "geometry" not in info
    assert info["triangles"] == prism.load_scene(path)["triangles"]
    bvh = info["accelerators"]["bvh"]
    assert set(bvh) == {"build_ms", "nodes", "leaves", "max_depth", "bytes",
                        "bytes_per_primitive", "sah_cost"}
    # The structure (not the time) is the command line's.
    result = run_prism("info", path, "--accel", "bvh", "--set", "bvh.layout=bvh4", "-t", 1)
    row = [line.split() for line in result.stdout.splitlines() if line.startswith("  bvh")][0]
    assert [int(x) for x in row[2:6]] == [bvh["nodes"], bvh["leaves"], bvh["max_depth"],
                                          bvh["bytes"]]
    assert set(prism.info(path, accel="brute")["accelerators"]) == {"brute"}
    assert list(prism.info(path)["accelerators"]) == prism.accelerators()

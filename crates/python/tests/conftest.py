"""Shared fixtures of the Python package's tests: the repository, the command-line binary the
package is checked against (``$PROPBET_BIN``, else target/release/propbet), and a runner."""

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def cli(repo):
    """Runs the ``propbet`` binary from the repository root; returns its exit status."""
    binary = Path(os.environ.get("PROPBET_BIN", repo / "target" / "release" / "propbet"))
    assert binary.is_file(), f"{binary}: build the binary first (cargo build --release -p propbet-cli)"

    def run(*argv, ok=(0, 1)):
        done = subprocess.run([str(binary), *map(str, argv)], cwd=repo, capture_output=True, text=True)
        assert done.returncode in ok, f"propbet {' '.join(map(str, argv))}: exit {done.returncode}\n{done.stderr}"
        return done.returncode

    return run


@pytest.fixture(autouse=True)
def at_repo(repo, monkeypatch):
    """Every test runs from the repository root, as the command-line tests do."""
    monkeypatch.chdir(repo)

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


def written(table):
    """A DataFrame's cells as propbet's CSV files write them: numbers to 7 significant digits
    (the binary's own formatter), empty where a number is NaN."""
    import math

    import propbet

    cells = {}
    for name in table.columns:
        col = table[name]
        if col.dtype.kind == "f":
            cells[name] = ["" if math.isnan(v) else propbet._native.format_number(v) for v in col]
        elif col.dtype.kind == "b":
            cells[name] = ["true" if v else "false" for v in col]
        else:
            cells[name] = [str(v) for v in col]
    return cells


def file_cells(path):
    """A CSV file's cells as text."""
    import pandas as pd

    t = pd.read_csv(path, dtype=str, keep_default_na=False)
    return {name: list(t[name]) for name in t.columns}


@pytest.fixture(scope="session")
def same_as_file():
    """Asserts that a DataFrame is a CSV file of propbet's to the last digit written: the same
    columns in the same order, every cell the same text."""

    def check(table, path):
        import propbet

        # The package's names of the file's columns (`flags` is `point_flags`).
        expected = {propbet.column_name(k): v for k, v in file_cells(path).items()}
        assert list(table.columns) == list(expected), f"{path}: columns"
        got = written(table)
        for name in expected:
            diff = [(i, a, b) for i, (a, b) in enumerate(zip(got[name], expected[name])) if a != b]
            assert not diff and len(got[name]) == len(expected[name]), f"{path}: {name}: {diff[:5]}"

    return check

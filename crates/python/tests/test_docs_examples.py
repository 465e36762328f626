"""The book's Python examples (docs/python/*.py, included in docs/python.md) run as a reader
would run them, from the repository root."""

import subprocess
import sys


def run(*argv, cwd):
    done = subprocess.run([sys.executable, *map(str, argv)], cwd=cwd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_thrust_stand_example_draws_its_figure(repo, tmp_path):
    out = run("docs/python/thrust_stand.py", tmp_path / "figure.png", cwd=repo)
    assert "11 steady points" in out and "thrust: mean error" in out
    png = (tmp_path / "figure.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20_000


def test_the_dask_example_validates_two_props_on_two_workers(repo):
    out = run("docs/python/validate_dask.py", cwd=repo)
    # The workers' own output (each validate prints its table) comes first; the gathered table last.
    lines = out.strip().splitlines()[-3:]
    assert lines[0].split() == ["prop", "points", "ct_median", "cp_median"]
    rows = {l.split()[0]: l.split() for l in lines[1:]}
    assert set(rows) == {"apcsf_9x4.7", "gwsdd_9x5"}
    assert all(0 < float(r[2]) < 0.5 for r in rows.values())


def test_the_readmes_python_example_runs(repo, tmp_path):
    text = (repo / "README.md").read_text()
    block = text.split("```python\n", 1)[1].split("```", 1)[0]
    (tmp_path / "readme.py").write_text(block)
    out = run(tmp_path / "readme.py", cwd=repo)
    assert "torque-tare" in out


def test_the_motor_example_answers_the_three_questions(repo):
    out = run("docs/python/motor.py", cwd=repo)
    assert "hover at 1.5 N:" in out and "held-out current error" in out
    assert "apcsf_10x4.7.qprop" in out and "Most grams per watt at hover" in out

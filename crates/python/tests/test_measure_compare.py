"""Measurements, comparison, diagnosis and validation from Python, checked against the command
line's files for the same input."""

import json

import pandas as pd
import pytest

import propbet

PHOTO = "props/photofoil_8x4.5"
LOG = f"{PHOTO}/StepsTestV2_2022-01-18_153833.csv"
TARE = "tests/data/hidden_effects/torque_tare"


def read(path):
    return propbet._csv(open(path, "rb").read())


def test_read_measurements_gives_the_points_compare_scores(cli, tmp_path):
    points = propbet.read_measurements(LOG)
    cli("compare", "--prop", f"{PHOTO}/QProp_8x4_5.txt", "--measured", LOG, "--rho", "1.1648", "--out", tmp_path)
    compared = read(tmp_path / "points.csv")
    assert len(points) == len(compared) > 10
    for col in ["rpm", "thrust_n", "torque_nm", "line_first", "line_last"]:
        pd.testing.assert_series_equal(points[col], compared[col], check_exact=True)
    assert set(points.format) == {"rc_benchmark"}
    dropped = points.attrs["dropped"]
    assert list(dropped.columns) == ["file", "line", "reason", "detail"]


def test_read_measurements_of_uiuc_files_give_coefficients():
    files = [f"props/apcsf_10x4.7/uiuc/apcsf_10x4.7_static_kt0835.txt", "props/apcsf_10x4.7/uiuc/apcsf_10x4.7_kt0836_4014.txt"]
    points = propbet.read_measurements(files)
    assert set(points.file) == set(files)
    sweep = points[points.file == files[1]]
    assert sweep.j.notna().all() and sweep.ct.notna().all() and sweep.thrust_n.isna().all()


def test_compare_is_the_command_lines(cli, tmp_path):
    prop = propbet.Prop.from_qprop(f"{PHOTO}/QProp_8x4_5.txt")
    result = propbet.compare(prop, LOG, out=tmp_path / "py", rho=1.1648)
    cli("compare", "--prop", f"{PHOTO}/QProp_8x4_5.txt", "--measured", LOG, "--rho", "1.1648", "--out", tmp_path / "cli")
    pd.testing.assert_frame_equal(result.points, read(tmp_path / "cli" / "points.csv"), check_exact=True)
    expected = json.loads((tmp_path / "cli" / "metrics.json").read_text())
    # The same but for the output folder in the command it records.
    assert result.metrics["command"].replace(str(tmp_path / "py"), str(tmp_path / "cli")) == expected.pop("command")
    assert {k: v for k, v in result.metrics.items() if k != "command"} == expected
    metrics, points = result
    assert metrics is result.metrics and result.report.is_file()
    assert points.thrust_pred.notna().all()


def test_diagnose_finds_the_hidden_torque_tare(cli, tmp_path):
    found = propbet.diagnose(f"{TARE}/cam6x3.qprop", f"{TARE}/cam6x3_steps.csv", out=tmp_path / "py")
    cli("diagnose", "--prop", f"{TARE}/cam6x3.qprop", "--measured", f"{TARE}/cam6x3_steps.csv", "--out", tmp_path / "cli")
    expected = json.loads((tmp_path / "cli" / "diagnosis.json").read_text())
    assert found.effects == expected["final_effects"]
    assert found.effects[0].startswith("torque-tare")
    assert "torque-tare" in found.answer
    assert list(found.ladder.added)[:2] == ["baseline", "torque-tare"]
    assert found.ranking.id.iloc[0] == "torque-tare"
    assert found.report.is_file() and found.ok


def test_validate_is_the_command_lines(cli, tmp_path):
    data = dict(uiuc="tests/data/validate/uiuc", pe0="tests/data/validate/pe0", airfoils="props/airfoils")
    result = propbet.validate(**data, out=tmp_path / "py", only=["apcsf_9x4.7"], engine="neuralfoil", quiet=True)
    cli("validate", "--uiuc", data["uiuc"], "--pe0", data["pe0"], "--airfoils", data["airfoils"], "--only",
        "apcsf_9x4.7", "--engine", "neuralfoil", "--quiet", "-o", tmp_path / "cli")
    pd.testing.assert_frame_equal(result.table, read(tmp_path / "cli" / "validation.csv"), check_exact=True)
    assert list(result.table.prop) == ["apcsf_9x4.7"]
    assert "median error" in result.markdown and result.report.is_file()


def test_a_scan_gives_a_prop(cli, tmp_path):
    stl = "props/apcsf_10x4.7/apcsf_10x4.7.stl"
    prop = propbet.Prop.from_scan(stl, out=tmp_path / "py", units="mm", stations="0.3:0.9/5")
    cli("scan", stl, "--units", "mm", "--stations", "0.3:0.9/5", "-o", tmp_path / "cli")
    assert prop.path.read_text() == (tmp_path / "cli" / "prop.qprop").read_text()
    st = prop.stations
    assert len(st) == 5 and st.r_over_tip.between(0.29, 0.91).all()


def test_read_measurements_of_a_generic_csv_with_a_column_map(tmp_path):
    (tmp_path / "map.toml").write_text(
        'rpm = { column = "Motor speed", unit = "rpm" }\n'
        'thrust = { column = "Pull", unit = "N" }\n'
        'torque = { column = "Q", unit = "N m" }\n'
    )
    points = propbet.read_measurements("tests/data/bad_inputs/colmap_gen.csv", columns=tmp_path / "map.toml")
    assert list(points.rpm[:2]) == [3000, 4000]
    assert list(points.thrust_n[:2]) == [0.01, 0.02] and list(points.torque_nm[:2]) == [0.002, 0.004]
    generic = propbet.read_measurements("tests/data/hidden_effects/no_effect/cam6x3_tunnel.csv")
    assert generic.v_m_s.max() > 0 and (generic.temperature_k == 288.15).all()


def test_an_error_is_the_command_lines_message(repo):
    import os
    import subprocess

    binary = os.environ.get("PROPBET_BIN", str(repo / "target" / "release" / "propbet"))
    argv = ["compare", "--prop", "props/cam6x3/cam6x3.qprop", "--measured", "tests/data/bad_inputs/stand_thrust_1e308.csv",
            "--out", "unused"]
    done = subprocess.run([binary, *argv], capture_output=True, text=True)
    assert done.returncode == 2
    with pytest.raises(propbet.InputError) as e:
        propbet.execute(*argv)
    assert done.stderr.strip() == f"propbet: error: {e.value}"


def test_read_measurements_of_every_stand_format_and_a_batch_match_compare(cli, tmp_path):
    """Tyto's Flight Stand (two powertrains, sparse rows), its database table, a Latin-1
    CR-only re-save and a file that cannot be read, in one batch: the points compare scores,
    the refused file in the dropped table."""
    stand = "tests/data/thrust_stand"
    latin = tmp_path / "resaved.csv"
    text = open(f"{stand}/series1580_gf_steps.csv", encoding="utf-8-sig").read()
    latin.write_bytes(text.replace("\n", "\r").encode("latin-1"))
    bad = tmp_path / "bad.csv"
    bad.write_text("Time (s),ESC signal (µs),Thrust (N),Motor Optical Speed (RPM)\n0,1000,0.1,0\n0.1,1000,0.1,0\n")
    files = [f"{stand}/flight_stand_two_powertrains.csv", f"{stand}/tyto_database.csv", str(latin), str(bad)]
    points = propbet.read_measurements(files)
    cli("compare", "--prop", "props/apcsf_10x4.7/apcsf_10x4.7.qprop", "--measured", *files, "--out", tmp_path / "out", ok=(0, 1))
    compared = read(tmp_path / "out" / "points.csv")
    assert len(points) == len(compared) > 20
    for col in ["file", "rpm", "thrust_n", "torque_nm", "line_first", "line_last"]:
        pd.testing.assert_series_equal(points[col], compared[col], check_exact=True)
    assert set(points.format) == {"flight_stand", "tyto_database", "rc_benchmark"}
    assert (points.thrust_samples < points.samples).any(), "sparse rows counted"
    dropped = points.attrs["dropped"]
    refused = dropped[dropped.reason == "file_refused"]
    assert list(refused.file) == [str(bad)] and refused.line.isna().all()

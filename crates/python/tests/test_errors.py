"""Bad input from Python: a Python exception naming the value, never a crash. The inputs that
broke propbet (tests/data/bad_inputs, from ../shared/examples/bad_inputs) run through the
package in this interpreter: each is refused with `propbet.InputError` or done (True/False),
and no Rust panic reaches the interpreter (`propbet.InternalError` would say one did)."""

import numpy as np
import pytest

import propbet

CAM = "props/cam6x3/cam6x3.qprop"
B = "tests/data/bad_inputs"
H = "tests/data/hidden_effects/torque_tare"
APC = "props/apcsf_10x4.7/apcsf_10x4.7.qprop"


def test_a_missing_file_is_named():
    with pytest.raises(propbet.InputError, match="no_such.qprop"):
        propbet.Prop.from_qprop("no_such.qprop")


def test_a_wrong_unit_is_named():
    with pytest.raises(propbet.InputError, match="furlong"):
        propbet.Prop.from_qprop(CAM, units="furlong")
    with pytest.raises(propbet.InputError, match="'20 Kelvins'"):
        propbet.Prop.from_qprop(CAM).predict(rpm=4000, air={"temp": "20 Kelvins", "pressure": "101325"})


def test_a_nan_in_an_array_is_named():
    prop = propbet.Prop.from_qprop(CAM)
    with pytest.raises(propbet.InputError, match=r"j\[2\] = nan"):
        prop.predict(rpm=4000, j=np.array([0.0, 0.1, np.nan]))
    with pytest.raises(propbet.InputError, match=r"rpm = inf"):
        prop.predict(rpm=float("inf"))


def test_an_unknown_option_or_air_key_is_named():
    with pytest.raises(TypeError, match="unexpected keyword argument 'bogus'"):
        propbet.compare(CAM, f"{H}/cam6x3_steps.csv", bogus=3)
    with pytest.raises(propbet.InputError, match="'density'"):
        propbet.Prop.from_qprop(CAM).predict(rpm=4000, air={"density": 1.2})


def test_a_value_out_of_range_is_the_command_lines_message():
    with pytest.raises(propbet.InputError, match="--rpm"):
        propbet.Prop.from_qprop(CAM).predict(rpm=-5)


# The commands of ../shared/examples/bad_inputs/README.md that need neither a fake XFOIL nor a
# signal, as the package runs them (O: an output folder).
BAD = [
    ["predict", "--prop", f"{B}/prop_R_metres_stations_cm.qprop", "--rpm", "8000", "--v", "5"],
    ["predict", "--prop", f"{B}/prop_R_metres_stations_cm.qprop", "--rpm", "8000", "--v", "5", "--qprop-compat"],
    ["scan", f"{B}/cloud_hang.ply", "--stations", "0.3:0.9/5", "-o", "O"],
    ["predict", "--prop", APC, "--polars", f"{B}/polars_alpha_reversed.json", "--rpm", "5000", "--v", "0,5"],
    ["compare", "--prop", APC, "--measured", f"{B}/uiuc_static_inf_hang.txt", "--out", "O"],
    ["diagnose", "--prop", APC, "--measured", f"{B}/uiuc_sweep_1e308_kt0000_4014.txt", "--out", "O"],
    ["compare", "--prop", CAM, "--measured", f"{B}/stand_thrust_1e308.csv", "--out", "O"],
    ["compare", "--prop", CAM, "--measured", f"{B}/stand_duplicated_header.csv", "--out", "O"],
    ["run", f"{B}/run_huge_grid", "-o", "O"],
    ["predict", "--prop", CAM, "--rpm", "1000:20000/100000", "--j", "0:1/100000"],
    ["--threads", "1", "diagnose", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{B}/diag_pressure_1e200.csv", "-o", "O"],
    ["--threads", "4000", "predict", "--prop", CAM, "--rpm", "4000"],
    ["predict", "--prop", CAM, "--rpm", "1e-300", "--j", "0,0.3"],
    ["run", f"{B}/case_sweep_tiny_rpm", "-o", "O"],
    ["compare", "--prop", APC, "--measured", f"{B}/uiuc_tiny_rpm_static_kt0000.txt", "--out", "O"],
    ["compare", "--prop", CAM, "--measured", f"{B}/stand_pressure_zero.csv", "--rho", "1e-310", "-o", "O"],
    ["compare", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{B}/stand_pressure_zero.csv", "-o", "O"],
    ["compare", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{B}/stand_pressure_in_hpa.csv", "-o", "O"],
    ["compare", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{B}/stand_temp_minus300C.csv", "-o", "O"],
    ["compare", "--prop", APC, "--measured", f"{B}/uiuc_zero_ct_kt0000_4014.txt", "-o", "O"],
    ["compare", "--prop", APC, "--measured", "props/apcsf_10x4.7/uiuc/apcsf_10x4.7_kt0836_4014.txt",
     "--per3", f"{B}/per3_ct_1e308.dat", "-o", "O"],
    ["scan", "props/apcsf_10x4.7/apcsf_10x4.7.stl", "--stations", "0.3:0.9/5", "--reference", f"{B}/geom_zero_chord.txt", "-o", "O"],
    ["prop", f"{B}/prop_close_stations.qprop"],
    ["predict", "--prop", f"{B}/prop_closer_stations.qprop", "--rpm", "8000", "--v", "5"],
    ["predict", "--prop", CAM, "--rpm", "3000", "--v", "0,6", "--user-effects", f"{B}/fx_v_times_1e300.toml", "--effect", "fx"],
    ["predict", "--prop", CAM, "--rpm", "3000", "--v", "0,6", "--user-effects", f"{B}/fx_rpm_times_1e6.toml", "--effect", "fx"],
    ["predict", "--prop", CAM, "--rpm", "3000", "--v", "0,6", "--user-effects", f"{B}/fx_rho_negative.toml", "--effect", "fx"],
    ["predict", "--prop", CAM, "--rpm", "3000", "--v", "0,6", "--user-effects", f"{B}/fx_chord_sqrt_inboard.toml", "--effect", "fx"],
    ["compare", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{B}/stand_short_row.csv", "-o", "O"],
    ["compare", "--prop", CAM, "--measured", f"{B}/colmap_gen.csv", "--columns", f"{B}/colmap_same_column.toml", "-o", "O"],
    ["compare", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{B}/stand_thrust_no_unit.csv", "-o", "O"],
    ["diagnose", "--prop", f"{H}/cam6x3.qprop", "--measured", f"{H}/cam6x3_steps.csv", "--user-effects",
     f"{B}/fx_param_scale_zero.toml", "--effects", "fx", "-o", "O"],
    ["predict", "--prop", CAM, "--rpm", "4000", "--rho", "1e300"],
    ["predict", "--prop", CAM, "--rpm", "4000", "--effect", "pitch-offset:deg=1e308"],
    ["prop", f"{B}/prop_title_ansi.qprop"],
    ["run", f"{B}/case_name_ansi", "-o", "O"],
    ["predict", "--prop", "/dev/zero", "--rpm", "4000"],
]


@pytest.mark.parametrize("argv", BAD, ids=[" ".join(a)[:60] for a in BAD])
def test_the_inputs_that_broke_propbet_raise_or_finish(argv, tmp_path):
    argv = [str(tmp_path / "out") if a == "O" else a for a in argv]
    try:
        outcome = propbet.execute(*argv)
    except propbet.InputError as e:
        message = str(e)
        assert message and "panicked" not in message and len(message) < 4000, message
    else:
        assert outcome in (True, False)


def test_the_package_functions_refuse_them_too(tmp_path):
    with pytest.raises(propbet.InputError, match="polars_alpha_reversed.json"):
        propbet.Prop.from_qprop(APC, polars=f"{B}/polars_alpha_reversed.json").predict(rpm=5000, v=[0, 5])
    with pytest.raises(propbet.InputError):
        propbet.Prop.from_qprop(CAM).predict(rpm="1000:20000/100000", j="0:1/100000")
    with pytest.raises(propbet.InputError, match=r"stand_thrust_1e308.csv: no usable rows.*line 2: thrust"):
        propbet.read_measurements(f"{B}/stand_thrust_1e308.csv")


def test_propbets_warnings_are_python_warnings_and_its_messages_reach_sys_stderr(capsys, monkeypatch, caplog):
    """A notebook shows sys.stdout and sys.stderr, not the process's own: with
    ``propbet.verbose`` what propbet prints goes through them; without it, only to the
    ``propbet`` logger; its warnings are PropbetWarning either way."""
    with pytest.warns(propbet.PropbetWarning, match="QPROP 1.22 takes it unscaled"):
        propbet.Prop.from_qprop("props/photofoil_8x4.5/QProp_8x4_5.txt").predict(rpm=5000)
    args = ("props/photofoil_8x4.5/QProp_8x4_5.txt", "props/photofoil_8x4.5/StepsTestV2_2022-01-18_153833.csv")
    capsys.readouterr()
    with caplog.at_level("INFO", logger="propbet"):
        result = propbet.compare(*args, rho=1.1648)
    printed = capsys.readouterr()
    assert printed.out == "" and printed.err == "", printed
    assert any("12 rows -> 11 points" in r.getMessage() for r in caplog.records)
    monkeypatch.setattr(propbet, "verbose", True)
    result = propbet.compare(*args, rho=1.1648)
    printed = capsys.readouterr()
    assert f"report: {result.report}" in printed.out
    assert "12 rows -> 11 points" in printed.err


def test_calls_leave_no_files_behind_unless_given_out(tmp_path, monkeypatch):
    """A call without ``out=`` writes into a temporary folder that goes with the object it
    returned; with ``out=`` the files stay."""
    import gc

    monkeypatch.setattr(propbet.tempfile, "tempdir", str(tmp_path))
    args = ("props/photofoil_8x4.5/QProp_8x4_5.txt", "props/photofoil_8x4.5/StepsTestV2_2022-01-18_153833.csv")
    result = propbet.compare(*args, rho=1.1648)
    folder = result.folder
    assert folder.parent == tmp_path and result.report.is_file()
    del result
    gc.collect()
    assert not folder.exists() and list(tmp_path.iterdir()) == []
    kept = propbet.compare(*args, rho=1.1648, out=tmp_path / "kept")
    del kept
    gc.collect()
    assert (tmp_path / "kept" / "report.html").is_file()


def test_a_column_pandas_owns_is_renamed():
    sweep = propbet.Prop.from_qprop("props/cam6x3/cam6x3.qprop").predict(rpm=3000, j=[0, 0.5])
    assert "flags" not in sweep.columns and list(sweep.point_flags) == ["", ""]
    assert propbet.column_name("flags") == "point_flags" and propbet.column_name("ct") == "ct"


def test_keywords_are_checked_at_the_call_with_pythons_own_exceptions():
    """A misspelt or mistyped keyword fails where it is written, naming it; sub-zero air and a
    negative number reach propbet as values, not as flags."""
    with pytest.raises(TypeError, match="unexpected keyword argument 'bogus'"):
        propbet.Prop.from_qprop(CAM, bogus=1)
    with pytest.raises(TypeError, match=r"'dbeta'"):
        propbet.Prop.from_qprop(CAM, dbeta="x")
    with pytest.raises(TypeError, match=r"'effects'"):
        propbet.Prop.from_qprop(CAM, effects=5)
    prop = propbet.Prop.from_qprop(CAM)
    with pytest.raises(TypeError, match=r"'band'"):
        prop.predict(5000, band="yes")
    with pytest.raises(TypeError, match=r"rpm\[1\] = 'x': not a number"):
        prop.predict([5000, "x"])
    with pytest.raises(TypeError, match="unknown field `stationz`"):
        propbet.Prop.from_scan("props/apcsf_10x4.7/apcsf_10x4.7.stl", units="mm", stationz="0.3:0.9/5")
    with pytest.raises(TypeError, match="unexpected keyword argument 'verbos'"):
        propbet.run("props/cam6x3", verbos=True)
    cold = prop.predict(5000, air={"temp": "-10C", "pressure": "101325Pa"})
    warm = prop.predict(5000, air={"temp": "30C", "pressure": "101325Pa"})
    assert cold.thrust_n[0] > warm.thrust_n[0]
    with pytest.raises(propbet.InputError, match=r"--drag-factor -1: the sections' drag multiplier"):
        propbet.Prop.from_qprop(CAM, drag_factor=-1).predict(5000)

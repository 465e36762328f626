"""The prop, its stations, its polars and its predictions, checked against the command line's
files for the same input: the same columns and every cell to the last digit written."""

import threading
import time

import numpy as np
import pandas as pd
import pytest

import propbet

CAM = "props/cam6x3/cam6x3.qprop"


def read(path):
    return propbet._csv(open(path, "rb").read())


def test_predict_is_the_command_lines_table(cli, tmp_path, same_as_file):
    prop = propbet.Prop.from_qprop(CAM)
    j = np.arange(0, 0.61, 0.05)
    sweep = prop.predict(rpm=[4000, 6000], j=j, air={"temp": "25C", "pressure": "98000", "humidity": 40})
    cli("predict", "--prop", CAM, "--rpm", "4000,6000", "--j", ",".join(repr(float(x)) for x in j),
        "--temp", "25C", "--pressure", "98000", "--humidity", "40", "-o", tmp_path / "sweep.csv")
    assert len(sweep) == 26
    same_as_file(sweep, tmp_path / "sweep.csv")
    # Each number is the one the file's digits say, so the rows can be picked by their RPM.
    numbers = sweep.select_dtypes("number").columns
    pd.testing.assert_frame_equal(sweep[numbers], read(tmp_path / "sweep.csv")[numbers], check_exact=True, check_dtype=False)
    assert sweep[sweep.rpm == 4000].shape[0] == 13
    # And the numbers are a prediction: thrust grows with RPM, falls with J.
    static = sweep[sweep.j == 0].set_index("rpm").thrust_n
    assert static[6000] > 2 * static[4000]
    assert sweep[sweep.rpm == 6000].thrust_n.is_monotonic_decreasing


def test_predict_with_the_band_stations_and_effects(cli, tmp_path, same_as_file):
    prop = propbet.Prop.from_qprop(CAM)
    sweep, stations = prop.predict(rpm=5000, v=[0, 5], band=True, stations=True, effects=["pitch-offset:deg=1"])
    cli("predict", "--prop", CAM, "--rpm", "5000", "--v", "0,5", "--band", "--effect", "pitch-offset:deg=1",
        "-o", tmp_path / "s.csv", "--out-stations", tmp_path / "st.csv")
    same_as_file(sweep, tmp_path / "s.csv")
    same_as_file(stations, tmp_path / "st.csv")
    assert (sweep.ct_lo < sweep.ct).all() and (sweep.ct < sweep.ct_hi).all()
    assert len(stations) == 2 * 25


def test_stations_are_the_files_rows_in_si():
    st = propbet.Prop.from_qprop(CAM).stations
    assert list(st.columns[:4]) == ["r_m", "r_over_tip", "chord_m", "beta_deg"]
    # cam6x3.qprop: Rfac 0.0254 (inches); its first row is r = 0.75 in, beta 27.5 deg.
    assert st.r_m[0] == pytest.approx(0.75 * 0.0254, rel=1e-6)
    assert st.beta_deg[0] == 27.5
    assert st.r_over_tip.iloc[-1] == 1.0
    assert len(st) == 7


def test_the_case_model_predicts_what_run_writes(tmp_path, same_as_file):
    """A case's model from Python sweeps the case's points to the same table as `propbet run`."""
    prop = propbet.Prop.from_case("props/apcsf_10x4.7", out=tmp_path / "case")
    assert prop.polars_file is not None and prop.polars_file.is_file()
    result = propbet.run("props/apcsf_10x4.7", out=tmp_path / "run")
    assert result.summary["case"] == "APC 10x4.7 Slow Flyer"
    assert result.ok  # its polars' notes are no problems: exit status 0
    sweep = prop.predict(band=True)
    same_as_file(sweep, result.folder / "predict" / "sweep.csv")
    assert result.report.is_file() and result.diagnosis["final_effects"]


def test_polars_with_neuralfoil_give_a_tabulated_model(cli, tmp_path):
    geometry = "props/apcsf_10x4.7/apcsf_10x4.7_geometry.qprop"
    prop = propbet.Prop.from_qprop(geometry)
    tabulated = prop.polars(rpm=[4000, 6000], j=[0, 0.3, 0.6], engine="neuralfoil",
                            airfoil="props/airfoils/e63.dat", out=tmp_path / "py")
    cli("polars", "--geometry", geometry, "--airfoil", "props/airfoils/e63.dat", "--rpm", "4000,6000",
        "--j", "0,0.3,0.6", "--engine", "neuralfoil", "--out-prop", tmp_path / "cli.qprop",
        "--out-polars", tmp_path / "cli.json")
    assert (tmp_path / "py" / "prop.qprop").read_text() == (tmp_path / "cli.qprop").read_text()
    a = tabulated.predict(rpm=5000, j=[0, 0.3])
    b = propbet.Prop.from_qprop(tmp_path / "cli.qprop", polars=tmp_path / "cli.json").predict(rpm=5000, j=[0, 0.3])
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    plain = prop.predict(rpm=5000, j=[0, 0.3])
    assert not np.allclose(a.ct, plain.ct)  # the tables, not the file's coefficients


def test_the_gil_is_released_while_propbet_computes():
    """While a 100,000-point sweep runs in another thread, this one keeps running Python."""
    model = propbet._native.Model(CAM)
    ticks = 0
    done = threading.Event()

    def sweep():
        try:
            propbet._native.predict(model, "2000:9000/500", "0:0.6/200")
        finally:
            done.set()

    worker = threading.Thread(target=sweep)
    started = time.perf_counter()
    worker.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0)
    worker.join()
    elapsed = time.perf_counter() - started
    assert elapsed > 0.02, elapsed
    # Held, the GIL would leave this loop a handful of turns before the call; released, it turns
    # every few microseconds for the whole sweep.
    assert ticks > 100, f"{ticks} turns in {elapsed:.3f} s: the GIL was held"


def test_the_propeller_you_own_from_apcs_design_file(cli, tmp_path, same_as_file):
    """APC's PE0 file as it is: the same table as the command line's."""
    pe0 = "props/apcsp_10x7/10x7-PERF.PE0"
    prop = propbet.Prop.from_file(pe0, engine="neuralfoil")
    assert len(prop.stations) == 17
    sweep = prop.predict(rpm=5000, j=[0, 0.2, 0.4, 0.6])
    cli("predict", "--prop", pe0, "--engine", "neuralfoil", "--rpm", "5000", "--j", "0,0.2,0.4,0.6", "-o", tmp_path / "s.csv")
    same_as_file(sweep, tmp_path / "s.csv")
    assert sweep.ct.is_monotonic_decreasing and sweep.ct.iloc[0] > 0.1


def test_the_expected_accuracy_of_a_family_and_of_a_maker_never_validated():
    sport = propbet.expected_accuracy("10x7-PERF.PE0")
    assert sport["group"] == "APC Sport" and sport["props"] >= 3
    assert 0 < sport["ct_median"] < 0.5 and 0 < sport["band_ct_inside"] <= 1
    assert "APC Sport props" in sport["sentence"]
    scan = propbet.expected_accuracy(None)
    assert scan["group"] is None and scan["props"] is None
    assert "no prop of this maker line" in scan["sentence"]

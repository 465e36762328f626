"""The motor, the battery, the fit and propellers side by side from Python: the same tables as
the command line's files for the same input, every cell to the last digit written."""

import pytest

import propbet

CAM = "props/cam6x3/cam6x3.qprop"
PHOTO = "props/photofoil_8x4.5/QProp_8x4_5.txt"
APC = "props/apcsf_10x4.7/apcsf_10x4.7.qprop"
AXI = "props/motors/axi2204-54.motor"
LOG = "props/photofoil_8x4.5/StepsTestV2_2022-01-18_153833.csv"


def test_a_motor_file_and_a_motor_of_constants():
    axi = propbet.Motor.from_file(AXI)
    assert axi.kind == 1 and len(axi.params) == 3
    assert (axi.r, axi.io, axi.kv) == tuple(axi.params)
    made = propbet.Motor(axi.r, axi.io, axi.kv, name="copy")
    lines = [x.strip() for x in made.text().splitlines() if x.strip()]
    assert lines[0] == "copy" and lines[1].startswith("1")
    assert [float(x.split()[0]) for x in lines[2:5]] == axi.params
    with pytest.raises(propbet.InputError, match="R"):
        propbet.Motor(-0.1, 0.5, 1400)
    with pytest.raises(propbet.InputError, match="no_such.motor"):
        propbet.Motor.from_file("no_such.motor")


def test_predict_on_a_motor_with_stations_is_the_command_lines_pair(cli, tmp_path, same_as_file):
    prop = propbet.Prop.from_qprop(CAM)
    axi = propbet.Motor.from_file(AXI)
    table, stations = prop.predict(motor=axi, volts=[6, 8], v=[0, 5], stations=True)
    cli("predict", "--prop", CAM, "--motor", AXI, "--volts", "6,8", "--v", "0,5", "-o", tmp_path / "m.csv",
        "--out-stations", tmp_path / "s.csv")
    same_as_file(table, tmp_path / "m.csv")
    same_as_file(stations, tmp_path / "s.csv")
    assert len(stations) % len(table) == 0 and set(stations.rpm) == set(table.rpm)


def test_a_battery_and_its_bad_values():
    b = propbet.Battery("3S,2200mAh", esc_ohms=0.01)
    assert b.cells == 3 and b.capacity_mah == 2200 and b.volts == pytest.approx(11.1) and b.esc_ohms == 0.01
    with pytest.raises(propbet.InputError, match="--battery '3Q'"):
        propbet.Battery("3Q")
    with pytest.raises(propbet.InputError, match="--esc-ohms"):
        propbet.Battery("3S", esc_ohms=-1)


def test_predict_on_a_motor_is_the_command_lines_table(cli, tmp_path, same_as_file):
    prop = propbet.Prop.from_qprop(CAM)
    axi = propbet.Motor.from_file(AXI)
    table = prop.predict(motor=axi, volts=[6, 8, 10], v=[0, 5])
    cli("predict", "--prop", CAM, "--motor", AXI, "--volts", "6,8,10", "--v", "0,5", "-o", tmp_path / "m.csv")
    same_as_file(table, tmp_path / "m.csv")
    assert (table.amps > 0).all() and len(table) == 6
    # Hover on a battery: its throttle and minutes of flight, as the command line's.
    battery = propbet.Battery("3S,2200mAh")
    hover = prop.predict(motor=axi, thrust=1.0, battery=battery)
    cli("predict", "--prop", CAM, "--motor", AXI, "--thrust", "1", "--battery", "3S,2200mAh", "-o", tmp_path / "h.csv")
    same_as_file(hover, tmp_path / "h.csv")
    assert 0 < hover.throttle[0] < 1 and hover.endurance_min[0] > 0
    banded = prop.predict(motor=axi, volts=8, band=True)
    assert (banded.ct_lo < banded.ct).all() and (banded.ct < banded.ct_hi).all()
    full = prop.predict(motor=axi, throttle=[0.5, 1.0], battery=battery)
    assert full.thrust_n[1] > full.thrust_n[0] and full.battery_amps[1] > full.battery_amps[0]


def test_a_point_without_an_operating_point_is_a_warning_and_a_row():
    prop = propbet.Prop.from_qprop(CAM)
    axi = propbet.Motor.from_file(AXI)
    with pytest.warns(propbet.PropbetWarning):
        table = prop.predict(motor=axi, thrust=[1.0, 500.0])
    assert table.no_solution[0] == "" and table.no_solution[1] != ""
    with pytest.raises(propbet.InputError, match="give one of them"):
        prop.predict(motor=axi, volts=8, amps=5)
    with pytest.raises(propbet.InputError, match="--throttle: needs a battery"):
        prop.predict(motor=axi, throttle=0.5)
    with pytest.raises(propbet.InputError, match="give a motor"):
        prop.predict(rpm=5000, volts=8)


def test_the_fit_is_the_command_lines_file(cli, tmp_path):
    fitted = propbet.fit_motor(LOG, kv=1000)
    cli("motor", "fit", "--measured", LOG, "--kv", "1000", "-o", tmp_path / "f.motor")
    assert fitted.text == (tmp_path / "f.motor").read_text()
    assert fitted.kv == (1000.0, 0.0) and fitted.kv_from == "given"
    assert fitted.r[1] > 0 and fitted.held_out_median < 0.05
    assert len(fitted.steps) == 11 and fitted.steps.amps_held_out.notna().all()
    assert fitted.motor.kv == 1000 and fitted.motor.r == pytest.approx(fitted.r[0], rel=1e-9)
    assert fitted.kq is None and fitted.motor.kind == 1
    # A type 2 fit needs the motor's own current: this log stops below half throttle.
    with pytest.raises(propbet.InputError, match="a fit of Kq needs the ESC command"):
        propbet.fit_motor(LOG, kv=1000, kq=True)


def test_props_side_by_side_are_the_command_lines_table(cli, tmp_path, same_as_file):
    axi = propbet.Motor.from_file(AXI)
    table = propbet.compare_props([CAM, PHOTO, APC], axi, propbet.Battery("3S,2200mAh"), hover=2)
    cli("compare-props", CAM, PHOTO, APC, "--motor", AXI, "--battery", "3S,2200mAh", "--hover", "2", "-o", tmp_path / "side")
    same_as_file(table, tmp_path / "side" / "props.csv")
    assert list(table["rank_"]) == [1, 2, 3]  # `rank` is a DataFrame method
    assert any("Most grams per watt at hover" in a for a in table.attrs["answer"])


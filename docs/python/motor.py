"""Your motor and battery, and which propeller, from Python (the book's guide, page 4): the
same tables as `propbet predict --motor`, `propbet motor fit` and `propbet compare-props`.
Run from the repository root."""

import propbet

axi = propbet.Motor.from_file("props/motors/axi2204-54.motor")
battery = propbet.Battery("3S,2200mAh")
prop = propbet.Prop.from_qprop("props/cam6x3/cam6x3.qprop")

hover = prop.predict(motor=axi, thrust=1.5, battery=battery)
h = hover.iloc[0]
print(f"hover at 1.5 N: {h.throttle:.0%} throttle, {h.battery_amps:.2f} A, {h.g_per_w:.2f} g/W, {h.endurance_min:.0f} min")

fitted = propbet.fit_motor("props/photofoil_8x4.5/StepsTestV2_2022-01-18_153833.csv", kv=1000)
print(f"fitted: R {fitted.r[0]:.3f} ± {fitted.r[1]:.3f} ohm, Io {fitted.io[0]:.2f} ± {fitted.io[1]:.2f} A; "
      f"held-out current error {fitted.held_out_median:.1%}")

ranked = propbet.compare_props(
    ["props/cam6x3/cam6x3.qprop", "props/apcsf_10x4.7/apcsf_10x4.7.qprop"], axi, battery, hover=2
)
print(ranked[["rank_", "prop", "hover_g_per_w", "hover_battery_amps", "full_thrust_n"]].to_string(index=False))
print(ranked.attrs["answer"][0])

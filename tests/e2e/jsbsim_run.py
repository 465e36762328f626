"""Runs JSBSim (the Python package) on a propeller file propbet exported: a minimal aircraft of
one electric engine and that propeller, held at an airspeed, given a shaft power; JSBSim spins
the propeller up until the power it absorbs is the power given. Prints, per case, JSBSim's own
steady RPM, thrust [N], absorbed power [W], airspeed [m/s] and density [kg/m^3] as JSON.

Usage: python jsbsim_run.py ROOT PROPELLER '[[power_w, airspeed_m_s], ...]'
ROOT is a folder this script fills with aircraft/ and engine/; PROPELLER the exported XML.
"""
import json
import os
import shutil
import sys

import jsbsim

FT = 0.3048
LBF = 4.4482216152605
SLUG_FT3 = 515.378818
FTLB_S = 1.3558179483314
MAX_W = 20000.0

root, prop, cases = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
os.makedirs(os.path.join(root, "aircraft", "bench"), exist_ok=True)
os.makedirs(os.path.join(root, "engine"), exist_ok=True)
shutil.copy(prop, os.path.join(root, "engine", "prop.xml"))
with open(os.path.join(root, "engine", "motor.xml"), "w") as f:
    f.write(f'<?xml version="1.0"?>\n<electric_engine name="motor">\n'
            f'  <power unit="WATTS"> {MAX_W} </power>\n</electric_engine>\n')
# A heavy body with no aerodynamics: the airspeed stays where the initial condition puts it.
with open(os.path.join(root, "aircraft", "bench", "bench.xml"), "w") as f:
    f.write("""<?xml version="1.0"?>
<fdm_config name="bench" version="2.0" release="ALPHA">
  <metrics>
    <wingarea unit="FT2"> 1 </wingarea> <wingspan unit="FT"> 1 </wingspan> <chord unit="FT"> 1 </chord>
    <htailarea unit="FT2"> 0 </htailarea> <htailarm unit="FT"> 0 </htailarm>
    <vtailarea unit="FT2"> 0 </vtailarea> <vtailarm unit="FT"> 0 </vtailarm>
    <location name="AERORP" unit="IN"> <x>0</x> <y>0</y> <z>0</z> </location>
  </metrics>
  <mass_balance>
    <ixx unit="SLUG*FT2"> 1000 </ixx> <iyy unit="SLUG*FT2"> 1000 </iyy> <izz unit="SLUG*FT2"> 1000 </izz>
    <emptywt unit="LBS"> 1e6 </emptywt>
    <location name="CG" unit="IN"> <x>0</x> <y>0</y> <z>0</z> </location>
  </mass_balance>
  <ground_reactions>
    <contact type="STRUCTURE" name="C"> <location unit="IN"> <x>0</x> <y>0</y> <z>-100</z> </location>
      <static_friction> 0 </static_friction> <dynamic_friction> 0 </dynamic_friction>
      <spring_coeff unit="LBS/FT"> 1000 </spring_coeff> <damping_coeff unit="LBS/FT/SEC"> 100 </damping_coeff>
    </contact>
  </ground_reactions>
  <aerodynamics> <axis name="DRAG"> </axis> </aerodynamics>
  <propulsion>
    <engine file="motor">
      <thruster file="prop">
        <location unit="IN"> <x>0</x> <y>0</y> <z>0</z> </location>
        <orient unit="DEG"> <roll>0</roll> <pitch>0</pitch> <yaw>0</yaw> </orient>
      </thruster>
    </engine>
  </propulsion>
</fdm_config>
""")

out = []
for power, airspeed in cases:
    fdm = jsbsim.FGFDMExec(root)
    fdm.set_debug_level(0)
    if not fdm.load_model("bench"):
        sys.exit("JSBSim could not load the bench aircraft")
    fdm["ic/h-sl-ft"] = 1000.0
    fdm["ic/u-fps"] = airspeed / FT
    fdm.run_ic()
    fdm["propulsion/set-running"] = -1
    fdm.set_dt(1.0 / 2000.0)
    last, steady = -1.0, 0
    for step in range(200000):
        fdm["fcs/throttle-cmd-norm"] = power / MAX_W
        fdm.run()
        if step % 200 == 199:
            rpm = fdm["propulsion/engine/propeller-rpm"]
            steady = steady + 1 if abs(rpm - last) < 1e-4 * rpm else 0
            last = rpm
            if steady >= 5:
                break
    out.append({
        "rpm": fdm["propulsion/engine/propeller-rpm"],
        "thrust_n": fdm["propulsion/engine/thrust-lbs"] * LBF,
        "power_w": fdm["propulsion/engine/propeller-power-ftlbps"] * FTLB_S,
        "v_m_s": fdm["velocities/u-aero-fps"] * FT,
        "rho": fdm["atmosphere/rho-slugs_ft3"] * SLUG_FT3,
        "steady": steady >= 5,
    })
print(json.dumps(out))

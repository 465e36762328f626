#!/usr/bin/env python3
"""Tabulates validate runs side by side: validation_table.py NAME CSV [NAME CSV ...] (each CSV a
run's validation.csv); per-prop CT / CP medians and the medians over props, computed as validate does."""
import csv,sys
def q(v,p):
    v=sorted(v); import math
    return v[int(math.floor((len(v)-1)*p+0.5))]
props=['apce_10x5','apce_11x7','apcff_4.2x4','apcsf_10x4.7','apcsf_9x4.7','apcsp_10x6']
args=sys.argv[1:]
print('| candidate | ' + ' | '.join(f'{p} CT / CP' for p in props) + ' | median CT | median CP | median p90 CT | median p90 CP |')
print('|---|' + '---|'*(len(props)+4))
for name,f in zip(args[::2],args[1::2]):
    R={r['prop']:r for r in csv.DictReader(open(f))}
    cells=[f"{100*float(R[p]['ct_median']):.1f} / {100*float(R[p]['cp_median']):.1f} %" for p in props]
    med=lambda k: 100*q([float(R[p][k]) for p in props],.5)
    print(f"| {name} | " + ' | '.join(cells) + f" | {med('ct_median'):.1f} % | {med('cp_median'):.1f} % | {med('ct_p90'):.1f} % | {med('cp_p90'):.1f} % |")

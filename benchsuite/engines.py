#!/usr/bin/env python3
"""NeuralFoil against XFOIL, section by section: the polars of one blade made by each engine
(`propbet polars ... --out-polars`), compared where both have a point (XFOIL converged; the
NeuralFoil polar is incompressible, so its lift is taken to the XFOIL polar's Mach with
Prandtl-Glauert, as the tables do). Usage: engines.py NAME XFOIL_POLARS NEURALFOIL_POLARS.
Prints one markdown row: all common points, and those inside each station's working angles."""
import json
import math
import sys


def quantile(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(q * len(v)))] if v else float("nan")


name, xf, nf = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
both, working = [], []
for sx, sn in zip(xf["stations"], nf["stations"]):
    assert abs(sx["r"] - sn["r"]) < 1e-9, "the same blade"
    lo, hi = sx["alpha_range_deg"]
    by_re = {round(p["re"]): p for p in sn["polars"]}
    for px in sx["polars"]:
        pn = by_re.get(round(px["re"]))
        if pn is None:
            continue
        pg = 1.0 / math.sqrt(1.0 - px["mach"] ** 2)
        made_by_nf = {f["alpha_deg"] for f in px.get("neuralfoil", [])}
        at = {p["alpha_deg"]: p for p in pn["points"]}
        for p in px["points"]:
            q = at.get(p["alpha_deg"])
            if q is None or p["alpha_deg"] in made_by_nf:
                continue
            d = (q["cl"] * pg - p["cl"], q["cd"] / p["cd"] - 1.0)
            both.append(d)
            if lo <= p["alpha_deg"] <= hi:
                working.append(d)


def cells(v):
    dcl = [abs(a) for a, _ in v]
    dcd = [abs(b) for _, b in v]
    bias = quantile([b for _, b in v], 0.5)
    return (f"{len(v)} | {quantile(dcl, 0.5):.3f} / {quantile(dcl, 0.9):.3f} | "
            f"{100 * quantile(dcd, 0.5):.1f} / {100 * quantile(dcd, 0.9):.1f} % ({100 * bias:+.1f} %)")


print(f"| {name} | {cells(both)} | {cells(working)} |")

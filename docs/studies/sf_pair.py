#!/usr/bin/env python3
"""The two Slow Flyer props against each other: sf_pair.py NAME DIR [NAME DIR ...], each DIR a
validate output holding apcsf_9x4.7/ and apcsf_10x4.7/ (their compare/points.csv).

Each scored point of the 9x4.7 SF is matched with the 10x4.7 SF at the same J (linear in J
within the 10x4.7's J sweep nearest in RPM; a static point with the 10x4.7's static point
nearest in RPM). For a matched pair, d = (CT9/CT10 predicted) / (CT9/CT10 measured) - 1: how
far the model's thrust ratio of the two props is from the measured one. Whatever the model's
errors e9, e10 on the two points, (1 + e9) / (1 + e10) = 1 + d, so the larger of |e9|, |e10| is
at least about |d| / 2: a model that keeps this ratio cannot bring both props closer than that.
Printed per candidate: each prop's CT median error, the median of |d| over the matched points
(all, static, forward flight) and the ratio's median signed d by regime. The same for CP."""
import csv, math, sys


def q(v, p):
    v = sorted(v)
    return v[int(math.floor((len(v) - 1) * p + 0.5))]


def load(d, prop):
    """A prop's compared points inside validate's window: static points, and each J sweep's
    points below 0.85 of its measured zero-thrust J (linear between the last positive and the
    first non-positive CT), as `compare::metrics::in_window`."""
    rows = list(csv.DictReader(open(f"{d}/{prop}/compare/points.csv")))
    keep = []
    for f in sorted({r["file"] for r in rows}):
        pts = sorted((r for r in rows if r["file"] == f), key=lambda r: float(r["j"]))
        j0 = None
        for a, b in zip(pts, pts[1:]):
            ca, cb = float(a["ct"]), float(b["ct"])
            if ca > 0.0 >= cb:
                j0 = float(a["j"]) + ca / (ca - cb) * (float(b["j"]) - float(a["j"]))
                break
        keep += [r for r in pts if j0 is None or float(r["j"]) < 0.85 * j0]
    return keep


def matched(a, b, key):
    """(J, rpm, measured ratio, predicted ratio) for each point of a with its match in b."""
    out = []
    statics = [r for r in b if float(r["j"]) == 0.0]
    sweeps = [r for r in b if float(r["j"]) > 0.0]
    rpms = sorted({float(r["rpm"]) for r in sweeps})
    for r in a:
        j, rpm = float(r["j"]), float(r["rpm"])
        if j == 0.0:
            if not statics:
                continue
            m = min(statics, key=lambda s: abs(float(s["rpm"]) - rpm))
            mb, pb = float(m[key]), float(m[key + "_pred"])
        else:
            near = min(rpms, key=lambda x: abs(x - rpm))
            g = sorted((s for s in sweeps if abs(float(s["rpm"]) - near) < 1.0), key=lambda s: float(s["j"]))
            lo = [s for s in g if float(s["j"]) <= j]
            hi = [s for s in g if float(s["j"]) >= j]
            if not lo or not hi:
                continue
            s0, s1 = lo[-1], hi[0]
            j0, j1 = float(s0["j"]), float(s1["j"])
            t = 0.0 if j1 == j0 else (j - j0) / (j1 - j0)
            mb = float(s0[key]) * (1 - t) + float(s1[key]) * t
            pb = float(s0[key + "_pred"]) * (1 - t) + float(s1[key + "_pred"]) * t
        ma, pa = float(r[key]), float(r[key + "_pred"])
        if min(ma, mb) <= 0.0 or min(pa, pb) <= 0.0:
            continue
        out.append((j, rpm, ma / mb, pa / pb))
    return out


def main():
    args = sys.argv[1:]
    if not args or len(args) % 2:
        sys.exit(__doc__)
    print("| candidate | 9x4.7 CT / CP median | 10x4.7 CT / CP median | matched points | "
          "median \\|d\\|/2 CT / CP | static: median d CT / CP | forward: median d CT / CP | "
          "static CT rise predicted, 9x4.7 / 10x4.7 (measured +5.5 / +22.7 %) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, d in zip(args[::2], args[1::2]):
        a, b = load(d, "apcsf_9x4.7"), load(d, "apcsf_10x4.7")
        rel = lambda rows, k: q([abs(float(r[k + "_pred"]) / float(r[k]) - 1) for r in rows], 0.5) * 100
        cells = []
        ds = {}
        for key in ("ct", "cp"):
            m = matched(a, b, key)
            ds[key] = [(j, p / mr - 1) for j, _, mr, p in m]
        n = len(ds["ct"])
        half = " / ".join(f"{q([abs(x) / 2 for _, x in ds[k]], 0.5) * 100:.1f}" for k in ("ct", "cp"))
        st = " / ".join(f"{q([x for j, x in ds[k] if j == 0.0], 0.5) * 100:+.1f}" for k in ("ct", "cp"))
        fw = " / ".join(f"{q([x for j, x in ds[k] if j > 0.0], 0.5) * 100:+.1f}" for k in ("ct", "cp"))
        cells = [f"{rel(a, 'ct'):.1f} / {rel(a, 'cp'):.1f} %", f"{rel(b, 'ct'):.1f} / {rel(b, 'cp'):.1f} %",
                 str(n), f"{half} %", f"{st} %", f"{fw} %"]
        v = {r["prop"]: r for r in csv.DictReader(open(f"{d}/validation.csv"))}
        rise = lambda p: 100 * float(v[p]["static_ct_rise_predicted"])
        cells.append(f"+{rise('apcsf_9x4.7'):.1f} / +{rise('apcsf_10x4.7'):.1f} %")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()

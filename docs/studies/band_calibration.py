"""Calibrates the uncertainty band by cross-validation over props (docs/studies/uncertainty-band.md).

Reads one `propbet validate` run of the default model (each prop's `compare/band_sources.csv`:
CT and CP at every compared point and at each band source's two ends) and, optionally, runs of
alternative models (their `compare/points.csv`, the same points in the same order), and scores
band constructions by the share of measured CT and CP inside the band on props the band's scale
was not chosen on, and by its median half-width.

A construction is a set of sources: the stated ones (blade angle, chord, drag, the sections'
transition), and each alternative model as a one-sided source (the band reaches from the
prediction to the alternative's). Each side of the band is the root-sum-square of the sources'
moves that way, times a scale k. k is chosen on the training props (the smallest k on a grid
whose median-over-props coverage of CT and of CP both reach TARGET) and applied to the held-out
fold's props; the folds are validate's families dealt round-robin (cv_default.py's).

    python3 docs/studies/band_calibration.py DEFAULT_DIR [NAME=DIR ...]
"""

import csv
import itertools
import math
import os
import sys

import numpy as np

from cv_default import family, folds, median, pct

TARGET = float(os.environ.get("BAND_TARGET", "0.80"))
GRID = [0.5 + 0.05 * i for i in range(51)]  # k from 0.5 to 3.0


def read_points(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(x):
    return float(x) if x not in ("", None) else math.nan


def load(default_dir, alternatives):
    """Per prop: a list of scored points, each {q: (measured, predicted, [(down, up) per source])}
    for q in ct, cp; the stated sources first, then each alternative's."""
    props = {}
    for prop in sorted(os.listdir(default_dir)):
        f = os.path.join(default_dir, prop, "compare", "band_sources.csv")
        if not os.path.isfile(f) or family(prop) == "other":
            continue
        rows = read_points(f)
        sources = sorted({k.rsplit("_", 2)[0] for k in rows[0] if k.endswith("_ct_lo")})
        alt_rows = {}
        for name, d in alternatives:
            p = os.path.join(d, prop, "compare", "points.csv")
            if os.path.isfile(p):
                a = read_points(p)
                if len(a) == len(rows) and all(x["line_first"] == y["line_first"] for x, y in zip(a, rows)):
                    alt_rows[name] = a
        pts = []
        for i, r in enumerate(rows):
            if r["scored"] != "1":
                continue
            point = {}
            for q in ("ct", "cp"):
                c, m = num(r[f"{q}_pred"]), num(r[q])
                if not (math.isfinite(c) and math.isfinite(m) and c != 0):
                    break
                moves = {}
                for s in sources:
                    ends = [num(r[f"{s}_{q}_lo"]) - c, num(r[f"{s}_{q}_hi"]) - c]
                    ends = [e for e in ends if math.isfinite(e)]
                    moves[s] = (max([0.0] + [-e for e in ends]), max([0.0] + ends))
                for name, a in alt_rows.items():
                    e = num(a[i][f"{q}_pred"]) - c
                    moves[name] = (max(0.0, -e), max(0.0, e)) if math.isfinite(e) else (0.0, 0.0)
                point[q] = (m, c, moves)
            else:
                pts.append(point)
        props[prop] = pts
    return props


def choose_k(arr, names, n):
    """The smallest k on GRID whose band holds TARGET of CT and of CP (median over `names`)."""
    for k in GRID:
        s = cover_w(arr, names, np.full(n, k * k))
        if s["ct"][0] >= TARGET and s["cp"][0] >= TARGET:
            return k
    return GRID[-1]


def arrays(props, names, sources):
    """Per prop and quantity: measured, predicted, and the sources' down and up moves as arrays
    (points x sources)."""
    out = {}
    for p in names:
        out[p] = {}
        for q in ("ct", "cp"):
            pts = props[p]
            m = np.array([x[q][0] for x in pts])
            c = np.array([x[q][1] for x in pts])
            down = np.array([[x[q][2].get(s, (0.0, 0.0))[0] for s in sources] for x in pts])
            up = np.array([[x[q][2].get(s, (0.0, 0.0))[1] for s in sources] for x in pts])
            out[p][q] = (m, c, down ** 2, up ** 2)
    return out


def cover_w(arr, names, w2):
    """Median over props of the share inside and of the median half-width, per quantity, with
    each source's range times sqrt(w2)."""
    res = {}
    for q in ("ct", "cp"):
        ins, wid = [], []
        for p in names:
            m, c, d2, u2 = arr[p][q]
            down, up = np.sqrt(d2 @ w2), np.sqrt(u2 @ w2)
            ins.append(float(np.mean((m >= c - down) & (m <= c + up))))
            wid.append(float(median(list(0.5 * (up + down) / np.abs(c)))))
        res[q] = (median(ins), median(wid))
    return res


SCALES = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]


# Each source's scale within what its physics allows (the stated range times these), and the
# model-form level (its own error, in per cent of the prediction) from 0 to 14 %.
PHYSICAL = {"blade_angle": [0.5, 1.0, 1.5], "chord": [1.0, 5 / 3], "section_drag": [0.5, 1.0],
            "sections__transition": [0.5, 1.0], "level": [0, 2, 4, 6, 8, 10, 12, 14]}


def choose_w(arr, names, n, grid=None):
    """The per-source scales (each from SCALES, or `grid`'s per source) whose band is narrowest
    (CT's and CP's median half-widths summed) with both coverages at TARGET or more."""
    best = None
    for ks in itertools.product(*(grid or [SCALES] * n)):
        w2 = np.array(ks) ** 2
        r = cover_w(arr, names, w2)
        if r["ct"][0] >= TARGET and r["cp"][0] >= TARGET:
            width = r["ct"][1] + r["cp"][1]
            if best is None or width < best[0]:
                best = (width, ks)
    return best[1] if best else tuple([SCALES[-1]] * n)


def per_source(props, names, sources, label, physical=False):
    arr = arrays(props, names, sources)
    grid = None
    if physical:
        grid = [PHYSICAL.get(s, [0.0, 0.5, 1.0]) for s in sources]
    held, chosen = {}, []
    for test in folds(names):
        train = [p for p in names if p not in test]
        ks = choose_w(arr, train, len(sources), grid)
        chosen.append(ks)
        w2 = np.array(ks) ** 2
        for p in test:
            held[p] = cover_w(arr, [p], w2)
    h = {q: (median(held[p][q][0] for p in names), median(held[p][q][1] for p in names)) for q in ("ct", "cp")}
    ks_all = choose_w(arr, names, len(sources), grid)
    print(f"| {label}, each source's range scaled ({', '.join(sources)}) | folds chose "
          f"{'; '.join('/'.join(f'{k:g}' for k in ks) for ks in chosen)}; all props: {'/'.join(f'{k:g}' for k in ks_all)} | "
          f"{pct(h['ct'][0])} / {pct(h['ct'][1])} | {pct(h['cp'][0])} / {pct(h['cp'][1])} |")


def main(args):
    default_dir, alternatives = args[0], [a.split("=", 1) for a in args[1:]]
    props = load(default_dir, alternatives)
    stated = sorted({s for pts in props.values() for p in pts for s in p["ct"][2]} - {n for n, _ in alternatives})
    names = sorted(props)
    constructions = [("stated sources", stated)]
    for n, _ in alternatives:
        constructions.append((f"stated + {n}", stated + [n]))
    if len(alternatives) > 1:
        constructions.append(("stated + " + " + ".join(n for n, _ in alternatives), stated + [n for n, _ in alternatives]))
    print(f"{len(names)} props, {sum(len(v) for v in props.values())} scored points; target coverage {pct(TARGET)}\n")
    print("| construction | k = 1: CT inside / half-width | CP inside / half-width | k cross-validated (per fold) "
          "| held-out CT inside / half-width | CP inside / half-width | props with CT inside < 50 % |")
    print("|---|---|---|---|---|---|---|")
    held_all = {}
    for label, sources in constructions:
        arr, n = arrays(props, names, sources), len(sources)
        s1 = cover_w(arr, names, np.ones(n))
        ks, held = [], {}
        for test in folds(names):
            train = [p for p in names if p not in test]
            k = choose_k(arr, train, n)
            ks.append(k)
            for p in test:
                held[p] = cover_w(arr, [p], np.full(n, k * k))
        held_all[label] = held
        h = {q: (median(held[p][q][0] for p in names), median(held[p][q][1] for p in names)) for q in ("ct", "cp")}
        low = sum(held[p]["ct"][0] < 0.5 for p in names)
        print(f"| {label} | {pct(s1['ct'][0])} / {pct(s1['ct'][1])} | {pct(s1['cp'][0])} / {pct(s1['cp'][1])} | "
              f"{', '.join(f'{k:.2f}' for k in ks)} | {pct(h['ct'][0])} / {pct(h['ct'][1])} | "
              f"{pct(h['cp'][0])} / {pct(h['cp'][1])} | {low} |")
    print("\n| construction | scales chosen | held-out CT inside / half-width | CP inside / half-width |")
    print("|---|---|---|---|")
    for label, sources in constructions:
        per_source(props, names, sources, label)
    # The model-form level: a source moving the prediction by 1 % each way.
    for pts in props.values():
        for pt in pts:
            for q in ("ct", "cp"):
                pt[q][2]["level"] = (0.01 * abs(pt[q][1]), 0.01 * abs(pt[q][1]))
    for label, sources in constructions:
        per_source(props, names, sources + ["level"], label + " + model-form level, physical ranges", True)
    label = constructions[-1][0]
    print(f"\nBy family, held out ({label}):\n")
    print("| family | props | CT inside | CT half-width | CP inside | CP half-width |")
    print("|---|---|---|---|---|---|")
    held = held_all[label]
    for fam in sorted({family(p) for p in names}):
        fp = [p for p in names if family(p) == fam]
        row = [median(held[p][q][i] for p in fp) for q in ("ct", "cp") for i in (0, 1)]
        print(f"| {fam} | {len(fp)} | " + " | ".join(pct(x) for x in row) + " |")


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(__file__))
    main(sys.argv[1:])

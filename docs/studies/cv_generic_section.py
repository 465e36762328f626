"""Chooses the generic section (the airfoil a prop without its maker's sections gets) by nested
cross-validation over the other makers' props (docs/studies/other-makers.md).

Each candidate is one `propbet validate --generic-section CANDIDATE` run on the same props (its
validation.csv); only the props whose sections were assumed count. The props are dealt into
FOLDS folds stratified by maker line (the UIUC name's prefix: each line dealt round-robin, in
name order). In each fold the candidate with the lowest score on the other folds' props is
chosen and scored on the fold's props. The score is the mean of the median over props of the
CT median and of the CP median (validate's pure prediction, before any calibration); the tail
(p90 of a prop's larger median, props above 15 %, the worst line of 3 props or more) is printed
beside it.

    python3 docs/studies/cv_generic_section.py NAME=DIR [NAME=DIR ...]   (the first is the current default)
"""

import csv
import statistics
import sys

FOLDS = 5


def line(prop):
    return prop.split("_", 1)[0]


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {
        r["prop"]: (float(r["ct_median"]), float(r["cp_median"]))
        for r in rows
        if r["assumed_section"] and r["ct_median"] and r["cp_median"]
    }


def folds(props):
    out = [[] for _ in range(FOLDS)]
    k = 0
    for group in sorted({line(p) for p in props}):
        for p in sorted(p for p in props if line(p) == group):
            out[k % FOLDS].append(p)
            k += 1
    return out


def medians(table, props):
    return statistics.median(table[p][0] for p in props), statistics.median(table[p][1] for p in props)


def score(table, props):
    return 0.5 * sum(medians(table, props))


def tail(table, props):
    larger = sorted(max(table[p]) for p in props)
    p90 = larger[int((len(larger) - 1) * 0.9 + 0.5)]
    lines = {}
    for g in sorted({line(p) for p in props}):
        gp = [p for p in props if line(p) == g]
        if len(gp) >= 3:
            lines[g] = medians(table, gp)
    worst = max(lines, key=lambda g: max(lines[g]))
    return p90, sum(x > 0.15 for x in larger), worst, lines


def pct(x):
    return f"{100 * x:.1f} %"


def main(args):
    names, tables = [], []
    for a in args:
        name, path = a.split("=", 1)
        names.append(name)
        tables.append(read(f"{path}/validation.csv"))
    props = sorted(set.intersection(*(set(t) for t in tables)))
    print(f"Candidates on the {len(props)} props of other makers every candidate validated:\n")
    print("| candidate | CT / CP median | score | p90 of a prop's larger median | props above 15 % | worst line (3 props or more) |")
    print("|---|---|---|---|---|---|")
    for name, t in zip(names, tables):
        ct, cp = medians(t, props)
        p90, above, worst, lines = tail(t, props)
        print(f"| {name} | {pct(ct)} / {pct(cp)} | {pct(0.5 * (ct + cp))} | {pct(p90)} | {above} | "
              f"{worst} {pct(lines[worst][0])} / {pct(lines[worst][1])} |")
    held, chosen = {}, []
    for test in folds(props):
        train = [p for p in props if p not in test]
        best = min(range(len(names)), key=lambda i: (score(tables[i], train), i))
        chosen.append(names[best])
        for p in test:
            held[p] = tables[best][p]
    ct, cp = medians(held, props)
    p90, above, worst, lines = tail(held, props)
    winner = min(range(len(names)), key=lambda i: (score(tables[i], props), i))
    optimism = 0.5 * (ct + cp) - score(tables[winner], props)
    print(f"\nChosen in the {FOLDS} folds: {', '.join(chosen)}. Nested, every prop predicted by the candidate "
          f"chosen without it: CT {pct(ct)}, CP {pct(cp)} (score {pct(0.5 * (ct + cp))}); p90 {pct(p90)}, "
          f"{above} props above 15 %, worst line {worst} {pct(lines[worst][0])} / {pct(lines[worst][1])}. "
          f"Chosen on all {len(props)}: {names[winner]}, score {pct(score(tables[winner], props))} in sample: "
          f"the choice among {len(names)} candidates is optimistic by {100 * optimism:+.1f} points.")


if __name__ == "__main__":
    main(sys.argv[1:])

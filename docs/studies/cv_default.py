"""Chooses the default model by cross-validation over props (docs/studies/default-by-cross-validation.md).

Each candidate is one `propbet validate` run on the shared props (its validation.csv). The props
are split into FOLDS folds stratified by family (E, SF, SP, FF: each family dealt round-robin, in
name order; the props of other makers, whose sections are assumed, stay out as they do of
validate's medians); for each fold the candidate with the lowest score on the other folds'
props is chosen and scored on the fold's props. The score is the mean of the median over props of
the CT median and of the CP median (validate's pure prediction, before any calibration).

    python3 docs/studies/cv_default.py NAME=DIR [NAME=DIR ...]   (the first is the current default)
"""

import csv
import sys

FOLDS = 5


def family(prop):
    for prefix, name in [("apce_", "E"), ("apcsf_", "SF"), ("apcsp_", "SP"), ("apcff_", "FF")]:
        if prop.startswith(prefix):
            return name
    return "other"


def read(path):
    with open(path, newline="") as f:
        rows = {r["prop"]: r for r in csv.DictReader(f)}
    out = {}
    num = lambda x: float(x) if x else float("nan")
    for prop, r in rows.items():
        # Props of other makers (sections assumed) stay out, as they do of validate's medians.
        if r["ct_median"] and r["cp_median"] and not r["assumed_section"]:
            out[prop] = (float(r["ct_median"]), float(r["cp_median"]), float(r["ct_p90"]), float(r["cp_p90"]),
                         num(r["forward_ct_error_rpm_change"]), num(r["static_fm_error"]))
    return out


def folds(props):
    by_family = {}
    for p in sorted(props):
        by_family.setdefault(family(p), []).append(p)
    out = [[] for _ in range(FOLDS)]
    k = 0
    for fam in sorted(by_family):
        for p in by_family[fam]:
            out[k % FOLDS].append(p)
            k += 1
    return out


def median(values):
    """validate's median when this study was run (the value at the rounded middle rank), so
    that the numbers here are that day's table's; propbet's median is now the mean of the two
    middle values for an even count (`propbet_units::stats::median`)."""
    v = sorted(values)
    return v[int((len(v) - 1) * 0.5 + 0.5)]


def medians(table, props):
    return median(table[p][0] for p in props), median(table[p][1] for p in props)


def score(table, props):
    ct, cp = medians(table, props)
    return 0.5 * (ct + cp)


def pct(x):
    return f"{100 * x:.1f} %"


def main(args):
    names, tables = [], []
    for a in args:
        name, path = a.split("=", 1)
        names.append(name)
        tables.append(read(f"{path}/validation.csv"))
    props = sorted(set.intersection(*(set(t) for t in tables)))
    families = sorted({family(p) for p in props})
    print(f"Candidates on the {len(props)} props every candidate validated (median over props):\n")
    head = "| candidate | CT median | CT p90 | CP median | CP p90 | score | " + " | ".join(
        f"{f} CT / CP" for f in families) + " |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for name, t in zip(names, tables):
        ct, cp = medians(t, props)
        p90 = [median(t[p][2] for p in props), median(t[p][3] for p in props)]
        fam = []
        for f in families:
            fp = [p for p in props if family(p) == f]
            a, b = medians(t, fp)
            fam.append(f"{pct(a)} / {pct(b)}")
        print(f"| {name} | {pct(ct)} | {pct(p90[0])} | {pct(cp)} | {pct(p90[1])} | {pct(0.5 * (ct + cp))} | "
              + " | ".join(fam) + " |")
    print("\nThe data's signatures under each candidate (median over the props that have them): the forward-flight CT "
          "error's change with RPM at fixed J (validate's `forward_ct_error_rpm_change`), and the static figure of "
          "merit's error (`static_fm_error`):\n")
    print("| candidate | CT error's change with RPM at fixed J | props | static figure of merit error | props |")
    print("|---|---|---|---|---|")
    for name, t in zip(names, tables):
        trend = [t[p][4] for p in props if t[p][4] == t[p][4]]
        fm = [t[p][5] for p in props if t[p][5] == t[p][5]]
        print(f"| {name} | {100 * median(trend):+.1f} % | {len(trend)} | {100 * median(fm):+.1f} % | {len(fm)} |")
    print(f"\nFolds ({FOLDS}, stratified by family): the candidate chosen on the other folds, scored on the fold's props:\n")
    print("| fold | props | chosen on the others | its CT / CP median on the fold | the current default's on the fold |")
    print("|---|---|---|---|---|")
    held = {}
    for k, test in enumerate(folds(props)):
        train = [p for p in props if p not in test]
        best = min(range(len(names)), key=lambda i: (score(tables[i], train), i))
        for p in test:
            held[p] = tables[best][p]
        a, b = medians(tables[best], test)
        c, d = medians(tables[0], test)
        print(f"| {k + 1} | {len(test)} | {names[best]} | {pct(a)} / {pct(b)} | {pct(c)} / {pct(d)} |")
    ct = median(v[0] for v in held.values())
    cp = median(v[1] for v in held.values())
    d_ct, d_cp = medians(tables[0], props)
    print(f"\nCross-validated (every prop predicted by the candidate chosen without it): CT median {pct(ct)}, "
          f"CP median {pct(cp)}, score {pct(0.5 * (ct + cp))}; the current default ({names[0]}) on every prop: "
          f"CT {pct(d_ct)}, CP {pct(d_cp)}, score {pct(0.5 * (d_ct + d_cp))}.")
    protocol(names, tables, props)


def tail(table, props):
    """The tail over props: the 90th percentile of a prop's larger median (CT or CP), the props
    above 15 % in either, and the worst family's larger median."""
    larger = sorted(max(table[p][0], table[p][1]) for p in props)
    p90 = larger[int((len(larger) - 1) * 0.9 + 0.5)]
    above = sum(x > 0.15 for x in larger)
    fams = {}
    for f in sorted({family(p) for p in props}):
        fp = [p for p in props if family(p) == f]
        if len(fp) >= 2:  # a family of one prop is that prop (validate's table: the same)
            fams[f] = medians(table, fp)
    worst = max(fams, key=lambda f: max(fams[f]))
    return p90, above, worst, fams


def eligible(tables, i, props, loss=0.03):
    """The family rule: a candidate that loses any family by more than `loss` (3 points) of its
    median, in CT or CP, against the current default (the first) is not a default."""
    fams_0, fams_i = tail(tables[0], props)[3], tail(tables[i], props)[3]
    return all(fams_i[f][q] <= fams_0[f][q] + loss for f in fams_0 for q in (0, 1))


def protocol(names, tables, props):
    """Nested selection: in each outer fold the candidate is chosen on the other folds' props
    alone (the family rule judged there too), then scored on the fold's; the tail beside the
    median; and how optimistic the in-sample choice is."""
    n = len(names)
    print(f"\nThe protocol: {n} candidates, each with its physical hypothesis written before it was scored; "
          "in each fold the choice (lowest score among the candidates that lose no family by more than 3 points "
          "on the other folds' props) is made without the fold.\n")
    print("| candidate | eligible on all props | CT / CP median | p90 of a prop's larger median | props above 15 % "
          "| worst family (CT / CP) |")
    print("|---|---|---|---|---|---|")
    for name, t, i in zip(names, tables, range(n)):
        ct, cp = medians(t, props)
        p90, above, worst, fams = tail(t, props)
        print(f"| {name} | {'yes' if eligible(tables, i, props) else 'no'} | {pct(ct)} / {pct(cp)} | {pct(p90)} | "
              f"{above} | {worst} {pct(fams[worst][0])} / {pct(fams[worst][1])} |")
    held = {}
    chosen = []
    for test in folds(props):
        train = [p for p in props if p not in test]
        ok = [i for i in range(n) if eligible(tables, i, train)]
        best = min(ok, key=lambda i: (score(tables[i], train), i))
        chosen.append(names[best])
        for p in test:
            held[p] = tables[best][p]
    ct = median(v[0] for v in held.values())
    cp = median(v[1] for v in held.values())
    p90, above, worst, fams = tail(held, props)
    ok_all = [i for i in range(n) if eligible(tables, i, props)]
    winner = min(ok_all, key=lambda i: (score(tables[i], props), i))
    w_ct, w_cp = medians(tables[winner], props)
    optimism = 0.5 * (ct + cp) - 0.5 * (w_ct + w_cp)
    print(f"\nChosen in the folds: {', '.join(chosen)}. Nested, every prop predicted by the candidate chosen "
          f"without it: CT {pct(ct)}, CP {pct(cp)} (score {pct(0.5 * (ct + cp))}); p90 of a prop's larger median "
          f"{pct(p90)}, {above} props above 15 %, worst family {worst} {pct(fams[worst][0])} / "
          f"{pct(fams[worst][1])}. Chosen on all {len(props)} props: {names[winner]}, score "
          f"{pct(0.5 * (w_ct + w_cp))} in sample: the choice among {n} candidates is optimistic by "
          f"{100 * optimism:+.1f} points.")


if __name__ == "__main__":
    main(sys.argv[1:])

#!/usr/bin/env python3
"""Every whole-model candidate measured in the studies, against issue 16's median targets:
census.py [DIR] (default: the directory of this script).

Reads every table row of DIR/*.md that holds the six shared props' pure-prediction CT / CP
medians ("a / b %" cells in the order apce_10x5, apce_11x7, apcff_4.2x4, apcsf_10x4.7,
apcsf_9x4.7, apcsp_10x6, as the studies print them; each row one `propbet validate` run) and
prints, per row, the medians over props (validate's: the 4th smallest of six), how many props
are at or below 7 % in CT and in CP, and the worst prop's larger median. Rows of held-out
("after") tables and the per-prop transposed tables are left out: they are not one model's
pure prediction of all six (`pure`). Issue 16 asks CT and CP medians <= 7 %, i.e. four props at or
below 7 % in each."""
import glob
import os
import re
import sys

PAIR = re.compile(r"\**(\d+\.\d+) / (\d+\.\d+) ?%?\**")


def pure(header):
    """Whether a table (by its header row) holds pure predictions of the six props: its second
    column is a prop's "CT / CP" and no column is a held-out ("after") one. The held-out tables
    of diagnosis-trades.md name "after" or give bare prop names."""
    cells = [c.strip() for c in header.strip().strip("|").split("|")]
    return len(cells) > 1 and "CT / CP" in cells[1] and "after" not in header


def rows(d):
    for path in sorted(glob.glob(os.path.join(d, "*.md"))):
        name = os.path.basename(path)
        header, prev = "", ""
        for line in open(path, encoding="utf-8"):
            if line.startswith("|") and not prev.startswith("|"):
                header = line
            prev = line
            if not line.startswith("|") or line is header or not pure(header):
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            label = cells[0]
            pairs = [tuple(map(float, m.groups())) for c in cells if (m := PAIR.fullmatch(c))]
            if len(pairs) < 6 or label.startswith("apc"):
                continue  # not a six-prop row; a prop's row of a transposed table
            yield name, label, pairs[:6]


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    print("| study | candidate | median CT / CP | props <= 7 % CT | props <= 7 % CP | worst prop |")
    print("|---|---|---|---|---|---|")
    n = 0
    most_ct = most_cp = 0
    for name, label, p in rows(d):
        ct = sorted(x[0] for x in p)[3]
        cp = sorted(x[1] for x in p)[3]
        n_ct = sum(x[0] <= 7.0 for x in p)
        n_cp = sum(x[1] <= 7.0 for x in p)
        most_ct, most_cp = max(most_ct, n_ct), max(most_cp, n_cp)
        worst = max(max(x) for x in p)
        print(f"| {name} | {label} | {ct:.1f} / {cp:.1f} % | {n_ct} | {n_cp} | {worst:.1f} % |")
        n += 1
    print(f"\n{n} candidates; the most props at or below 7 % under one candidate: {most_ct} in CT, "
          f"{most_cp} in CP (medians <= 7 % need 4 in each, under the same candidate)")


if __name__ == "__main__":
    main()

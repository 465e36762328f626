#!/usr/bin/env python3
"""UIUC's static tests against their J sweeps (docs/studies/diagnosis-trades.md, 2026-11-26):
each sweep starting below J 0.16, a quadratic through its first five points extrapolated to
J 0, against the static CT at the sweep's RPM, measured and predicted.
Usage: static_vs_sweeps.py VAL_DIR PROP [PROP ...]   (VAL_DIR: a `propbet validate -o` folder)"""
import csv, sys, collections
def polyfit2(x,y):
    # least squares a+bx+cx^2
    S=[[sum(xi**(i+j) for xi in x) for j in range(3)] for i in range(3)]
    T=[sum(yi*xi**i for xi,yi in zip(x,y)) for i in range(3)]
    # gaussian elimination
    A=[S[i]+[T[i]] for i in range(3)]
    for i in range(3):
        p=max(range(i,3),key=lambda r:abs(A[r][i])); A[i],A[p]=A[p],A[i]
        for r in range(3):
            if r!=i:
                f=A[r][i]/A[i][i]
                A[r]=[a-f*b for a,b in zip(A[r],A[i])]
    return [A[i][3]/A[i][i] for i in range(3)]
def interp(x,xs,ys):
    for a,b,ya,yb in zip(xs,xs[1:],ys,ys[1:]):
        if a<=x<=b: return ya+(yb-ya)*(x-a)/(b-a)
    return None
for prop in sys.argv[2:]:
    rows=list(csv.DictReader(open(f'{sys.argv[1]}/{prop}/compare/points.csv')))
    byf=collections.defaultdict(list)
    for r in rows: byf[r['file']].append(r)
    static=sorted([r for f,rs in byf.items() for r in rs if float(r['j'])<0.005],key=lambda r: float(r['rpm']))
    srpm=[float(r['rpm']) for r in static]; sct=[float(r['ct']) for r in static]; sctp=[float(r['ct_pred']) for r in static]
    for f,rs in byf.items():
        rs=sorted([r for r in rs if float(r['j'])>0.005],key=lambda r: float(r['j']))
        if not rs or float(rs[0]['j'])>0.16: continue
        k=min(5,len(rs))
        jj=[float(r['j']) for r in rs[:k]]; ct=[float(r['ct']) for r in rs[:k]]; ctp=[float(r['ct_pred']) for r in rs[:k]]
        rpm=sum(float(r['rpm']) for r in rs)/len(rs)
        sm=interp(rpm,srpm,sct); sp=interp(rpm,srpm,sctp)
        if sm is None: continue
        em=polyfit2(jj,ct)[0]; ep=polyfit2(jj,ctp)[0]
        print(f"{prop:15s} {rpm:6.0f} rpm, J from {jj[0]:.3f}: static / extrapolated sweep - 1: measured {100*(sm/em-1):+.1f} %, model {100*(sp/ep-1):+.1f} %")

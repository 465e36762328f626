#!/usr/bin/env python3
"""Repeatability of UIUC's runs over validate's scored window (docs/studies/diagnosis-trades.md,
2026-11-26): pairs of points at one RPM (within 3 %) in two files, the second interpolated in J
(gap <= 0.1), as diagnose pairs them (thrust above a quarter of the largest: "current") and over
every scored point, normalised as the diagnosis's residuals are (floor 5 % of the largest load).
Usage: repeatability_window.py VAL_DIR PROP [PROP ...]   (VAL_DIR: a `propbet validate -o` folder)"""
import os, sys, math
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sf_pair import load as window_rows  # validate's window, as compare::metrics::in_window
def load(d, prop):
    """The scored points of validate's window, parsed."""
    return [dict(file=r['file'], rpm=float(r['rpm']), j=float(r['j']), T=float(r['thrust_n']),
                 Q=float(r['torque_nm']) if r['torque_nm'] else None, ct=float(r['ct']))
            for r in window_rows(d, prop) if r['scored']=='1']
def rep(pts, floor_frac, pair_floor):
    maxT=max(abs(p['T']) for p in pts); maxQ=max(abs(p['Q']) for p in pts if p['Q'] is not None)
    fl=(floor_frac or 0)*maxT; flq=(floor_frac or 0)*maxQ
    d2=[]; d2t=[]
    files=sorted(set(p['file'] for p in pts))
    for ia,fa in enumerate(files):
        A=[p for p in pts if p['file']==fa and p['T']>pair_floor*maxT]
        for fb in files[ia+1:]:
            B=sorted([p for p in pts if p['file']==fb],key=lambda p:p['j'])
            for a in A:
                near=[b for b in B if abs(b['rpm']/a['rpm']-1)<0.03]
                if a['j']<0.01:
                    bs=[b for b in near if b['j']<0.01 and b['T']>pair_floor*maxT]
                    if bs:
                        b=bs[0]; pr=[(b,b,0.0)]
                    else: continue
                else:
                    pr=[]
                    for b0,b1 in zip(near,near[1:]):
                        if b0['j']<=a['j']<=b1['j'] and b1['j']-b0['j']<=0.1 and b1['j']>b0['j'] and b0['T']>pair_floor*maxT and b1['T']>pair_floor*maxT:
                            pr=[(b0,b1,(a['j']-b0['j'])/(b1['j']-b0['j']))]; break
                    if not pr: continue
                b0,b1,t=pr[0]
                # normalize loads by rho omega^2 ~ rpm^2
                n=lambda p,x: x/(p['rpm']**2)
                tb=n(b0,b0['T'])+t*(n(b1,b1['T'])-n(b0,b0['T']))
                ta=n(a,a['T'])
                if floor_frac is None:
                    e=(ta/tb-1)
                else:
                    e=(ta-tb)/max(abs(ta),fl/a['rpm']**2)
                d2.append(e*e); d2t.append(e*e)
                if a['Q'] is not None and b0['Q'] is not None:
                    qb=n(b0,b0['Q'])+t*(n(b1,b1['Q'])-n(b0,b0['Q'])); qa=n(a,a['Q'])
                    e=(qa/qb-1) if floor_frac is None else (qa-qb)/max(abs(qa),flq/a['rpm']**2)
                    d2.append(e*e)
    if len(d2)<3: return None
    return math.sqrt(sum(d2)/(2*len(d2))), len(d2), math.sqrt(sum(d2t)/(2*len(d2t)))
for prop in sys.argv[2:]:
    pts=load(sys.argv[1], prop)
    cur=rep(pts,None,0.25); alt=rep(pts,0.05,0.0)
    print(prop, 'current sd %.2f%% (%d rows)'%(100*cur[0],cur[1]) if cur else 'current none', '| all window pairs, residual normalisation: sd %.2f%% (%d rows), thrust alone %.2f%%'%(100*alt[0],alt[1],100*alt[2]) if alt else 'alt none')

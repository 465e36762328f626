"""NeuralFoil's own answers for the parity test (crates/neuralfoil/tests/parity.rs).

For each airfoil file given, the package's Kulfan parameters (AeroSandbox's least-squares fit,
8 weights a side, as NeuralFoil's own `get_aero_from_airfoil` makes them) and NeuralFoil's
coefficients over a grid of angle, Reynolds number, Ncrit and forced transition, as JSON on
standard output.
"""
import json
import sys

import aerosandbox as asb
import numpy as np
import neuralfoil as nf

size = sys.argv[1]
cases = []
for path in sys.argv[2:]:
    af = asb.Airfoil(name=path, coordinates=path).normalize()
    k = af.to_kulfan_airfoil(n_weights_per_side=8).kulfan_parameters
    kp = {
        "upper": [float(v) for v in k["upper_weights"]],
        "lower": [float(v) for v in k["lower_weights"]],
        "leading_edge": float(k["leading_edge_weight"]),
        "te_thickness": float(k["TE_thickness"]),
    }
    alpha, re, ncrit, xtr = np.meshgrid(
        np.arange(-8.0, 16.1, 2.0), [2e4, 6e4, 2e5], [5.0, 9.0], [1.0, 0.5], indexing="ij"
    )
    alpha, re, ncrit, xtr = (a.ravel() for a in (alpha, re, ncrit, xtr))
    out = nf.get_aero_from_kulfan_parameters(
        kulfan_parameters=k, alpha=alpha, Re=re, n_crit=ncrit, xtr_upper=xtr, xtr_lower=xtr, model_size=size
    )
    for i in range(len(alpha)):
        cases.append(
            {
                "airfoil": path,
                "kulfan": kp,
                "alpha": float(alpha[i]),
                "re": float(re[i]),
                "ncrit": float(ncrit[i]),
                "xtr": float(xtr[i]),
                "cl": float(out["CL"][i]),
                "cd": float(out["CD"][i]),
                "cm": float(out["CM"][i]),
                "confidence": float(out["analysis_confidence"][i]),
            }
        )
json.dump(cases, sys.stdout)

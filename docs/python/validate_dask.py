"""Validate many props in parallel with Dask: each worker runs `propbet.validate` on one prop,
and the rows come back as one DataFrame.

Run from the repository root. Arguments: the UIUC folder, the PE0 folder and the props (default:
the shipped subset tests/data/validate and two of its props); NeuralFoil polars, so that each
prop takes seconds.
"""

import sys
import tempfile

import pandas as pd
from dask.distributed import Client, LocalCluster

import propbet


def validate_one(prop: str, uiuc: str, pe0: str) -> pd.DataFrame:
    """One prop's row of the validation table (runs on a worker)."""
    out = tempfile.mkdtemp(prefix=f"validate-{prop}-")
    result = propbet.validate(uiuc, pe0, "props/airfoils", out=out, only=prop, engine="neuralfoil", quiet=True)
    return result.table


def main() -> None:
    uiuc, pe0, *props = sys.argv[1:] or ["tests/data/validate/uiuc", "tests/data/validate/pe0"]
    props = props or ["apcsf_9x4.7", "gwsdd_9x5"]
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster, Client(cluster) as client:
        rows = client.gather(client.map(validate_one, props, uiuc=uiuc, pe0=pe0))
    table = pd.concat(rows, ignore_index=True)
    print(table[["prop", "points", "ct_median", "cp_median"]].to_string(index=False))


if __name__ == "__main__":
    main()

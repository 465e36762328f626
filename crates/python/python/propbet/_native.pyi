"""Type hints of propbet's native module (crates/python/src: lib.rs, model.rs, motor.rs)."""

import os
from typing import Any, Optional, Sequence, Union

__version__: str

PathLike = Union[str, os.PathLike]
Numbers = Union[float, str, Sequence[float], Any]
Columns = list[tuple[str, str, Union[bytes, list[str]]]]

class InputError(Exception):
    """Bad input: a file, value or option propbet cannot use (exit status 2)."""

class InternalError(Exception):
    """A fault of propbet's own (a Rust panic caught at the boundary)."""

class Model:
    prop: os.PathLike
    polars: Optional[os.PathLike]
    def __init__(
        self, prop: PathLike, *, units: Optional[str] = ..., qprop_compat: bool = ..., no_tip_loss: bool = ...,
        dbeta: float = ..., rotation: Optional[str] = ..., drag_factor: Optional[float] = ...,
        effects: Sequence[str] = ..., user_effects: Optional[PathLike] = ..., polars: Optional[PathLike] = ...,
        airfoil: Optional[str] = ..., sections_from: Optional[PathLike] = ..., airfoils: Optional[PathLike] = ...,
        engine: Optional[str] = ..., neuralfoil_size: Optional[str] = ..., xfoil: Optional[PathLike] = ...,
        cache: Optional[PathLike] = ..., no_cache: bool = ..., quiet: bool = ..., xfoil_budget: Optional[float] = ...,
    ) -> None: ...
    def with_tables(self, prop: PathLike, polars: PathLike) -> "Model": ...

class Motor:
    name: str
    kind: int
    params: list[float]
    r: float
    io: float
    kv: float
    def __init__(self, r: float, io: float, kv: float, *, name: str = ...) -> None: ...
    @staticmethod
    def from_file(path: PathLike) -> "Motor": ...
    def text(self) -> str: ...

class Battery:
    cells: int
    volts: float
    capacity_mah: float
    cell_ohms: float
    cutoff_volts: float
    usable: float
    esc_ohms: float
    def __init__(self, spec: str, *, esc_ohms: float = ...) -> None: ...

def execute(argv: list[str]) -> bool: ...
def format_number(v: float) -> str: ...
def expected_accuracy(name: Optional[str] = None) -> dict: ...
def predict(
    model: Model, rpm: Optional[Numbers] = ..., j: Optional[Numbers] = ..., v: Optional[Numbers] = ...,
    air: Optional[dict] = ..., effects: Sequence[str] = ..., band: bool = ..., stations: bool = ...,
) -> tuple[Columns, Optional[Columns], int, int]: ...
def stations(model: Model) -> bytes: ...
def case_model(case: PathLike, out: PathLike) -> tuple[Model, Optional[tuple[os.PathLike, Optional[str], Optional[os.PathLike]]]]: ...
def read_measurements(files: Sequence[PathLike], poles: Optional[int] = ..., rpm_source: Optional[str] = ..., atmosphere: Optional[str] = ..., rho: Optional[float] = ..., columns: Optional[PathLike] = ...) -> tuple[bytes, bytes]: ...
def compare(model: Model, files: Sequence[PathLike], out: PathLike, **options: Any) -> tuple[bool, bytes, bytes, bytes]: ...
def diagnose(model: Model, files: Sequence[PathLike], out: PathLike, **options: Any) -> tuple[bool, bytes, bytes]: ...
def run(case: Optional[PathLike], out: PathLike, **options: Any) -> tuple[bool, bytes, Optional[bytes], Optional[bytes], Optional[bytes]]: ...
def validate(uiuc: PathLike, pe0: PathLike, airfoils: PathLike, out: PathLike, **options: Any) -> tuple[bool, str, bytes]: ...
def powered(model: Model, motor: Motor, **options: Any) -> tuple[Columns, list[str]]: ...
def fit_motor(files: Sequence[PathLike], **options: Any) -> tuple[Motor, str, dict, Columns]: ...
def compare_props(models: Sequence[tuple[str, Model]], motor: Motor, battery: Battery, hover: float, **options: Any) -> tuple[Columns, list[str]]: ...

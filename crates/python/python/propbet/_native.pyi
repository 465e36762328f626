"""Type hints of propbet's native module (crates/python/src/lib.rs)."""

from typing import Optional, Union

__version__: str

class InputError(Exception):
    """Bad input: a file, value or option propbet cannot use (exit status 2)."""

class InternalError(Exception):
    """A fault of propbet's own (a Rust panic caught at the boundary)."""

def execute(argv: list[str]) -> bool: ...
Columns = list[tuple[str, str, Union[bytes, list[str]]]]

def predict(argv: list[str], stations: bool) -> tuple[Columns, Optional[Columns], int, int]: ...
def format_number(v: float) -> str: ...
def stations(argv: list[str]) -> bytes: ...
def case_stages(case: str, out: str) -> list[list[str]]: ...
def read_measurements(argv: list[str]) -> tuple[bytes, bytes]: ...

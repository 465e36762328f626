"""propbet from Python: propeller performance from geometry, compared with measurements.

The same engine as the ``propbet`` command line, run in this process: every function here is
a command with its flags given as keyword arguments (``ncrit=7`` is ``--ncrit 7``,
``rpm=[4000, 6000]`` is ``--rpm 4000,6000``, ``qprop_compat=True`` is ``--qprop-compat``), and
its tables returned as pandas DataFrames with the columns and digits of the files the command
writes. Nothing is computed twice: the numbers are the command line's.

    import propbet
    prop = propbet.Prop.from_qprop("props/cam6x3/cam6x3.qprop")
    sweep = prop.predict(rpm=[4000, 6000], j=np.arange(0, 0.61, 0.05))

Bad input raises :class:`InputError` with the command line's message (the file, line or value);
the GIL is released while propbet computes. Calls are quiet: propbet's warnings are
:class:`PropbetWarning`, the rest of what the command line would print goes to the ``propbet``
logger (``logging.INFO``), and to ``sys.stdout`` / ``sys.stderr`` as well with
``propbet.verbose = True``. A call writes no file unless given ``out=`` (its temporary folder
goes with the object it returned). A column whose name a DataFrame already uses as an attribute
is renamed: ``flags`` is ``point_flags`` (``sweep.point_flags``).
"""

from __future__ import annotations

import functools
import io
import json
import logging
import math
import numbers
import os
import sys
import tempfile
import threading
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Mapping, Optional, Sequence, Union

import numpy as np
import pandas as pd

from . import _native
from ._native import InputError, InternalError

__all__ = [
    "Prop",
    "Comparison",
    "Diagnosis",
    "RunResult",
    "Validation",
    "read_measurements",
    "compare",
    "diagnose",
    "run",
    "validate",
    "execute",
    "InputError",
    "InternalError",
    "PropbetWarning",
]
__version__ = _native.__version__

PathLike = Union[str, "os.PathLike[str]"]

verbose = False
"""True: what the command line would print is written to ``sys.stdout`` and ``sys.stderr``
too (it always goes to the ``propbet`` logger)."""

_log = logging.getLogger("propbet")

# Columns whose names a DataFrame owns as attributes (`df.flags`), renamed in the package's
# tables; any other such name gets a trailing underscore.
_COLUMN_NAMES = {"flags": "point_flags"}


def column_name(name: str) -> str:
    """The package's name of a column of propbet's files: the same, except where a DataFrame
    attribute has it (``flags`` -> ``point_flags``)."""
    if name in _COLUMN_NAMES:
        return _COLUMN_NAMES[name]
    return name + "_" if hasattr(pd.DataFrame, name) else name

# Flags given once per value (`--effect a --effect b`); every other list is comma-joined.
_REPEATED = {"effect"}
# Flags that take several values after one flag (`--measured a b c`).
_MANY = {"measured"}


def _number(name: str, value: Any, index: Optional[int] = None) -> str:
    where = name if index is None else f"{name}[{index}]"
    x = float(value)
    if math.isnan(x) or math.isinf(x):
        raise InputError(f"{where} = {x!r}: not a finite number")
    return repr(x) if not float(x).is_integer() else str(int(x)) if abs(x) < 1e15 else repr(x)


def _text(name: str, value: Any) -> str:
    """One flag's value as the command line writes it."""
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    if isinstance(value, bool):
        raise InputError(f"{name} = {value!r}: a switch takes True or False alone")
    if isinstance(value, numbers.Real):
        return _number(name, value)
    try:
        items = list(value)
    except TypeError:
        raise InputError(f"{name} = {value!r}: not a number, a text or a list") from None
    if not items:
        raise InputError(f"{name}: an empty list")
    parts = []
    for i, v in enumerate(items):
        if isinstance(v, numbers.Real) and not isinstance(v, bool):
            parts.append(_number(name, v, i))
        elif isinstance(v, (str, os.PathLike)):
            parts.append(os.fspath(v))
        else:
            raise InputError(f"{name}[{i}] = {v!r}: not a number")
    return ",".join(parts)


# predict's flags that are not the model's: the sweep, the air, the outputs.
_NOT_MODEL = {"rpm", "j", "v", "rho", "mu", "a", "temp", "pressure", "humidity", "out", "format", "out_stations", "band"}


def _switch(where: str, name: str, value: Any) -> bool:
    """A True/False keyword, checked: ``band="yes"`` is a TypeError, not True."""
    if not isinstance(value, bool):
        raise TypeError(f"{where}(): {name} = {value!r}: True or False")
    return value


@functools.lru_cache(maxsize=None)
def _flags_of(command: str) -> tuple:
    """The flags ``command`` takes, with their kinds (the binary's own list, read once)."""
    return tuple(_native.flags(command))


def _check_options(where: str, options: Mapping[str, Any], command: Optional[str] = "predict", exclude: set = frozenset(), extra: Mapping[str, str] = {}) -> None:
    """Keyword arguments checked at the call against the flags ``command`` takes (the binary's
    own list; None: ``extra`` alone): an unknown name is a TypeError, a value of the wrong kind
    a TypeError or a ValueError, each naming the keyword."""
    known = {k: kind for k, kind in (_flags_of(command) if command else ()) if k not in exclude}
    known.update(extra)
    for key, value in options.items():
        kind = known.get(key)
        if kind is None:
            raise TypeError(f"{where}() got an unexpected keyword argument '{key}' (it takes: {', '.join(sorted(known))})")
        if value is None:
            continue
        if kind == "switch":
            _switch(where, key, value)
        elif kind == "number":
            if isinstance(value, bool) or not isinstance(value, (numbers.Real, str)):
                raise TypeError(f"{where}(): {key} = {value!r}: a number")
            if isinstance(value, str):
                try:
                    float(value)
                except ValueError:
                    raise ValueError(f"{where}(): {key} = {value!r}: not a number") from None
        elif kind == "many":
            items = [value] if isinstance(value, (str, os.PathLike)) else value
            try:
                items = list(items)
            except TypeError:
                raise TypeError(f"{where}(): {key} = {value!r}: a text or a list of them") from None
            for v in items:
                if isinstance(v, bool) or not isinstance(v, (str, os.PathLike, numbers.Real)):
                    raise TypeError(f"{where}(): {key} holds {v!r}: a text or a list of them")
        elif isinstance(value, bool) or not isinstance(value, (str, os.PathLike, numbers.Real)):
            raise TypeError(f"{where}(): {key} = {value!r}: a text, path or number")


def _flags(options: Mapping[str, Any]) -> list[str]:
    """Keyword arguments as command-line flags: ``key_name=value`` is ``--key-name=value`` (so
    that a value with a leading dash, ``-10C``, stays a value), True a switch, None and False
    nothing."""
    argv: list[str] = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if value is True:
            argv.append(flag)
        elif key in _REPEATED and not isinstance(value, (str, os.PathLike)):
            for v in value:
                argv.append(f"{flag}={_text(key, v)}")
        elif key in _MANY:
            values = [value] if isinstance(value, (str, os.PathLike)) else list(value)
            argv += [flag, *(os.fspath(v) for v in values)]
        else:
            argv.append(f"{flag}={_text(key, value)}")
    return argv


def _csv(data: bytes) -> pd.DataFrame:
    """A table propbet wrote (CSV bytes), its numbers as written."""
    if not data.strip():
        return pd.DataFrame()
    table = pd.read_csv(io.BytesIO(data), keep_default_na=False, na_values=[""])
    # An empty cell is a number not given (NaN) in a numeric column, an empty text in the others.
    for name in table.columns:
        if not pd.api.types.is_numeric_dtype(table[name]):
            table[name] = table[name].fillna("")
    return table.rename(columns=column_name)


def _frame(columns: Sequence[tuple]) -> pd.DataFrame:
    """A table propbet handed over as columns (name, kind, values): numbers as arrays."""
    data = {}
    for name, kind, values in columns:
        data[column_name(name)] = values if kind == "str" else np.frombuffer(values, dtype=np.dtype(kind)).copy()
    return pd.DataFrame(data)


def _read_csv(path: Path) -> pd.DataFrame:
    return _csv(path.read_bytes()) if path.is_file() else pd.DataFrame()


def _read_json(path: Path) -> Any:
    return json.loads(path.read_text()) if path.is_file() else None


def _folder(out: Optional[PathLike], prefix: str) -> tuple:
    """The output folder: ``out``, or a new temporary folder, removed with the object the call
    returns (which holds the second value, its owner; None for ``out``)."""
    if out is None:
        scratch = tempfile.TemporaryDirectory(prefix=f"propbet-{prefix}-")
        return Path(scratch.name), scratch
    Path(out).mkdir(parents=True, exist_ok=True)
    return Path(out), None


class PropbetWarning(UserWarning):
    """A warning of propbet's (the command line's ``propbet: warning: ...`` lines): what it read
    differently from QPROP, a setting it corrected, ..."""


# What propbet prints is caught while any call runs (the file descriptors are the process's:
# calls in several threads share one capture, relayed when the last ends).
_TERMINAL = threading.Lock()
_capture: dict = {"calls": 0}


def _relay(out: Any, err: Any) -> None:
    out.seek(0)
    err.seek(0)
    printed, errors = (f.read().decode("utf-8", "replace") for f in (out, err))
    for line in printed.splitlines():
        if line.strip():
            _log.info(line)
    if printed and verbose:
        sys.stdout.write(printed)
    for line in errors.splitlines():
        if line.startswith("propbet: warning: "):
            warnings.warn(line[len("propbet: warning: ") :], PropbetWarning, stacklevel=4)
        elif line.strip():
            _log.info(line)
            if verbose:
                sys.stderr.write(line + "\n")


def _relayed(call: Callable[[], Any]) -> Any:
    """Runs ``call`` with what propbet prints to the process's standard output and error
    caught, then writes it through ``sys.stdout`` and ``sys.stderr`` (which a notebook shows,
    unlike the process's own), its warnings as :class:`PropbetWarning`."""
    with _TERMINAL:
        if _capture["calls"] == 0:
            for stream in (sys.stdout, sys.stderr):
                stream.flush()
            files = (tempfile.TemporaryFile(), tempfile.TemporaryFile())
            _capture.update(saved=(os.dup(1), os.dup(2)), files=files)
            os.dup2(files[0].fileno(), 1)
            os.dup2(files[1].fileno(), 2)
        _capture["calls"] += 1
    try:
        return call()
    finally:
        with _TERMINAL:
            _capture["calls"] -= 1
            if _capture["calls"] == 0:
                saved, files = _capture.pop("saved"), _capture.pop("files")
                for fd, old in zip((1, 2), saved):
                    os.dup2(old, fd)
                    os.close(old)
                try:
                    _relay(*files)
                finally:
                    for f in files:
                        f.close()


def execute(*argv: Any) -> bool:
    """Runs ``propbet ARGV...`` as the command line does, in this process (its files written
    where its flags say). Returns True when done, False when done with problems it reported
    (the command line's exit status 1); raises :class:`InputError` on an error (exit 2)."""
    args = [os.fspath(a) if isinstance(a, os.PathLike) else str(a) for a in argv]
    return _relayed(lambda: _native.execute(args))


def _air(air: Optional[Mapping[str, Any]]) -> list[str]:
    """The air as flags: ``{"rho": 1.2}``, or ``{"temp": "20C", "pressure": "1013hPa",
    "humidity": 40}``, and ``mu``, ``a``."""
    if air is None:
        return []
    if not isinstance(air, Mapping):
        raise InputError(f"air = {air!r}: a dict such as {{'temp': '20C', 'pressure': '101325'}} or {{'rho': 1.2}}")
    known = {"rho", "mu", "a", "temp", "pressure", "humidity"}
    unknown = sorted(set(air) - known)
    if unknown:
        raise InputError(f"air: unknown key {unknown[0]!r}; the keys are {', '.join(sorted(known))}")
    return _flags(air)


def _sweep(rpm: Any, j: Any, v: Any) -> list[str]:
    if rpm is None:
        raise InputError("rpm: the rotation speeds are needed (a number, a list or 'start:stop:step')")
    if j is not None and v is not None:
        raise InputError("j and v: give one of them (advance ratios or axial speeds)")
    return _flags({"rpm": rpm, "j": j, "v": v})


class Prop:
    """A propeller model: a QPROP prop file, the tabulated polars that replace its section
    coefficients (after :meth:`polars`), and the model flags every prediction uses.

    Made by :meth:`from_qprop`, :meth:`from_scan` or :meth:`from_case`.
    """

    def __init__(
        self,
        path: PathLike,
        *,
        polars: Optional[PathLike] = None,
        model_flags: Sequence[str] = (),
        geometry: Optional[PathLike] = None,
        sections: Sequence[str] = (),
        folder: Optional[PathLike] = None,
        sweep: Sequence[str] = (),
        air_flags: Sequence[str] = (),
    ) -> None:
        self.path = Path(path)
        """The prop file the predictions read."""
        self.polars_file = Path(polars) if polars is not None else None
        """The tabulated polars (JSON) that replace the file's coefficients, if any."""
        self.geometry = Path(geometry) if geometry is not None else self.path
        """The blade geometry :meth:`polars` computes polars for."""
        self.folder = Path(folder) if folder is not None else None
        """The folder the scan, polars or case stages wrote, if any."""
        self._model_flags = list(model_flags)
        self._sections = list(sections)
        self._sweep = list(sweep)
        self._air = list(air_flags)
        self._scratch: Any = None

    def __repr__(self) -> str:
        polars = f", polars={str(self.polars_file)!r}" if self.polars_file else ""
        return f"Prop({str(self.path)!r}{polars})"

    def model_args(self) -> list[str]:
        """The model's flags as ``predict``, ``compare`` and ``diagnose`` take them."""
        argv = ["--prop", str(self.path)]
        if self.polars_file is not None:
            argv += ["--polars", str(self.polars_file)]
        return argv + self._model_flags

    @classmethod
    def from_qprop(cls, path: PathLike, **options: Any) -> "Prop":
        """A QPROP prop file as it is. ``options`` are the model flags of ``propbet predict``:
        ``units="in"``, ``qprop_compat=True``, ``no_tip_loss=True``, ``dbeta=1.5`` [deg],
        ``rotation="snel"``, ``drag_factor=1.1``, ``effects=["pitch-offset:deg=1"]``,
        ``user_effects=path``, ``polars=path`` (tables from :meth:`polars`)."""
        _check_options("from_qprop", options, exclude=_NOT_MODEL | {"effect", "prop"}, extra={"effects": "many"})
        options = dict(options)
        effects = options.pop("effects", None)
        if effects is not None:
            options["effect"] = [effects] if isinstance(effects, str) else list(effects)
        polars = options.pop("polars", None)
        prop = cls(path, polars=polars, model_flags=_flags(options))
        prop.stations  # read once: a bad file fails here, naming itself
        return prop

    @classmethod
    def from_file(cls, path: PathLike, **options: Any) -> "Prop":
        """The propeller you own, from what you have: APC's design file (PE0), a UIUC geometry
        table, a blade table (CSV of ``r (mm)``, ``chord (mm)``, ``beta (deg)``, optionally
        ``t/c`` and ``airfoil``) or a QPROP prop file. A file without section coefficients has
        its polars computed at each prediction's operating points: ``engine="neuralfoil"`` (or
        ``"xfoil"``, the default), ``airfoil="E63@0.25,APC12@0.45"`` (a UIUC table's sections),
        ``sections_from=pe0_path`` (APC's sections on UIUC's measured blade); the other
        ``options`` are :meth:`from_qprop`'s."""
        return cls.from_qprop(path, **options)

    @classmethod
    def from_scan(cls, path: PathLike, out: Optional[PathLike] = None, **options: Any) -> "Prop":
        """Blade geometry from a scan (STL mesh, PLY / COLMAP / XYZ cloud) by ``propbet scan``:
        ``options`` are its flags (``units="mm"``, ``stations="0.2:0.96/20"``,
        ``blade_colour=...``, ``reference=path``, ...). Written into ``out`` (a new temporary
        folder without it); the prop is the scan's ``prop.qprop``, its sections the scan's
        airfoils."""
        folder, scratch = _folder(out, "scan")
        ok = execute("scan", os.fspath(path), "-o", str(folder), *_flags(options))
        if not ok:
            warnings.warn(f"propbet scan: some stations could not be measured or fitted (see {folder})")
        airfoils = folder / "airfoils"
        sections = ["--station-airfoils", str(airfoils)] if airfoils.is_dir() else []
        prop = cls(folder / "prop.qprop", sections=sections, folder=folder)
        prop._scratch = scratch
        return prop

    @classmethod
    def from_case(cls, case: PathLike, out: Optional[PathLike] = None) -> "Prop":
        """The model of a case directory (``case.toml``): its scan and polars stages run as
        ``propbet run`` runs them, into ``out`` (a new temporary folder without it); the
        prediction's model flags, air and sweep are the case's (``predict()`` without
        ``rpm`` sweeps the case's operating points)."""
        folder, scratch = _folder(out, "case")
        stages = _native.case_stages(os.fspath(case), str(folder))
        geometry, sections, predict = None, [], None
        for argv in stages:
            if argv[0] == "scan":
                execute(*argv)
            elif argv[0] == "polars":
                # `propbet run` makes each stage's folder; the command alone writes into one.
                for flag in ("--out-prop", "--out-polars"):
                    target = _value(argv, flag)
                    if target is not None:
                        Path(target).parent.mkdir(parents=True, exist_ok=True)
                execute(*argv)
                geometry, sections = _polars_inputs(argv)
            elif argv[0] == "predict":
                predict = argv
        if predict is None:
            raise InternalError(f"{case}: the case has no prediction stage")
        model, sweep, air = _split_predict(predict[1:])
        prop = _value(model, "--prop")
        polars = _value(model, "--polars")
        rest = _without(model, {"--prop", "--polars"})
        made = cls(
            prop, polars=polars, model_flags=rest, geometry=geometry, sections=sections,
            folder=folder, sweep=sweep, air_flags=air,
        )
        made._scratch = scratch
        return made

    @property
    def stations(self) -> pd.DataFrame:
        """The prop file's rows in SI: ``r_m``, ``r_over_tip``, ``chord_m``, ``beta_deg`` and
        the ten QPROP section coefficients of each row."""
        argv = ["prop", str(self.path)]
        argv += [x for p in _pairs(self._model_flags) if _flag_name(p[0]) in {"--units", "--qprop-compat"} for x in p]
        return _csv(_relayed(lambda: _native.stations(argv)))

    def polars(
        self,
        rpm: Any,
        j: Any = None,
        v: Any = None,
        *,
        engine: Optional[str] = None,
        ncrit: Optional[float] = None,
        airfoil: Optional[PathLike] = None,
        out: Optional[PathLike] = None,
        **options: Any,
    ) -> "Prop":
        """Polars of every station at its Reynolds and Mach numbers over these operating points
        (``propbet polars``, with its cache): ``engine`` "xfoil", "neuralfoil" or "auto",
        ``ncrit``, ``trip``, ``airfoil`` (a file or a NACA 4-digit name; the scan's sections
        without it), and the command's other flags. Returns the prop with the tables as its
        section model; files in ``out`` (a new temporary folder without it)."""
        folder, scratch = _folder(out, "polars")
        sections = ["--airfoil", os.fspath(airfoil)] if airfoil is not None else self._sections
        if not sections:
            raise InputError(
                f"{self.geometry}: no sections known for this blade: give airfoil= (a file or a NACA name)"
            )
        argv = [
            "polars", "--geometry", str(self.geometry), *sections, *_sweep(rpm, j, v),
            *_flags({"engine": engine, "ncrit": ncrit, **options}),
            "--out-prop", str(folder / "prop.qprop"), "--out-polars", str(folder / "polars.json"),
        ]
        if not execute(*argv):
            warnings.warn(f"propbet polars: some stations were not fitted or XFOIL faulted ({folder})")
        made = Prop(
            folder / "prop.qprop", polars=folder / "polars.json", model_flags=self._model_flags,
            geometry=self.geometry, sections=self._sections, folder=folder, sweep=self._sweep,
            air_flags=self._air,
        )
        # The temporary folder lives as long as the props that read from it.
        made._scratch = (scratch, getattr(self, "_scratch", None))
        return made

    def predict(
        self,
        rpm: Any = None,
        j: Any = None,
        v: Any = None,
        *,
        air: Optional[Mapping[str, Any]] = None,
        effects: Iterable[str] = (),
        band: bool = False,
        stations: bool = False,
    ) -> Any:
        """Performance over every RPM with every J (or V, or static without either): a
        DataFrame with the columns of ``propbet predict``'s CSV and its numbers (7 significant
        digits, the solver's accuracy; NaN where it leaves a cell empty) (``rpm``, ``v_m_s``, ``j``,
        ``thrust_n``, ``torque_nm``, ``power_w``, ``ct``, ``cp``, ``cq``, ``eta``, ...), and
        ``ct_lo`` ... ``eta_hi`` with ``band=True``. ``air`` as a dict (``{"rho": 1.2}``,
        ``{"temp": "20C", "pressure": "1013hPa"}``), ``effects`` added to the model
        (``"pitch-offset:deg=1.2"``). With ``stations=True``, a pair: the sweep and the
        per-station table."""
        if rpm is None and self._sweep:
            points = list(self._sweep)
            if j is not None or v is not None:
                raise InputError("j and v: give rpm with them")
        else:
            points = _sweep(rpm, j, v)
        _check_options("predict", {"effects": effects}, command=None, extra={"effects": "many"})
        _switch("predict", "band", band)
        _switch("predict", "stations", stations)
        effect = [effects] if isinstance(effects, str) else list(effects)
        argv = [
            "predict", *self.model_args(), *_flags({"effect": effect or None}), *points,
            *(_air(air) if air is not None else self._air), *(["--band"] if band else []),
        ]
        table, per_station, failed, at_points = _relayed(lambda: _native.predict(argv, stations))
        sweep = _frame(table)
        sweep.attrs["not_converged"] = failed
        if failed:
            warnings.warn(
                f"propbet predict: {failed} station solutions at {at_points} operating points did not converge"
            )
        return (sweep, _frame(per_station)) if stations else sweep


def _value(argv: Sequence[str], flag: str) -> Optional[str]:
    for i, a in enumerate(argv):
        if a == flag and i + 1 < len(argv):
            return argv[i + 1]
        if a.startswith(flag + "="):
            return a[len(flag) + 1 :]
    return None


# predict's switches (flags without a value).
_SWITCHES = {"--band", "--qprop-compat", "--no-tip-loss"}


def _pairs(argv: Sequence[str]) -> Iterator[list[str]]:
    """A command line's flags, each with its value: a flag alone when it is a known switch,
    holds its value (``--rpm=4000``), or the next word is another flag (a value never starts
    with ``--``: a negative number has one dash)."""
    i = 0
    while i < len(argv):
        a = argv[i]
        alone = a in _SWITCHES or "=" in a or not a.startswith("-") or i + 1 == len(argv)
        if alone or argv[i + 1].startswith("--"):
            yield [a]
            i += 1
        else:
            yield [a, argv[i + 1]]
            i += 2


def _flag_name(a: str) -> str:
    return a.split("=", 1)[0]


def _without(argv: Sequence[str], flags: set) -> list[str]:
    return [x for p in _pairs(argv) if _flag_name(p[0]) not in flags for x in p]


def _split_predict(argv: Sequence[str]) -> tuple:
    """A predict command line's model flags, its sweep and its air."""
    sweep_flags = {"--rpm", "--j", "--v"}
    air_flags = {"--rho", "--mu", "--a", "--temp", "--pressure", "--humidity"}
    output = {"--out", "-o", "--format", "--out-stations", "--band"}
    model, sweep, air = [], [], []
    for p in _pairs(argv):
        name = _flag_name(p[0])
        if name in sweep_flags:
            sweep += p
        elif name in air_flags:
            air += p
        elif name not in output:
            model += p
    return model, sweep, air


def _polars_inputs(argv: Sequence[str]) -> tuple:
    """A polars command line's geometry and sections."""
    geometry = _value(argv, "--geometry")
    sections = [x for p in _pairs(argv) if _flag_name(p[0]) in {"--airfoil", "--station-airfoils"} for x in p]
    return geometry, sections


def read_measurements(paths: Union[PathLike, Sequence[PathLike]], **options: Any) -> pd.DataFrame:
    """Measured files (RCbenchmark / Tyto logs, UIUC files, generic CSV with ``columns=`` a
    TOML column map) read as ``compare`` reads them: one row per steady point (``rpm``,
    ``v_m_s`` or ``j``, ``thrust_n`` and ``torque_nm`` or ``ct`` and ``cp``, their standard
    deviations, ``samples`` / ``thrust_samples`` / ``torque_samples`` the readings of each
    signal that made the point, the lines they came from). ``options``: ``poles``,
    ``rpm_source``, ``atmosphere``, ``rho``, ``columns``. The rows not used are in
    ``.attrs["dropped"]`` (file, line, reason, detail); a file that cannot be read is one row
    there with reason ``file_refused`` and no line, as ``compare`` goes on without it."""
    argv = _flags({"measured": paths, **options})
    points, dropped = _relayed(lambda: _native.read_measurements(argv))
    table = _csv(points)
    table.attrs["dropped"] = _csv(dropped)
    return table


@dataclass
class Comparison:
    """What ``propbet compare`` writes: ``metrics`` (metrics.json), ``points`` (points.csv:
    measured beside predicted), ``summary`` (summary.json), the ``report`` page, and ``ok``
    (False when it reported problems: dropped rows, unconverged points). Unpacks as
    ``metrics, points``."""

    metrics: dict
    points: pd.DataFrame
    summary: dict
    report: Path
    folder: Path
    ok: bool
    _scratch: Any = field(default=None, repr=False, compare=False)

    def __iter__(self) -> Iterator[Any]:
        return iter((self.metrics, self.points))


def _measured_args(measured: Any, options: Mapping[str, Any]) -> list[str]:
    return _flags({"measured": measured, **options})


def _prop(prop: Union[Prop, PathLike]) -> Prop:
    return prop if isinstance(prop, Prop) else Prop.from_qprop(prop)


def compare(
    prop: Union[Prop, PathLike],
    measured: Union[PathLike, Sequence[PathLike]],
    out: Optional[PathLike] = None,
    **options: Any,
) -> Comparison:
    """Measurements against the prediction (``propbet compare``): ``options`` are its flags
    (``per3=path``, ``poles=14``, ``atmosphere="20C,101325,40%"``, ``columns=path``, ...).
    Files in ``out`` (a new temporary folder without it)."""
    prop = _prop(prop)
    folder, scratch = _folder(out, "compare")
    ok = execute("compare", *prop.model_args(), *_measured_args(measured, options), "--out", str(folder))
    return Comparison(
        metrics=_read_json(folder / "metrics.json"),
        points=_read_csv(folder / "points.csv"),
        summary=_read_json(folder / "summary.json"),
        report=folder / "report.html",
        folder=folder,
        ok=ok,
        _scratch=scratch,
    )


@dataclass
class Diagnosis:
    """What ``propbet diagnose`` writes: ``answer`` (the verdict in words), ``effects`` (the
    effects it found, as ``--effect`` specs), ``ladder`` and ``ranking`` (DataFrames), the whole
    ``diagnosis.json`` as ``json``, ``summary`` (summary.json), the ``report`` page, ``ok``."""

    answer: str
    effects: list
    ladder: pd.DataFrame
    ranking: pd.DataFrame
    json: dict
    summary: dict
    report: Path
    folder: Path
    ok: bool
    _scratch: Any = field(default=None, repr=False, compare=False)


def diagnose(
    prop: Union[Prop, PathLike],
    measured: Union[PathLike, Sequence[PathLike]],
    out: Optional[PathLike] = None,
    **options: Any,
) -> Diagnosis:
    """Which physical effect is missing (``propbet diagnose``): ``options`` are its flags
    (``effects="all"`` or a list of ids, ``folds``, ``max_steps``, ``window``, the measurement
    flags). Files in ``out`` (a new temporary folder without it)."""
    prop = _prop(prop)
    folder, scratch = _folder(out, "diagnose")
    options = dict(options)
    candidates = options.pop("effects", None)
    if candidates is not None and not isinstance(candidates, str):
        candidates = ",".join(candidates)
    argv = ["diagnose", *prop.model_args(), *_measured_args(measured, options)]
    argv += _flags({"effects": candidates}) + ["--out", str(folder)]
    ok = execute(*argv)
    doc = _read_json(folder / "diagnosis.json") or {}
    summary = _read_json(folder / "summary.json") or {}
    found = summary.get("diagnosis", {})
    inner = doc.get("diagnosis", {})
    return Diagnosis(
        answer=found.get("verdict", ""),
        effects=list(doc.get("final_effects", [])),
        ladder=pd.DataFrame(inner.get("ladder", [])),
        ranking=pd.DataFrame(inner.get("ranking", [])),
        json=doc,
        summary=summary,
        report=folder / "report.html",
        folder=folder,
        ok=ok,
        _scratch=scratch,
    )


@dataclass
class RunResult:
    """What ``propbet run`` writes: ``summary`` (summary.json: the headline, the diagnosis,
    every stage's command), the ``sweep`` (predict/sweep.csv), the compared ``points``
    (compare/points.csv, empty without measurements), the ``diagnosis`` (diagnosis.json, None
    without measurements), the ``report`` page, and ``ok`` (False when it reported problems)."""

    summary: dict
    sweep: pd.DataFrame
    points: pd.DataFrame
    diagnosis: Optional[dict]
    report: Path
    folder: Path
    ok: bool
    _scratch: Any = field(default=None, repr=False, compare=False)


def run(case: Optional[PathLike] = None, out: Optional[PathLike] = None, **options: Any) -> RunResult:
    """The main job on a case directory (``propbet run``; the shipped default case without
    one): scan, polars, sweeps, comparison, diagnosis and one report, in ``out`` (a new
    temporary folder without it). ``options``: ``verbose``, ``xfoil``, ``cache``, ...
    """
    folder, scratch = _folder(out, "run")
    argv = ["run"] + ([os.fspath(case)] if case is not None else []) + ["-o", str(folder)] + _flags(options)
    ok = execute(*argv)
    return RunResult(
        summary=_read_json(folder / "summary.json"),
        sweep=_read_csv(folder / "predict" / "sweep.csv"),
        points=_read_csv(folder / "compare" / "points.csv"),
        diagnosis=_read_json(folder / "diagnose" / "diagnosis.json"),
        report=folder / "report.html",
        folder=folder,
        ok=ok,
        _scratch=scratch,
    )


@dataclass
class Validation:
    """What ``propbet validate`` writes: the ``table`` (validation.csv, one row per prop),
    the ``markdown`` text (validation.md), the ``report`` page, and ``ok``."""

    table: pd.DataFrame
    markdown: str
    report: Path
    folder: Path
    ok: bool
    _scratch: Any = field(default=None, repr=False, compare=False)


def validate(
    uiuc: PathLike,
    pe0: PathLike,
    airfoils: PathLike,
    out: Optional[PathLike] = None,
    **options: Any,
) -> Validation:
    """Validation on UIUC's measurements (``propbet validate``): ``options`` are its flags
    (``per3=path``, ``only="apce_9x6"`` or a list, ``engine="neuralfoil"``, ``quiet=True``,
    ``trip``, ``ncrit``, ...). Files in ``out`` (a new temporary folder without it)."""
    folder, scratch = _folder(out, "validate")
    options = dict(options)
    only = options.pop("only", None)
    if only is not None and not isinstance(only, str):
        only = ",".join(only)
    argv = ["validate", "--uiuc", os.fspath(uiuc), "--pe0", os.fspath(pe0), "--airfoils", os.fspath(airfoils)]
    argv += _flags({"only": only, **options}) + ["-o", str(folder)]
    ok = execute(*argv)
    md = folder / "validation.md"
    return Validation(
        table=_read_csv(folder / "validation.csv"),
        markdown=md.read_text() if md.is_file() else "",
        report=folder / "validation.html",
        folder=folder,
        ok=ok,
        _scratch=scratch,
    )

"""propbet from Python: propeller performance from geometry, compared with measurements.

The same engine as the ``propbet`` command line, run in this process through propbet's typed
API: every function here is a command with its settings given as keyword arguments (``ncrit=7``,
``rpm=[4000, 6000]`` or ``rpm="4000:8000:1000"``, ``qprop_compat=True``), never as a command
line, and its tables returned as pandas DataFrames with the columns and digits of the files the
command writes. Nothing is computed twice: the numbers are the command line's.

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
from ._native import Battery, InputError, InternalError, Motor

__all__ = [
    "expected_accuracy",
    "Prop",
    "Motor",
    "Battery",
    "FittedMotor",
    "fit_motor",
    "compare_props",
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


class Prop:
    """A propeller model: a blade file, how it is read, and (after :meth:`polars`) the
    tabulated polars that replace its section coefficients.

    Made by :meth:`from_qprop`, :meth:`from_file`, :meth:`from_scan` or :meth:`from_case`.
    """

    def __init__(
        self,
        model: Any,
        *,
        geometry: Optional[PathLike] = None,
        sections: Optional[Mapping[str, str]] = None,
        folder: Optional[PathLike] = None,
    ) -> None:
        self.model = model
        """The typed model (``propbet._native.Model``) every prediction uses."""
        self.path = Path(model.prop)
        """The blade file the predictions read."""
        self.polars_file = Path(model.polars) if model.polars is not None else None
        """The tabulated polars (JSON) that replace the file's coefficients, if any."""
        self.geometry = Path(geometry) if geometry is not None else self.path
        """The blade geometry :meth:`polars` computes polars for."""
        self.folder = Path(folder) if folder is not None else None
        """The folder the scan, polars or case stages wrote, if any."""
        self._sections = dict(sections or {})
        self._scratch: Any = None

    def __repr__(self) -> str:
        polars = f", polars={str(self.polars_file)!r}" if self.polars_file else ""
        return f"Prop({str(self.path)!r}{polars})"

    @classmethod
    def from_qprop(cls, path: PathLike, **options: Any) -> "Prop":
        """A QPROP prop file as it is. ``options`` are the model's settings (as ``propbet
        predict``'s flags): ``units="in"``, ``qprop_compat=True``, ``no_tip_loss=True``,
        ``dbeta=1.5`` [deg], ``rotation="snel"``, ``drag_factor=1.1``,
        ``effects=["pitch-offset:deg=1"]``, ``user_effects=path``, ``polars=path`` (tables from
        :meth:`polars`). A misspelt or mistyped keyword is a TypeError naming it."""
        effects = options.pop("effects", None)
        if effects is not None:
            options["effects"] = [effects] if isinstance(effects, str) else effects
        prop = cls(_native.Model(path, **options))
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
    def from_scan(
        cls,
        path: PathLike,
        out: Optional[PathLike] = None,
        *,
        reference: Optional[PathLike] = None,
        name: Optional[str] = None,
        **settings: Any,
    ) -> "Prop":
        """Blade geometry from a scan (STL mesh, PLY / COLMAP / XYZ cloud) by ``propbet scan``:
        ``settings`` are its settings, a case's ``[geometry]`` keys (``units="mm"``,
        ``stations="0.2:0.96/20"``, ``blade_colour=...``, ``box=...``, ``planar=True``, ...),
        ``reference`` a geometry table to draw beside it. Written into ``out`` (a new temporary
        folder without it); the prop is the scan's ``prop.qprop``, its sections the scan's
        airfoils."""
        folder, scratch = _folder(out, "scan")
        text = json.dumps(settings, default=os.fspath)
        ok = _relayed(lambda: _native.scan(os.fspath(path), str(folder), text, reference=reference, name=name))
        if not ok:
            warnings.warn(f"propbet scan: some stations could not be measured or fitted (see {folder})")
        airfoils = folder / "airfoils"
        sections = {"station_airfoils": str(airfoils)} if airfoils.is_dir() else {}
        prop = cls(_native.Model(folder / "prop.qprop"), sections=sections, folder=folder)
        prop._scratch = scratch
        return prop

    @classmethod
    def from_case(cls, case: PathLike, out: Optional[PathLike] = None) -> "Prop":
        """The model of a case directory (``case.toml``): its scan and polars stages run as
        ``propbet run`` runs them, into ``out`` (a new temporary folder without it); the
        prediction's model, air and sweep are the case's (``predict()`` without ``rpm``
        sweeps the case's operating points)."""
        folder, scratch = _folder(out, "case")
        model, polars = _relayed(lambda: _native.case_model(os.fspath(case), str(folder)))
        geometry, sections = None, {}
        if polars is not None:
            geometry, airfoil, station_airfoils = polars
            if airfoil is not None:
                sections["airfoil"] = airfoil
            if station_airfoils is not None:
                sections["station_airfoils"] = str(station_airfoils)
        made = cls(model, geometry=geometry, sections=sections, folder=folder)
        made._scratch = scratch
        return made

    @property
    def stations(self) -> pd.DataFrame:
        """The prop file's rows in SI: ``r_m``, ``r_over_tip``, ``chord_m``, ``beta_deg`` and
        the ten QPROP section coefficients of each row."""
        return _csv(_relayed(lambda: _native.stations(self.model)))

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
        without it), and the command's other settings (``alpha``, ``panels``, ``iter``,
        ``thickness``, ``ncrit_effect``, ``air``, ``xfoil``, ``cache``, ``quiet``, ...). Returns the prop with the tables as its
        section model; files in ``out`` (a new temporary folder without it)."""
        folder, scratch = _folder(out, "polars")
        sections = {"airfoil": os.fspath(airfoil)} if airfoil is not None else self._sections
        if not sections:
            raise InputError(
                f"{self.geometry}: no sections known for this blade: give airfoil= (a file or a NACA name)"
            )
        if isinstance(options.get("ncrit_effect"), (int, float)):
            options["ncrit_effect"] = [options["ncrit_effect"]]
        ok = _relayed(lambda: _native.polars(
            os.fspath(self.geometry), str(folder / "prop.qprop"), str(folder / "polars.json"),
            rpm=rpm, j=j, v=v, engine=engine, ncrit=ncrit, **sections, **options))
        if not ok:
            warnings.warn(f"propbet polars: some stations were not fitted or XFOIL faulted ({folder})")
        made = Prop(
            self.model.with_tables(folder / "prop.qprop", folder / "polars.json"),
            geometry=self.geometry, sections=self._sections, folder=folder,
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
        motor: Optional["Motor"] = None,
        volts: Any = None,
        amps: Any = None,
        thrust: Any = None,
        throttle: Any = None,
        battery: Optional["Battery"] = None,
    ) -> Any:
        """Performance over every RPM with every J (or V, or static without either): a
        DataFrame with the columns of ``propbet predict``'s CSV and its numbers (7 significant
        digits, the solver's accuracy; NaN where it leaves a cell empty) (``rpm``, ``v_m_s``, ``j``,
        ``thrust_n``, ``torque_nm``, ``power_w``, ``ct``, ``cp``, ``cq``, ``eta``, ...), and
        ``ct_lo`` ... ``eta_hi`` with ``band=True``. ``air`` as a dict (``{"rho": 1.2}``,
        ``{"temp": "20C", "pressure": "1013hPa"}``), ``effects`` added to the model
        (``"pitch-offset:deg=1.2"``). With ``stations=True``, a pair: the sweep and the
        per-station table.

        With a ``motor`` (:class:`Motor`) the propeller turns where the motor's torque meets
        its own, at each of ``volts``, ``amps``, ``thrust`` [N] (hover), ``rpm`` or, with a
        ``battery`` (:class:`Battery`), ``throttle`` (0 to 1), and each airspeed ``v``: the
        columns of ``propbet predict --motor`` (``rpm``, ``volts``, ``amps``, ``thrust_n``,
        ``shaft_power_w``, ``electrical_power_w``, ``eta_motor``, ``eta_total``, ``g_per_w``,
        ...; with a battery ``throttle``, ``battery_amps``, ``endurance_min``, ...; with
        ``band=True`` the propeller's ``ct_lo`` ... ``eta_hi`` at each operating point); a point
        without an operating point says why in ``no_solution``. With ``stations=True``, a pair:
        the table and the per-station table of every operating point found."""
        if motor is not None:
            if j is not None or effects:
                raise InputError("motor: j and effects are not available with a motor; give v= (airspeeds) instead of j=")
            table, problems, per_station = _relayed(lambda: _native.powered(
                self.model, motor, volts=volts, amps=amps, thrust=thrust, rpm=rpm, throttle=throttle,
                battery=battery, v=v, air=air, band=band, stations=stations))
            for p in problems:
                warnings.warn(p, PropbetWarning, stacklevel=2)
            return (_frame(table), _frame(per_station)) if stations else _frame(table)
        if any(x is not None for x in (volts, amps, thrust, throttle, battery)):
            raise InputError("volts, amps, thrust, throttle, battery: give a motor= with them")
        effects = [effects] if isinstance(effects, str) else list(effects)
        table, per_station, failed, at_points = _relayed(lambda: _native.predict(
            self.model, rpm, j, v, air=air, effects=effects, band=band, stations=stations))
        sweep = _frame(table)
        sweep.attrs["not_converged"] = failed
        if failed:
            warnings.warn(
                f"propbet predict: {failed} station solutions at {at_points} operating points did not converge"
            )
        return (sweep, _frame(per_station)) if stations else sweep


def _files(paths: Union[PathLike, Sequence[PathLike]]) -> list:
    return [os.fspath(paths)] if isinstance(paths, (str, os.PathLike)) else [os.fspath(p) for p in paths]


def read_measurements(paths: Union[PathLike, Sequence[PathLike]], **options: Any) -> pd.DataFrame:
    """Measured files (RCbenchmark / Tyto logs, UIUC files, generic CSV with ``columns=`` a
    TOML column map) read as ``compare`` reads them: one row per steady point (``rpm``,
    ``v_m_s`` or ``j``, ``thrust_n`` and ``torque_nm`` or ``ct`` and ``cp``, their standard
    deviations, ``samples`` / ``thrust_samples`` / ``torque_samples`` the readings of each
    signal that made the point, the lines they came from). ``options``: ``poles``,
    ``rpm_source``, ``atmosphere``, ``rho``, ``columns``. The rows not used are in
    ``.attrs["dropped"]`` (file, line, reason, detail); a file that cannot be read is one row
    there with reason ``file_refused`` and no line, as ``compare`` goes on without it."""
    points, dropped = _relayed(lambda: _native.read_measurements(_files(paths), **options))
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


def _prop(prop: Union[Prop, PathLike]) -> Prop:
    return prop if isinstance(prop, Prop) else Prop.from_qprop(prop)


def compare(
    prop: Union[Prop, PathLike],
    measured: Union[PathLike, Sequence[PathLike]],
    out: Optional[PathLike] = None,
    **options: Any,
) -> Comparison:
    """Measurements against the prediction (``propbet compare``): ``options`` are its
    settings (``per3=path``, ``qprop_output=path``, ``motor=path``, ``poles=14``,
    ``rpm_source="optical"``, ``atmosphere="20C,101325,40%"``, ``rho``, ``columns=path``).
    Files in ``out`` (a new temporary folder without it)."""
    prop = _prop(prop)
    folder, scratch = _folder(out, "compare")
    ok, metrics, summary, points = _relayed(
        lambda: _native.compare(prop.model, _files(measured), str(folder), **options))
    return Comparison(
        metrics=json.loads(metrics),
        points=_csv(points),
        summary=json.loads(summary),
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
    """Which physical effect is missing (``propbet diagnose``): ``options`` are its settings
    (``effects="all"`` or a list of ids, ``folds``, ``max_steps``, ``window``, and
    :func:`compare`'s measurement settings). Files in ``out`` (a new temporary folder without
    it)."""
    prop = _prop(prop)
    folder, scratch = _folder(out, "diagnose")
    options = dict(options)
    candidates = options.pop("effects", None)
    if isinstance(candidates, str):
        candidates = candidates.split(",")
    ok, doc, summary = _relayed(
        lambda: _native.diagnose(prop.model, _files(measured), str(folder), effects=candidates, **options))
    doc = json.loads(doc)
    summary = json.loads(summary)
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
    temporary folder without it). ``options``: ``verbose``, ``inputs_anywhere``, ``engine``,
    ``xfoil``, ``cache``, ``no_cache``, ``quiet``, ``xfoil_budget``, ``neuralfoil_size``.
    """
    folder, scratch = _folder(out, "run")
    case = os.fspath(case) if case is not None else None
    ok, summary, sweep, points, diagnosis = _relayed(lambda: _native.run(case, str(folder), **options))
    return RunResult(
        summary=json.loads(summary),
        sweep=_csv(sweep) if sweep else pd.DataFrame(),
        points=_csv(points) if points else pd.DataFrame(),
        diagnosis=json.loads(diagnosis) if diagnosis else None,
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
    """Validation on UIUC's measurements (``propbet validate``): ``options`` are its settings
    (``per3=path``, ``only="apce_9x6"`` or a list, ``engine="neuralfoil"``, ``quiet=True``,
    ``trip``, ``ncrit``, ``section_model``, ``geometry``, ``generic_section``, ...). Files in ``out`` (a new temporary folder without it)."""
    folder, scratch = _folder(out, "validate")
    options = dict(options)
    only = options.pop("only", None)
    if only is not None and not isinstance(only, str):
        only = ",".join(only)
    if isinstance(options.get("ncrit_effect"), (int, float)):
        options["ncrit_effect"] = [options["ncrit_effect"]]
    ok, markdown, table = _relayed(lambda: _native.validate(
        os.fspath(uiuc), os.fspath(pe0), os.fspath(airfoils), str(folder), only=only, **options))
    return Validation(
        table=_csv(table),
        markdown=markdown,
        report=folder / "validation.html",
        folder=folder,
        ok=ok,
        _scratch=scratch,
    )


@dataclass
class FittedMotor:
    """A motor fitted to stand logs (:func:`fit_motor`): the ``motor`` (:class:`Motor`), its
    QPROP motor file's ``text`` (the fit's numbers in its comments), ``r``, ``io`` and ``kv``
    each as (value, 95 % half-width) [ohm, A, rpm/V], ``kq`` too for a type 2 fit (None for
    type 1, whose Kq is Kv), ``kv_from`` ("given" or "esc_duty"), ``torque_kv`` (the torque
    side's Kv, 1/Kt, where the ESC command allows it; None otherwise), the
    supply current's ``rms_current`` error and ``held_out_median`` (each step predicted with
    itself left out), ``notes`` and ``misses`` in words, and the fitted ``steps``
    (DataFrame: ``rpm``, ``torque_nm``, ``volts``, ``amps``, ``esc_us``, ``amps_held_out``)."""

    motor: Motor
    text: str
    r: tuple
    io: tuple
    kv: tuple
    kq: Optional[tuple]
    kv_from: str
    torque_kv: Optional[tuple]
    rms_current: float
    held_out_median: Optional[float]
    notes: list
    misses: Optional[str]
    steps: pd.DataFrame


def expected_accuracy(prop: Optional[PathLike] = None) -> dict:
    """What to expect of a prediction of ``prop`` (its file: a PE0 file, a UIUC geometry table,
    a QPROP file; None for a scan) before any measurement, from the validation shipped with
    propbet: ``sentence`` (what ``predict`` prints), and its APC family's or maker line's
    ``group``, ``props``, ``ct_median``, ``cp_median``, ``band_ct_inside`` and
    ``band_cp_inside`` (None where the validation holds no prop of its kind, which the
    sentence says)."""
    name = None if prop is None else Path(prop).name
    return dict(_native.expected_accuracy(name))


def fit_motor(measured: Union[PathLike, Sequence[PathLike]], *, kv: Optional[float] = None, kq: bool = False, name: Optional[str] = None, **options: Any) -> FittedMotor:
    """R, Io and Kv of a type 1 motor fitted to stand logs that carry speed, torque, voltage
    and current (``propbet motor fit``): ``kv`` the maker's Kv [rpm/V] (without it, found
    from the ESC command's duty), ``kq=True`` a type 2 motor with its torque constant Kq fitted
    on its own (``--kq``), ``name`` the motor's; ``options`` the measurement settings of
    :func:`compare` (``poles``, ``rpm_source``, ...)."""
    motor, text, summary, steps = _relayed(lambda: _native.fit_motor(_files(measured), kv=kv, kq=kq, name=name, **options))
    return FittedMotor(
        motor=motor, text=text, r=summary["r"], io=summary["io"], kv=summary["kv"], kq=summary["kq"],
        kv_from=summary["kv_from"], torque_kv=summary["torque_kv"], rms_current=summary["rms_current"],
        held_out_median=summary["held_out_median"], notes=summary["notes"], misses=summary["misses"],
        steps=_frame(steps),
    )


def compare_props(
    props: Sequence[Union[Prop, PathLike]],
    motor: Motor,
    battery: Battery,
    hover: float,
    *,
    v: Any = None,
    air: Optional[Mapping[str, Any]] = None,
) -> pd.DataFrame:
    """Propellers side by side on one motor and battery (``propbet compare-props``): ranked by
    grams per watt at ``hover`` thrust [N] (one propeller's share of the weight), with hover
    throttle, current, RPM and endurance and full-throttle thrust and current (static; ``v``
    the full-throttle curves' airspeeds), each g/W with its range over the prediction's band:
    props.csv's columns. ``.attrs["answer"]`` holds the answer's sentences."""
    named = []
    for p in props:
        prop = _prop(p)
        named.append((prop.path.name, prop.model))
    table, answer = _relayed(lambda: _native.compare_props(named, motor, battery, hover, v=v, air=air))
    frame = _frame(table)
    frame.attrs["answer"] = answer
    return frame

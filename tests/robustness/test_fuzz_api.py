"""Property-based fuzz of the public API and the command line (issue 15, item 7).

Arbitrary overrides, inside and outside the schema (every numeric and choice key of
:mod:`sim.config_schema`, every bearing of ``conf/bearing``), go through ``sim.load_config`` and
``sim.simulate``; each example must end in one of three ways:

- a converged result: every value finite, the torque breakdown summing to the torque, a power
  loss >= 0, and the load distribution in balance, recomputed independently of the solver's
  residual bookkeeping (tests/helpers.py: each loaded roller's contact forces against its body
  loads; for an untilted TSRB the inner raceway's forces against (Fa, Fr));
- a recorded non-convergence (``converged = False``, its values NaN);
- the project's input error (``InputError``, ``GeometryError``, ``ConfigError``).

Any other exception fails, as does an example slower than the per-case deadline (a hang).
A few examples run ``python -m sim.run`` as a user does: exit 0 with a result file, exit 1 with
the result file when a case did not converge, or exit 2 with one ``error:`` line; never a
traceback.

Profiles (``HYPOTHESIS_PROFILE``): ``ci`` (default) is derandomised and small, so the file
runs in well under 2 minutes on 2 cores; ``long`` is the long fuzz (``FUZZ_EXAMPLES`` examples,
default 2000, and ``FUZZ_CLI_EXAMPLES`` command lines, default 30; random seed unless
``--hypothesis-seed`` is given): ``HYPOTHESIS_PROFILE=long
nice -n 10 python -m pytest tests/robustness/test_fuzz_api.py --hypothesis-seed=N``. Neither
writes an example database; a failure prints its reproduction blob.
"""
import math
import os
import re
from dataclasses import fields, is_dataclass

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import sim
from sim.config_schema import SCHEMAS, Choice, Flag, Number
from sim.errors import GeometryError, InputError
from tests.helpers import race_forces, roller_residuals
from tests.robustness.common import REPO, run

#: per-example deadline [ms]: the slowest accepted case (a non-converging continuation of the
#: quasi-static solve with friction) takes about 15 s on a loaded 2-core machine
DEADLINE_MS = 60_000
_QUIET = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]
settings.register_profile("ci", max_examples=40, deadline=DEADLINE_MS, derandomize=True, database=None,
                          print_blob=True, suppress_health_check=_QUIET)
settings.register_profile("long", max_examples=int(os.environ.get("FUZZ_EXAMPLES", "2000")), deadline=DEADLINE_MS,
                          database=None, print_blob=True, suppress_health_check=_QUIET)
PROFILE = os.environ.get("HYPOTHESIS_PROFILE", "ci")
settings.load_profile(PROFILE)
# On a failure Hypothesis imports libcst (to propose an @example patch), whose mypy_extensions
# import warns DeprecationWarning; pyproject turns that into an error that hides the failure.
pytestmark = pytest.mark.filterwarnings("ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")

BEARINGS = sorted(p.stem for p in (sim.CONF_DIR / "bearing").glob("*.yaml"))
PROJECT_ERRORS = (InputError, GeometryError)   # ConfigError is an InputError


def _keys(schema, path):
    """(dotted key, check) of every numeric, choice and flag field of a group schema, nested ones included."""
    out = []
    for f in fields(schema):
        if is_dataclass(f.type):
            out += _keys(f.type, f"{path}.{f.name}")
        elif isinstance(f.metadata.get("check"), (Number, Choice, Flag)):
            out.append((f"{path}.{f.name}", f.metadata["check"]))
    return out


KEYS = [k for group, schema in SCHEMAS.items() for k in _keys(schema, group)
        if k[0] not in ("bearing.type", "output.cache_dir")]
LOAD_KEYS = [k for k in KEYS if k[0].startswith("load.")]


def _fmt(v):
    """A value as a Hydra override writes it."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("nan" if math.isnan(v) else ("inf" if v > 0 else "-inf"))
    if isinstance(v, list):
        return "[" + ",".join(_fmt(x) for x in v) + "]"
    return str(v)


def _number_inside(c):
    lo = c.low if math.isfinite(c.low) else -1e6
    hi = c.high if math.isfinite(c.high) else max(1e6, 1e6 * abs(lo))
    if c.integer:
        return st.integers(int(math.ceil(lo)), int(min(hi, lo + 1000)))
    inside = st.floats(lo, hi, exclude_min=c.low_open and lo == c.low, exclude_max=c.high_open and hi == c.high,
                       allow_nan=False)
    if lo >= 0.0 and hi > 0.0:   # wide ranges: log-uniform too (clamped inside the open bounds)
        top = math.log10(hi)
        bottom = math.log10(lo) if lo > 0.0 else top - 12.0
        least = float(np.nextafter(lo, math.inf)) if c.low_open else lo
        most = float(np.nextafter(hi, -math.inf)) if c.high_open and hi == c.high else hi
        inside = st.one_of(inside, st.floats(bottom, top).map(lambda e: min(most, max(10.0 ** e, least))))
    edges = [x for x in (c.low, c.high) if c.accepts_number(x)]   # and the closed bounds themselves
    return st.one_of(inside, st.sampled_from(edges)) if edges else inside


def _number_outside(c):
    out = [st.sampled_from([math.nan, math.inf, -math.inf, "abc"])]
    beyond = st.floats(1e-9, 1e3)   # distance past a bound, relative to 1 + |bound|
    if math.isfinite(c.low):
        out.append(beyond.map(lambda d: c.low - d * (1.0 + abs(c.low))))
        out.append(st.just(float(np.nextafter(c.low, -math.inf)) if not c.low_open else c.low))
    if math.isfinite(c.high):
        out.append(beyond.map(lambda d: c.high + d * (1.0 + abs(c.high))))
        out.append(st.just(float(np.nextafter(c.high, math.inf)) if not c.high_open else c.high))
    if c.integer:
        out.append(st.just(c.low + 0.5 if math.isfinite(c.low) else 0.5))
    return st.one_of(out)


def value_for(check):
    """Values of one key: mostly inside its range, sometimes just at or beyond a bound."""
    if isinstance(check, Flag):
        return st.booleans()
    if isinstance(check, Choice):
        return st.one_of(st.sampled_from(check.options), st.just("no_such_option"))
    if check.shape == "list":
        return st.lists(_number_inside(check), min_size=2, max_size=2)
    one = st.one_of(_number_inside(check), _number_inside(check), _number_inside(check), _number_outside(check))
    if check.shape == "number or list":
        return st.one_of(one, one, st.lists(_number_inside(check), min_size=2, max_size=2))
    return one


@st.composite
def overrides(draw):
    """A bearing, friction on or off, slices, and 1-3 keys (load keys twice as likely) with values."""
    items = [f"bearing={draw(st.sampled_from(BEARINGS))}",
             f"friction.enabled={_fmt(draw(st.booleans() | st.just(True)))}",
             f"solver.n_slices={draw(st.integers(4, 20))}"]
    chosen = {}
    for _ in range(draw(st.integers(1, 3))):
        name, check = draw(st.sampled_from(KEYS + LOAD_KEYS))
        chosen.setdefault(name, check)          # a key drawn twice is set once
    for name, check in chosen.items():
        prefix = "++" if name.split(".")[-1] in _TYPE_SPECIFIC else ""
        items.append(f"{prefix}{name}={_fmt(draw(value_for(check)))}")
    return items


# keys that a bearing type may lack in its config file (added with "++", refused on the other type)
_TYPE_SPECIFIC = {f.name for schema in SCHEMAS.values() for f in fields(schema) if f.metadata.get("only")} | {
    f.name for f in fields(SCHEMAS["bearing"].__dataclass_fields__["surface"].type) if f.metadata.get("only")}

FINITE_WHEN_CONVERGED = ("torque", "torque_component", "power_loss", "pmax", "Q", "Q_rib", "P", "P0", "C", "C0",
                         "cage_speed", "L_eff", "axial_displacement", "ring_displacement", "residual", "lambda_ratio")


def check_result(cfg, ds):
    """The invariants of a returned Dataset (module docstring)."""
    from sim.api.cases import operating_points
    from sim.api.simulation import build_models, resolved

    converged = ds["converged"].values[0]
    for name in FINITE_WHEN_CONVERGED:
        if name not in ds:
            continue
        values = ds[name].values[0]
        if "case" not in ds[name].dims:     # a design variable (C, C0)
            assert np.all(np.isfinite(values)), (name, values)
            continue
        assert np.all(np.isfinite(values[converged])), (name, values)
        if name not in ("P", "P0"):         # DATA.md: a failed case holds NaN (but its load-derived P, P0)
            assert np.all(np.isnan(values[~converged])), (name, values)
    if "torque" in ds:
        t = ds["torque"].values[0][converged]
        np.testing.assert_allclose(ds["torque_component"].values[0][converged].sum(axis=-1), t,
                                   rtol=1e-9, atol=1e-12 * np.abs(t).max(initial=0.0))
        assert np.all(ds["power_loss"].values[0][converged] >= 0.0)
        static = ds["speed"].values[converged] == 0.0
        assert np.all(ds["power_loss"].values[0][converged][static] == 0.0)
        assert np.all(t[static] >= 0.0)
    if not converged.any():
        return
    # the load distribution of the first converged case, recomputed from the solved state
    plain = resolved(cfg)
    model, _ = build_models(cfg, plain)
    op = operating_points(plain["load"])[int(np.flatnonzero(converged)[0])]
    raw = model.solve(op)
    assert raw["converged"]
    tol = max(10.0 * model.settings.tolerance, 1e-8)
    scale = max(op.Fa, op.Fr)
    assert np.all(np.abs(raw["residual"]) <= tol * scale), raw["residual"]
    residuals = roller_residuals(model, raw, op, reported=True)
    assert np.all(residuals < tol), residuals
    if model.geometry.type == "TSRB" and op.tilt_deg == 0.0:
        Fx, Fz = race_forces(model, raw, 1, 0.0)
        np.testing.assert_allclose([Fx + op.Fr, Fz + op.Fa], 0.0, atol=tol * scale)


def outcome(items):
    """'result' (invariants checked), or 'refused' (the project's input error); anything else raises."""
    try:
        cfg = sim.load_config(items)
        ds = sim.simulate(cfg)
    except PROJECT_ERRORS as exc:
        assert str(exc).strip(), items
        event(f"refused: {type(exc).__name__}")
        return "refused"
    check_result(cfg, ds)
    event(f"result: {int(ds['converged'].values.sum())} of {ds.sizes['case']} cases converged")
    return "result"


@given(overrides())
def test_public_api_gives_a_result_a_non_convergence_or_an_input_error(items):
    outcome(items)


@settings(max_examples=3 if PROFILE == "ci" else int(os.environ.get("FUZZ_CLI_EXAMPLES", "30")), deadline=None)
@given(overrides())
def test_command_line_exits_0_with_a_result_or_2_with_one_error_line(tmp_path_factory, items):
    """``python -m sim.run``: exit 0 and a result file; exit 1 with the result file when a case did
    not converge (sim.run's documented status, one line saying so); or exit 2 and one ``error:``
    line. Never a traceback."""
    folder = tmp_path_factory.mktemp("cli")
    out = run(["-m", "sim.run", *items, f"hydra.run.dir={folder / 'run'}", "output.cache_dir=null"], folder,
              timeout=DEADLINE_MS / 1e3 + 60)
    assert "Traceback" not in out.stderr, (items, out.stderr[-3000:])
    assert out.returncode in (0, 1, 2), (items, out.returncode, out.stderr[-3000:])
    lines = [line for line in out.stderr.splitlines() if line.strip()]
    if out.returncode == 2:
        assert lines and lines[-1].startswith("error: "), (items, out.stderr[-3000:])
        return
    if out.returncode == 1:   # a recorded non-convergence, nothing else
        assert lines and re.fullmatch(r"\d+ of \d+ cases have no result \(written with converged = False; "
                                      r"the reasons above and in its failed_cases attribute\)", lines[-1]), out.stderr
    assert list((folder / "run").glob("*.nc")), (items, out.stdout[-2000:])

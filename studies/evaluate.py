"""Full simulations of design points and their NetCDF record (issue 5, item 1).

A point that cannot be simulated is kept, never dropped: its ``status`` says why
(impossible geometry, not converged, failed) and its results are NaN (DATA.md).
"""
import time

import numpy as np
import xarray as xr

from sim.io import CASE_VARIABLES, case_coords, utc_now
from sim.api import GeometryError, InputError, OperatingPoint, simulate, worker_pool
from studies.space import DESIGN_PARAMETERS

# CF flags of the ``status`` variable
STATUS = {"ok": 0, "not_converged": 1, "geometry_error": 2, "failed": 3}
STATUS_NAMES = {v: k for k, v in STATUS.items()}

# Results kept per point besides the objective; names and units as in DATA.md.
RECORDED = ("pmax", "axial_displacement", "L_eff", "C_eff", "L10", "P", "edge_stress")
EDGE_MARGIN = "edge_stress_margin"
# the continuous form of the ``edge_stress`` flag, for a surrogate to model: the simulation's
# edge_interference, max over the races (> 0 exactly when edge_stress is flagged)
EDGE_MARGIN_ATTRS = {"units": "1", "long_name": "edge-stress margin: interference at the roller ends over the largest "
                                                "elastic approach, worst roller, race and end; > 0: edge stress "
                                                "(sim.physics.elasticity.edge_interference)"}


def design_config(base_cfg, values):
    """Copy of a composed simulation config with the bearing's design parameters replaced (a None
    value, a per-point osculation that follows kappa, is left as the template has it)."""
    cfg = base_cfg.copy()
    for key, value in values.items():
        if value is not None:
            cfg.bearing[key] = float(value)
    return cfg


def _scalar(da):
    """A result of one design and case as a float; extra dims (race) reduced by their maximum."""
    return float(da.isel(design=0, case=0).max())


def simulate_point(cfg, quantities):
    """Run the full simulation of one composed config and summarise it.

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed simulation config (bearing, load case, solver, ...).
    quantities : sequence of str
        Result variables to keep (DATA.md names; the objective among them).

    Returns
    -------
    ds : xarray.Dataset or None
        The full result (None when the geometry is impossible or the simulation failed).
    record : dict
        ``status`` (key of :data:`STATUS`), ``message``, ``values`` {name: float, NaN unless ok,
        plus ``edge_stress_margin``}, ``attrs`` {name: {units, long_name}}, ``wall_time`` [s].

    Raises
    ------
    sim.errors.InputError
        Bad load or solver input: the same for every point, so a configuration error.
    KeyError
        A quantity that a converged simulation does not produce.
    """
    record = {"status": "ok", "message": "", "values": {q: np.nan for q in (*quantities, EDGE_MARGIN)},
              "attrs": {}}
    ds = None
    t0 = time.perf_counter()
    try:
        ds = simulate(cfg)
    except InputError:
        raise
    except GeometryError as err:
        record.update(status="geometry_error", message=str(err))
    except Exception as err:  # a numerical failure of the simulation is a result of this point
        record.update(status="failed", message=f"{type(err).__name__}: {err}")
    else:
        if not bool(ds.converged.all()):
            # an unconverged result may lack variables altogether (sim.io writes what it has)
            record.update(status="not_converged", message=f"not converged after {int(ds.iterations.max())} iterations")
        else:
            missing = [q for q in quantities if q not in ds]
            if missing:
                raise KeyError(f"the simulation result has no {missing}; it has {sorted(ds.data_vars)}")
            record["attrs"] = {q: {k: ds[q].attrs.get(k, "") for k in ("units", "long_name")} for q in quantities}
            record["values"] = {q: _scalar(ds[q]) for q in quantities}
            record["values"][EDGE_MARGIN] = _scalar(ds.edge_interference)
    record["wall_time"] = time.perf_counter() - t0
    return ds, record


def evaluate_design(base_cfg, values, quantities):
    """Record (see :func:`simulate_point`) of the template config with design parameters ``values``."""
    return simulate_point(design_config(base_cfg, values), quantities)[1]


def evaluate_designs(case_cfgs, points, quantities, n_jobs):
    """:func:`evaluate_design` of every design-parameter dict of ``points`` at every load case
    (``case_cfgs``: the template config at each case of the duty cycle), in ``n_jobs`` processes
    that die with this one (:func:`sim.api.worker_pool`: a killed study leaves no simulation
    running). Returns one list of per-case records per point, in order."""
    pairs = [(cfg, p) for p in points for cfg in case_cfgs]
    if n_jobs == 1 or len(pairs) <= 1:
        flat = [evaluate_design(cfg, p, quantities) for cfg, p in pairs]
    else:
        with worker_pool(min(n_jobs, len(pairs))) as pool:
            flat = list(pool.map(evaluate_design, *zip(*pairs), [quantities] * len(pairs)))
    m = len(case_cfgs)
    return [flat[i:i + m] for i in range(0, len(flat), m)]


def worst_status(statuses):
    """The status of a design from those of its cases: ok only if every case is ok, else the
    worst by :data:`STATUS` code (not converged < impossible geometry < failed)."""
    return STATUS_NAMES[max(STATUS[s] for s in statuses)]


def case_values(records):
    """{quantity: array over the cases} of one design's per-case records (NaN where a case has none)."""
    return {q: np.array([r["values"][q] for r in records], dtype=float) for q in records[0]["values"]}


def case_dataset_coords(cycle):
    """Coordinates of the ``case`` dim: the load quantities (sim.io.case_coords) and the time share."""
    coords = case_coords([OperatingPoint.from_config(c) for c in cycle.cases])
    coords["share"] = ("case", np.asarray(cycle.share, dtype=float), {"units": "1", "long_name": "time share of the case "
                                                                                                  "in the duty cycle"})
    return coords


def points_dataset(space, X, records, source, round_index, attrs, cycle):
    """Dataset of simulated design points along ``design`` and the duty cycle's load cases along
    ``case`` (DATA.md names and units).

    Parameters
    ----------
    space : studies.space.DesignSpace
    X : ndarray, shape (n, d)
        The points [parameter units].
    records : list of list of dict
        Per point, the per-case records of :func:`evaluate_designs`.
    source : str
        ``initial`` (space-filling design), ``verification`` or ``refinement`` (studies.refine).
    round_index : int
        0 for the initial design, -1 for the final local stage, else the verification round.
    attrs : dict
        Dataset attributes (provenance, study config).
    cycle : studies.cycle.DutyCycle
        The load cases (coordinates of ``case``, with their time shares).

    Results, ``case_status``, ``message`` and ``wall_time`` are per (design, case): a failed case
    is recorded as failed; ``status`` is the design's (:func:`worst_status`).
    """
    n, m = len(records), len(cycle)
    values = [space.bearing_values(x) for x in X]
    # every design parameter the designs set (a per-point osculation left to kappa is not one)
    shown = {k: a for k, a in DESIGN_PARAMETERS.items() if space.template[k] is not None or k in space.names}
    shown["ratings_alpha"] = ("deg", "contact angle of the ISO 281 factors")
    coords = {k: ("design", [v[k] for v in values], {"units": u, "long_name": ln}) for k, (u, ln) in shown.items()}
    coords["source"] = ("design", [source] * n,
                        {"long_name": "initial (space-filling), verification or refinement (final local stage) run"})
    coords["round"] = ("design", np.full(n, round_index, dtype=np.int32),
                       {"units": "1", "long_name": "verification round (0: initial design, -1: final local stage)"})
    coords.update(case_dataset_coords(cycle))
    names = list(records[0][0]["values"]) if records else []
    meta = {EDGE_MARGIN: EDGE_MARGIN_ATTRS}
    for r in (r for point in records for r in point):
        for q, a in r["attrs"].items():
            meta.setdefault(q, a)

    def table(key, dtype, convert=lambda v: v):
        return np.array([[convert(r[key]) for r in point] for point in records], dtype=dtype).reshape(n, m)

    data = {q: (("design", "case"), np.array([[r["values"][q] for r in point] for point in records],
                                             dtype=float).reshape(n, m), meta.get(q, {})) for q in names}
    flags = {"flag_values": np.array(list(STATUS.values()), dtype=np.int8), "flag_meanings": " ".join(STATUS)}
    data["status"] = ("design", np.array([STATUS[worst_status([r["status"] for r in point])] for point in records],
                                         dtype=np.int8), {"long_name": "simulation status of the design (the worst of "
                                                                       "its load cases)", **flags})
    data["case_status"] = (("design", "case"), table("status", np.int8, STATUS.__getitem__),
                           {"long_name": "simulation status of the design at the load case", **flags})
    data["message"] = (("design", "case"), table("message", object), {"long_name": "why the case has no result"})
    data["wall_time"] = (("design", "case"), table("wall_time", float), {"units": "s", "long_name": "simulation wall time"})
    return xr.Dataset(data, coords=coords, attrs=attrs)


# On disk (training.nc, verified.nc) a per-point table follows DATA.md: results on (design, case),
# and the race maximum of pmax under its own name (DATA.md's pmax is per race).
RACE_MAXIMA = {"pmax": ("pmax_any_race", "maximum contact pressure over both races, all rollers and slices")}


def table_to_file(ds):
    """A per-point table ``ds`` in its DATA.md form for writing: race maxima renamed
    (RACE_MAXIMA); the creation time joins the provenance."""
    out = ds
    for old, (new, long_name) in RACE_MAXIMA.items():
        if old in out:
            out = out.rename({old: new})
            out[new].attrs["long_name"] = long_name
    out.attrs.setdefault("created", utc_now())
    return out


def table_from_file(ds):
    """Inverse of :func:`table_to_file`: the per-point table the search works on, with the
    simulation's own long_name on the race maxima (sim.io.CASE_VARIABLES)."""
    out = ds
    for old, (new, _) in RACE_MAXIMA.items():
        if new in out:
            out = out.rename({new: old})
            out[old].attrs["long_name"] = CASE_VARIABLES[old][2]
    out.attrs.pop("created", None)
    return out


def design_matrix(ds, space):
    """The points of a points dataset as X (n, d) in ``space`` column order."""
    return np.column_stack([ds[n].values for n in space.names]) if ds.sizes["design"] else np.empty((0, len(space.names)))

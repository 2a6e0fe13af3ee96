"""The only builder of result Datasets and writer of NetCDF files (DATA.md).

Every variable carries ``units`` and ``long_name``; the dataset carries CF conventions and
provenance (package version, git commit, resolved config, solver, creation time). A case
that did not converge keeps its slot with ``converged = False`` and NaN data.
"""
import datetime as _dt
import functools
import os
import socket
import secrets
import hashlib
import subprocess
from importlib import metadata
from io import BytesIO
from pathlib import Path
from typing import NamedTuple

import numpy as np
import xarray as xr
from xarray.indexes import PandasIndex

from sim._math.jit import files_fingerprint, source_fingerprint  # noqa: F401  (files_fingerprint: public here)
from sim.physics import ratings
from sim.physics.friction import COMPONENTS

RACES = ["outer", "inner"]

# name: (dims after design/case, units, long_name)
CASE_VARIABLES = {
    "pmax": (("race",), "MPa", "maximum contact pressure over all rollers and slices"),
    "axial_displacement": ((), "mm", "shift of the most loaded roller along its axis relative to the inner ring, + towards the large end (rib side)"),
    "contact_length_ratio": (("race",), "1", "loaded length / Lwe of the most loaded roller"),
    "L_eff": ((), "mm", "effective (loaded) roller length, shorter of the two raceway contacts"),
    "edge_stress": ((), "1", "a contact runs onto a roller end (edge_interference > 0), where the roller's edge concentrates the pressure: pmax is then a slice average of that peak and grows with n_slices"),
    "edge_interference": (("race",), "1", "elastic interference extrapolated to the roller ends over the contact's largest elastic approach, worst roller and end (sim.physics.elasticity.edge_interference); > 0: edge contact"),
    "ring_displacement": (("direction",), "mm", "inner-ring displacement (axial along Fa, radial along Fr, lateral along y = z x Fr, which the friction of the load zone causes)"),
    "Q": (("roller", "race"), "N", "roller-raceway normal load"),
    "Q_rib": (("roller",), "N", "roller-end / rib normal load"),
    "pressure": (("race", "slice"), "MPa", "Hertz line-contact pressure along the most loaded roller"),
    "roller_tilt": (("roller",), "deg", "roller tilt in its meridian plane: the roller axis against its nominal direction at the angle alpha to the bearing axis (unloaded, centred), positive turning the axis towards the roller's outward radial axis v' (sim.solvers.quasi_static theta); rings' own tilt not removed"),
    "roller_skew": (("roller",), "deg", "roller skew: rotation of the roller axis out of its meridian plane about the roller's radial axis v', positive towards the rolling direction e_t of the cage frame; quasi-static, first order (sim.physics.friction)"),
    "roller_axial_displacement": (("roller",), "mm", "roller shift along its axis relative to the inner ring, + towards the large end"),
    "C_eff": ((), "N", "ISO 281 dynamic load rating with L_eff, thesis (7.1)"),
    "P": ((), "N", "ISO 281 equivalent dynamic load (2.12)"),
    "P0": ((), "N", "ISO 281 equivalent static load (2.8)"),
    "static_safety_factor": ((), "1", "static safety s0 = C0 / P0 from the solved contact, (4000 MPa / pmax)^2 (ISO 76: 4000 MPa at the most loaded contact defines C0; line contact, load ~ pressure^2); a case below 1 / solver.max_static_load_ratio is reported as not converged"),
    "L10": ((), "1e6 rev", "basic rating life with C_eff (2.15)"),
    "cage_speed": ((), "rpm", "cage speed: from the traction balance with friction, else rolling without slip (2.20)"),
    "torque": ((), "N*mm", "frictional torque of the bearing (on the outer ring; power loss / inner-ring speed with friction.kinematics = rolling); at speed 0 the breakaway torque (boundary friction, no film)"),
    "torque_component": (("component",), "N*mm", "torque breakdown by loss mechanism (power / inner-ring speed)"),
    "power_loss": ((), "W", "frictional power loss"),
    "skew_sliding": ((), "N*mm", "part of torque_component 'sliding' caused by roller skew: power of the lateral tractions on the lateral slip of the skewed rollers / inner-ring speed"),
    "srr": (("race", "slice"), "1", "slide-to-roll ratio along the most loaded roller, roller against ring (2.25)"),
    "film_thickness": (("race", "slice"), "um", "central EHL film thickness along the most loaded roller"),
    "lambda_ratio": (("race",), "1", "specific film thickness at the most loaded slice (2.27)"),
    "residual": (("direction",), "N", "inner-ring force residual at the solution (axial, radial, lateral)"),
    "converged": ((), "1", "solver converged"),
    "iterations": ((), "1", "ring Newton iterations"),
    "unrested_rollers": ((), "1", "rollers outside the load zone left unloaded where they should rest under their centrifugal force (a TRB's on the cup and rib, a TSRB's in the wedge between its raceways): where no equilibrium with the rest was found, the converged solution without it, their contact and its rolling loss neglected (sim.api.bearing_model.BearingModel.solve); 0 from the time-domain solver"),
    "wall_time": ((), "s", "solver wall time of the case"),
}
# kernel units (mm, N, s, rad) -> output units (DATA.md): power 1 N mm/s = 1e-3 W, speed
# 1 rad/s = 60 / (2 pi) rpm, film thickness 1 mm = 1e3 um
W_PER_N_MM_PER_S = 1e-3
RPM_PER_RAD_S = 30.0 / np.pi
UM_PER_MM = 1e3
# written only where the configuration computes them (written_optional), then for every case (NaN
# where a case has no result, DATA.md): the friction outputs with friction enabled, the skew outputs
# with friction.skew enabled (roller_skew from the time-domain solver too, whose rollers always
# have the skew degree of freedom)
FRICTION_VARIABLES = frozenset({"torque", "torque_component", "power_loss", "srr", "film_thickness", "lambda_ratio"})
SKEW_VARIABLES = frozenset({"roller_skew", "skew_sliding"})
OPTIONAL_VARIABLES = FRICTION_VARIABLES | SKEW_VARIABLES


def written_optional(friction, skew, dynamic=False):
    """The optional variables (:data:`OPTIONAL_VARIABLES`) that a configuration writes.

    friction: ``friction.enabled``; skew: ``friction.skew.enabled``; dynamic: ``solver=dynamic``
    (its summary holds the rollers' skew, 0 without free skew). Decided by the configuration, not
    by the results, so that a case without a result still has them (NaN), and a sweep's collector
    knows what each job's file must hold (sim.api.sweep.result_problem).
    """
    if not friction:
        return frozenset()
    if skew:
        return OPTIONAL_VARIABLES
    return FRICTION_VARIABLES | ({"roller_skew"} if dynamic else frozenset())
INTEGER_OR_BOOL = {"converged": bool, "edge_stress": bool, "iterations": np.int32, "unrested_rollers": np.int32}
# design coordinates: name -> (units, long_name); the first ones are config inputs, the last three derived
DESIGN_COORDS = {
    "alpha": ("deg", "roller-axis (mean contact) angle"), "Dpw": ("mm", "pitch diameter"),
    "Dwe": ("mm", "roller diameter"), "Lwe": ("mm", "roller length"), "Z": ("1", "number of rollers"),
    "PCR": ("mm", "profile curve radius of the roller"), "kappa": ("1", "osculation (2.7)"),
    "aP": ("mm", "distance between the contact points"), "aPk": ("mm", "small end face to the first contact point"),
    "gamma": ("deg", "taper angle (2.1)"), "aA": ("mm", "bearing axis to the centre of PCR (derived)"),
    "PCR_LB": ("mm", "raceway profile curve radius (derived)"),
}
# case coordinates (DATA.md), in the order of sim.api.OperatingPoint.values()
CASE_COORDS = ("Fa", "Fr", "speed", "tilt", "oil_temperature")
# a point without a result (failed, not computed) holds these; every other variable NaN
FILL_VALUES = {"converged": False, "edge_stress": False, "iterations": 0, "unrested_rollers": 0}


@functools.lru_cache(maxsize=1)
def git_commit():
    """Commit of the checkout the package runs from, or "unknown" (looked up once per process)."""
    try:
        root = Path(__file__).resolve().parent.parent
        out = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True, text=True, timeout=5)
        return out.stdout.strip() if out.returncode == 0 else "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def model_fingerprint():
    """SHA-256 of the sources of ``sim/`` (:func:`sim._math.jit.source_fingerprint`): two results
    with the same one were computed by the same simulation code (attribute ``model_fingerprint``)."""
    return source_fingerprint()


@functools.lru_cache(maxsize=1)
def package_version():
    """Installed version of tsrb-workbench, or the source version when not installed (looked up
    once per process: the metadata search costs about 0.5 ms)."""
    try:
        return metadata.version("tsrb-workbench")
    except metadata.PackageNotFoundError:
        return "0.1.0+source"


def _var(dims, data, attrs):
    """A Variable of ``data`` (converted as xarray would: ``np.asarray``)."""
    return xr.Variable(dims, np.asarray(data), attrs)


def _case_array(name, dims, results, sizes):
    shape = (1, len(results)) + tuple(sizes[d] for d in dims)
    kind = INTEGER_OR_BOOL.get(name)
    if kind is bool:
        arr = np.zeros(shape, dtype=bool)
    elif kind is not None:
        arr = np.zeros(shape, dtype=kind)
    else:
        arr = np.full(shape, np.nan)
    for c, res in enumerate(results):
        if name in res:
            arr[0, c] = res[name]
    return arr


def utc_now():
    """Creation time of a dataset, ISO 8601 in UTC to the second (DATA.md provenance)."""
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


CASE_COORD_ATTRS = {"Fa": ("N", "axial load"), "Fr": ("N", "radial load"), "speed": ("rpm", "inner-ring speed"),
                    "tilt": ("deg", "imposed inner-ring tilt"), "oil_temperature": ("degC", "oil temperature")}


def case_coords(ops):
    """Case coordinates (DATA.md) of a list of sim.api.simulation.OperatingPoint."""
    values = [o.values() for o in ops]   # in CASE_COORDS order
    return {name: ("case", [v[i] for v in values], {"units": units, "long_name": long_name})
            for i, (name, (units, long_name)) in enumerate((c, CASE_COORD_ATTRS[c]) for c in CASE_COORDS)}


SOURCES = ("thesis; ISO281; ISO/TS16281; Johnson1985; TeutschSauer2004; ZhouHoeprich1991; PanHamrock1989; "
           "HamrockDowson1977; BairWiner1979; JohnsonTevaarwerk1977")


def provenance_attrs(title, config_yaml, settings):
    """Dataset attributes (DATA.md provenance) of a result of the quasi-static solver."""
    return {
        "Conventions": "CF-1.10",
        "title": title,
        "package_version": package_version(),
        "git_commit": git_commit(),
        "model_fingerprint": model_fingerprint(),
        "config": config_yaml,
        "solver": "quasi_static",
        "solver_settings": str(settings),
        "created": utc_now(),
        "sources": SOURCES,
    }


def design_values(geometry):
    """Design coordinates (DATA.md, :data:`DESIGN_COORDS`) of a geometry: name -> value."""
    g = geometry
    values = {"alpha": g.alpha_deg, "gamma": np.degrees(g.gamma), "Dpw": g.Dpw, "Dwe": g.Dwe,
              "Lwe": g.Lwe, "Z": g.Z}
    if g.type == "TSRB":
        values.update(PCR=g.PCR, kappa=g.kappa, aP=g.aP, aPk=g.aPk, aA=g.aA, PCR_LB=g.PCR_LB)
    return values


RATING_ATTRS = {"C": {"units": "N", "long_name": "ISO 281 dynamic load rating (2.14)"},
                "C0": {"units": "N", "long_name": "ISO 281 static load rating (2.10)"}}
X_SLICE_ATTRS = {"units": "mm", "long_name": "slice centre from the large end"}
SLICE_ATTRS = {"long_name": "slice index from the large end", "units": "1"}


INDEX_ATTRS = {"race": {"long_name": "raceway"}, "direction": {"long_name": "inner-ring direction"},
               "component": {"long_name": "friction loss mechanism"},
               "roller": {"long_name": "roller index by azimuth, 0 under Fr", "units": "1"}, "slice": SLICE_ATTRS}


@functools.lru_cache(maxsize=64)
def _pandas_indexes(Z, n_slices):
    """The indexes of race, direction, component, roller, slice, built from numpy once (pandas
    Index construction is the slow part of an index)."""
    values = {"race": RACES, "direction": ["axial", "radial", "lateral"], "component": COMPONENTS, "roller": np.arange(Z),
              "slice": np.arange(n_slices)}
    return {name: PandasIndex.from_variables({name: _var(name, data, {})}, options={})
            for name, data in values.items()}


def _dimension_coords(Z, n_slices):
    """Index coordinates race, direction, component, roller, slice as (variables, indexes): new
    objects for every Dataset around the cached (immutable) pandas indexes."""
    variables, indexes = {}, {}
    for name, cached in _pandas_indexes(Z, n_slices).items():
        index = PandasIndex(cached.index, name, coord_dtype=cached.coord_dtype)
        variables.update(index.create_variables({name: xr.Variable(name, [], INDEX_ATTRS[name])}))
        indexes[name] = index
    return variables, indexes


DIRECT_CONSTRUCTION = hasattr(xr.Dataset, "_construct_direct")   # see _dataset


def _dataset(data, coords, indexes, attrs):
    """A Dataset of Variables that fit together by construction: ``data`` and ``coords`` name ->
    Variable (one per name; shared dims of one size, checked here), ``indexes`` the xarray
    indexes of the dimension coordinates among ``coords``.

    The public constructor merges the variables one by one (several copies and checks each,
    about 20 us per variable: most of the assembly of a 50-variable result); where xarray has
    it, ``Dataset._construct_direct`` takes them as they are. It is private but is what xarray
    itself builds its validated results with (since 0.16); tests/sweeps/test_simulate_caches.py
    checks that both paths give identical Datasets, so a change of it shows there.
    """
    variables = {**data, **coords}
    dims = {}
    for name, var in variables.items():
        for dim, size in zip(var.dims, var.shape):
            if dims.setdefault(dim, size) != size:
                raise ValueError(f"{name}: dimension {dim} has {size} entries, other variables {dims[dim]}")
    if DIRECT_CONSTRUCTION:
        return xr.Dataset._construct_direct(variables, set(coords), dims, attrs, indexes)
    return xr.Dataset(data, coords=xr.Coordinates(coords, indexes=indexes), attrs=attrs)


_DESIGN_PARTS = {}     # repr of a Geometry -> its design values and ratings
_DESIGN_PARTS_SIZE = 256


def _design_parts(geometry):
    """Design values and ratings {C, C0} [N] of a geometry, computed once per geometry."""
    key = repr(geometry)    # every field of the dataclass (arrays excluded: derived from the fields)
    parts = _DESIGN_PARTS.get(key)
    if parts is None:
        g = geometry
        C = ratings.dynamic_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha, g.b_m)
        C0 = ratings.static_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha)
        parts = (design_values(g), {"C": C, "C0": C0})
        if len(_DESIGN_PARTS) >= _DESIGN_PARTS_SIZE:
            _DESIGN_PARTS.pop(next(iter(_DESIGN_PARTS)))
        _DESIGN_PARTS[key] = parts
    return parts


def build_dataset(geometry, ops, results, config_yaml, settings, optional):
    """Assemble the DATA.md Dataset of one bearing (design dim of length 1) over its cases.

    Every array is filled in numpy first and the Dataset is created once from Variables
    (:func:`_dataset`), the pandas indexes and the ratings of a geometry computed once (a
    Dataset assembled from tuples, with its indexes, costs several ms per call).

    Parameters
    ----------
    geometry : sim.geometry.Geometry
    ops : list of sim.api.simulation.OperatingPoint
    results : list of dict
        Per-case outputs of :func:`sim.api.simulation.case_results` (output units).
    config_yaml : str
        The full resolved config.
    settings : sim.api.simulation.SolverSettings
    optional : set of str
        The optional variables the configuration computes (:func:`written_optional`), written
        for every case (NaN where a case has none).

    A case without a result (``converged`` False) has its reason in the attribute
    :data:`FAILED_CASES` (:func:`case_failure` reads it; the failure table of a batch,
    :func:`build_batch_dataset`, and of a sweep, sim.api.sweep.collect, hold the same messages).
    """
    g = geometry
    design, rating = _design_parts(g)
    sizes = {"race": 2, "slice": g.n_slices, "roller": g.Z, "direction": 3, "component": len(COMPONENTS)}
    data = {}
    for name, (dims, units, long_name) in CASE_VARIABLES.items():
        if name in OPTIONAL_VARIABLES and name not in optional:
            continue    # not computed by this configuration (friction or skew disabled): no placeholders
        arr = _case_array(name, dims, results, sizes)
        data[name] = xr.Variable(("design", "case") + dims, arr, {"units": units, "long_name": long_name})
    for name, value in rating.items():
        data[name] = _var(("design",), [value], RATING_ATTRS[name])
    coords, indexes = _dimension_coords(g.Z, g.n_slices)
    coords["x_slice"] = _var("slice", g.x_slice_from_large_end, X_SLICE_ATTRS)
    coords.update({name: _var(*value) for name, value in case_coords(ops).items()})
    coords["bearing_type"] = _var("design", [g.type], {"long_name": "bearing type"})
    for name, value in design.items():
        units, long_name = DESIGN_COORDS[name]
        coords[name] = _var("design", [value], {"units": units, "long_name": long_name})
    title = f"{g.type} quasi-static load distribution and friction"
    attrs = provenance_attrs(title, config_yaml, settings)
    failed = [f"{case_label(op.values())}: {failure_message(res)}" for op, res in zip(ops, results)
              if not res["converged"]]
    if failed:
        attrs[FAILED_CASES] = "\n".join(failed)
    return _dataset(data, coords, indexes, attrs)


# Attribute of a Dataset with cases without a result: one line "<case_label>: <reason>" per case.
FAILED_CASES = "failed_cases"


def failure_message(res):
    """Why a case of :func:`sim.api.simulation.case_results` has no result (``converged`` False)."""
    return res.get("status") or f"converged = False after {int(res['iterations'])} ring iterations"


def case_label(values):
    """The case coordinates ``values`` (:data:`CASE_COORDS` order) as text, exactly (repr of each
    float), the key of a line of the attribute :data:`FAILED_CASES`."""
    return ", ".join(f"{name} = {float(v)!r}" for name, v in zip(CASE_COORDS, values))


def case_failure(ds, values):
    """The reason recorded in ``ds.attrs`` (:data:`FAILED_CASES`) for the case ``values``, or None."""
    head = case_label(values) + ": "
    for line in ds.attrs.get(FAILED_CASES, "").splitlines():
        if line.startswith(head):
            return line[len(head):]
    return None


# Time series of the dynamic solver (sim.api.dynamic_model.outputs): name -> (dims after design,
# case, time; units; long_name). Named with a ``_t`` suffix beside the steady-state summary of the
# same quantity (DATA.md names on design, case).
SERIES_VARIABLES = {
    "roller_skew_t": (("roller",), "deg", "roller skew over time (as roller_skew)"),
    "roller_tilt_t": (("roller",), "deg", "roller tilt over time (as roller_tilt)"),
    "roller_xi_t": (("roller",), "mm", "roller centre along its nominal axis u (sim.solvers.quasi_static xi)"),
    "roller_eta_t": (("roller",), "mm", "roller centre along its nominal radial axis v (sim.solvers.quasi_static eta)"),
    "roller_speed_t": (("roller",), "rpm", "roller speed about its axis relative to its orbit"),
    "roller_orbit_speed_t": (("roller",), "rpm", "orbit speed of the roller centre"),
    "Q_t": (("roller", "race"), "N", "roller-raceway normal load over time"),
    "Q_rib_t": (("roller",), "N", "roller-end / rib normal load over time"),
    "pocket_force_t": (("roller",), "N", "cage pocket force on the roller along the rolling direction e_t"),
    "cage_speed_t": ((), "rpm", "cage speed over time"),
    "ring_displacement_t": (("direction",), "mm", "inner-ring displacement over time (axial, radial along Fr, lateral along y = z x Fr)"),
    "torque_t": ((), "N*mm", "torque on the outer ring over time (the bearing's friction torque is the drive's, drive_torque_t; they differ by the contacts' orbit moments, sim.solvers.dynamic)"),
    "drive_torque_t": ((), "N*mm", "torque that drives the inner ring at its speed over time"),
    "torque_component_t": (("component",), "N*mm", "loss power by mechanism / inner-ring speed over time"),
    "power_loss_t": ((), "W", "frictional power loss over time"),
}
SERIES_SOURCE = {"roller_skew_t": "roller_skew", "roller_tilt_t": "roller_tilt", "roller_xi_t": "roller_xi",
                 "roller_eta_t": "roller_eta", "roller_speed_t": "roller_speed",
                 "roller_orbit_speed_t": "roller_orbit_speed", "Q_t": "Q", "Q_rib_t": "Q_rib",
                 "pocket_force_t": "pocket_force", "cage_speed_t": "cage_speed",
                 "ring_displacement_t": "ring_displacement", "torque_t": "torque", "drive_torque_t": "drive_torque",
                 "torque_component_t": "torque_component", "power_loss_t": "power_loss"}


def build_dynamic_dataset(geometry, op, summary, series, config_yaml, settings, dynamic_settings, optional):
    """The Dataset of one dynamic run (one case): the steady-state summary in the layout of
    :func:`build_dataset` (``converged`` = a steady state was found; ``optional`` as there) plus
    the time series (:data:`SERIES_VARIABLES`) on (design, case, time); ``series``: name -> array
    (time, ...) in output units, ``time`` [s]; None for a run that never started (its quasi-static
    start did not converge): every series then has no time step."""
    ds = build_dataset(geometry, [op], [summary], config_yaml, settings, optional)
    if series is None:
        series = {"time": np.zeros(0)} | {SERIES_SOURCE[name]: np.zeros((0,) + tuple(ds.sizes[d] for d in dims))
                                          for name, (dims, _, _) in SERIES_VARIABLES.items()}
    data = {}
    for name, (dims, units, long_name) in SERIES_VARIABLES.items():
        values = np.asarray(series[SERIES_SOURCE[name]])[None, None]
        data[name] = (("design", "case", "time") + dims, values, {"units": units, "long_name": long_name})
    ds = ds.assign(data).assign_coords(time=("time", np.asarray(series["time"]),
                                             {"units": "s", "long_name": "time from the start of the run"}))
    ds.attrs.update(solver="dynamic", solver_settings=f"{settings}; dynamic: {dynamic_settings}",
                    title=f"{geometry.type} time-domain multibody run (sim.solvers.dynamic) and its steady state")
    return ds


#: this host, as a short tag in the names of temporary files (a hostname may hold dots)
HOST_TAG = hashlib.sha256(socket.gethostname().encode()).hexdigest()[:8]
TMP_SUFFIX = ".tmp"


def temporary_path(path):
    """A new temporary name beside ``path``: ``.<name>.<host tag>-<pid>-<random>.tmp``, so that a
    later run can tell an interrupted write (dead pid on this host) from a concurrent one."""
    path = Path(path)
    return path.parent / f".{path.name}.{HOST_TAG}-{os.getpid()}-{secrets.token_hex(4)}{TMP_SUFFIX}"


def write_bytes_atomic(path, data):
    """Write bytes through a unique temporary file in the same folder and an atomic rename.

    The file is created with mode 0o666 minus the umask, like any file a program writes
    (``tempfile.mkstemp`` would give 0o600); a reader sees the old file or the new one, never a
    partial one. The temporary name carries this host's tag and pid, so that the next run can
    tell an interrupted write (:func:`sim.api.sweep.remove_stale_files`) from a concurrent one.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_path(path)
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def write_figure_atomic(fig, path, dpi):
    """Save a matplotlib figure as PNG to ``path`` atomically (rendered in memory, then
    :func:`write_bytes_atomic`); ``dpi`` [1/inch]."""
    buf = BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return write_bytes_atomic(path, buf.getvalue())


def write_netcdf_atomic(ds, path):
    """Write ``ds`` to ``path`` via a temporary file in the same folder and an atomic rename.

    netCDF4 creates the temporary file itself, so it gets the user's umask (normally 0644), not
    the 0600 of a mkstemp file."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_path(path)
    try:
        encoding = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars
                    if ds[name].dtype.kind == "f"}
        ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


# ------------------------------------------------------------------ multi-case and multi-design datasets
def combine_cases(datasets, config_yaml):
    """One design's Dataset from Datasets of some of its cases (each with ``design`` 1), in order.

    Variables that only some cases carry are NaN in the others; attributes are those of the first
    Dataset with ``config`` set to ``config_yaml``, and :data:`FAILED_CASES` the lines of all.
    """
    ds = xr.concat(datasets, dim="case", data_vars="minimal", coords="minimal", compat="override",
                   join="outer", fill_value=FILL_VALUES, combine_attrs="override")
    ds.attrs["config"] = config_yaml
    failed = "\n".join(part.attrs[FAILED_CASES] for part in datasets if FAILED_CASES in part.attrs)
    ds.attrs.pop(FAILED_CASES, None)
    if failed:
        ds.attrs[FAILED_CASES] = failed
    return ds


def failed_dataset(bearing, ops, config_yaml, message):
    """Dataset of a design that produced no result (impossible geometry, bad input, a crash).

    It keeps the design's place in a sweep: case coordinates of ``ops``, the geometry inputs of
    the ``bearing`` config node as design coordinates (derived ones NaN), ``converged = False``.
    """
    coords = dict(case_coords(ops))
    coords["bearing_type"] = ("design", [str(bearing.get("type"))], {"long_name": "bearing type"})
    for name, (units, long_name) in DESIGN_COORDS.items():
        value = bearing.get(name)
        coords[name] = ("design", [np.nan if value is None else value], {"units": units, "long_name": long_name})
    converged = xr.Variable(("design", "case"), np.zeros((1, len(ops)), dtype=bool),
                            {"units": "1", "long_name": CASE_VARIABLES["converged"][2]})
    ds = xr.Dataset({"converged": converged}, coords=coords)
    ds.attrs.update({"Conventions": "CF-1.10", "title": "failed design", "package_version": package_version(),
                     "git_commit": git_commit(), "model_fingerprint": model_fingerprint(), "config": config_yaml,
                     "error": message,
                     "created": utc_now()})
    return ds


def combine_designs(datasets, extra_coords):
    """One ``design`` x ``case`` Dataset (DATA.md) from single-design Datasets.

    Parameters
    ----------
    datasets : list of xarray.Dataset
        One per design (``design`` 1), from :func:`build_dataset`, :func:`combine_cases` or
        :func:`failed_dataset`.
    extra_coords : dict
        name -> (list of one value per design, attrs): swept parameters that are not already
        design coordinates (a config-group choice, a solver setting).

    Returns
    -------
    xarray.Dataset
        Cases are matched by their coordinates (Fa, Fr, speed, tilt, oil_temperature) and form
        the union in order of first appearance; a design lacking a case holds NaN there with
        ``converged = False``. A design coordinate that some designs lack (PCR of a TRB) is NaN
        (or "") there. ``x_slice`` stays on ``slice`` while all computed designs share it, else
        it becomes (slice, design): DATA.md's ``x_slice (slice)`` with ``design`` as an extra
        trailing dimension (a sweep over Lwe or solver.n_slices). Attributes are those of the first
        Dataset.
    """
    keys = [list(zip(*(ds[c].values.tolist() for c in CASE_COORDS))) for ds in datasets]
    union = list(dict.fromkeys(k for ks in keys for k in ks))
    index = {k: i for i, k in enumerate(union)}
    design_coords = {}
    for ds in datasets:
        for name, coord in ds.coords.items():
            if coord.dims == ("design",) and name not in design_coords:
                design_coords[name] = ("" if coord.dtype.kind in "OUS" else np.nan, coord.attrs)
    x_slices = {tuple(ds.x_slice.values.tolist()) for ds in datasets if "x_slice" in ds.coords}
    shared_x = len(x_slices) == 1
    x_attrs = next((ds.x_slice.attrs for ds in datasets if "x_slice" in ds.coords), {})
    aligned = []
    for ds, ks in zip(datasets, keys):
        ds = ds.drop_vars(CASE_COORDS).assign_coords(case=[index[k] for k in ks])
        ds = ds.assign_coords({name: ("design", [missing], attrs) for name, (missing, attrs) in design_coords.items()
                               if name not in ds.coords})
        if "x_slice" in ds.coords:
            ds = ds.drop_vars("x_slice") if shared_x else ds.assign_coords(x_slice=ds.x_slice.expand_dims("design"))
        elif x_slices and not shared_x:   # a failed design among unlike ones: no slices, NaN there
            ds = ds.assign_coords(x_slice=(("design", "slice"), np.full((1, 0), np.nan), x_attrs),
                                  slice=("slice", np.arange(0), SLICE_ATTRS))
        aligned.append(ds)
    out = xr.concat(aligned, dim="design", data_vars="minimal", coords="minimal", compat="override",
                    join="outer", fill_value=FILL_VALUES, combine_attrs="override")
    out = out.drop_vars("case").assign_coords(
        {c: ("case", list(v), datasets[0][c].attrs) for c, v in zip(CASE_COORDS, zip(*union))})
    if shared_x:
        out = out.assign_coords(x_slice=("slice", list(next(iter(x_slices))), x_attrs))
    elif "x_slice" in out.coords:
        out = out.assign_coords(x_slice=out.x_slice.transpose("slice", "design"))
    return out.assign_coords({name: ("design", values, attrs) for name, (values, attrs) in extra_coords.items()})


FAILURE_COLUMNS = {"design": ("1", "design index of the failed point", np.int32),
                   "case": ("1", "case index of the failed point", np.int32),
                   "job": ("1", "multirun job number of the failed point", np.int32),
                   "overrides": (None, "command-line overrides of the job", str),
                   "reason": (None, "why the point has no result: error, not converged, missing", str),
                   "message": (None, "error message or solver status", str)}


def failure_table(rows, columns=tuple(FAILURE_COLUMNS)):
    """The failed points of a sweep as variables on dimension ``failure``.

    Parameters
    ----------
    rows : list of dict
        Keys ``design``, ``case`` (indices into the sweep dataset), ``job`` (Hydra job number),
        ``overrides`` (the job's command-line overrides), ``reason`` ("error", "not converged"
        or "missing") and ``message``.
    columns : sequence of str
        The keys to write (``failed_<key>``), of :data:`FAILURE_COLUMNS`; all by default
        (a batch has no job and no overrides).
    """
    return xr.Dataset(_failure_variables(rows, columns))


def _failure_variables(rows, columns):
    data = {}
    for name in columns:
        units, long_name, dtype = FAILURE_COLUMNS[name]
        attrs = {"long_name": long_name} | ({"units": units} if units else {})
        data[f"failed_{name}"] = xr.Variable(("failure",), np.array([r[name] for r in rows], dtype=dtype), attrs)
    return data


# ------------------------------------------------------------------ a batch of designs in one go
class DesignResult(NamedTuple):
    """A simulated design: the arguments of :func:`build_dataset`."""

    geometry: object
    ops: list
    results: list
    config_yaml: str
    settings: object
    optional: frozenset     # the optional variables its configuration computes (written_optional)


class DesignFailure(NamedTuple):
    """A design without a result: the arguments of :func:`failed_dataset`."""

    bearing: dict
    ops: list
    config_yaml: str
    message: str


def _design_coordinates(design):
    """Design coordinates (name -> value) of a design, as its single-design Dataset holds them."""
    if isinstance(design, DesignResult):
        return {"bearing_type": design.geometry.type, **_design_parts(design.geometry)[0]}
    values = {"bearing_type": str(design.bearing.get("type"))}
    for name in DESIGN_COORDS:
        value = design.bearing.get(name)
        values[name] = np.nan if value is None else value
    return values


def build_batch_dataset(designs):
    """One ``design`` x ``case`` Dataset (DATA.md) of many designs, built once from arrays.

    Data and coordinates are those :func:`combine_designs` gives for the single-design Datasets
    (:func:`build_dataset` of each :class:`DesignResult`, :func:`failed_dataset` of each
    :class:`DesignFailure`) without extra coordinates: cases the union in order of first
    appearance, NaN / ``converged = False`` where a design lacks a case, a variable or a
    roller, ``x_slice`` on ``slice`` while all computed designs share it. Added: the resolved
    config of every design (``design_config``) and the failure table (``failed_design``,
    ``failed_case``, ``failed_reason`` "error" or "not converged", ``failed_message``; a design
    without any case has one row with case -1). Attributes: the provenance of the first
    computed design (``config`` its YAML), with the title of the batch.

    Parameters
    ----------
    designs : list of DesignResult or DesignFailure
    """
    n_designs = len(designs)
    keys = [[op.values() for op in d.ops] for d in designs]
    union = list(dict.fromkeys(k for ks in keys for k in ks))
    index = {k: i for i, k in enumerate(union)}
    n_cases = len(union)
    computed = [d for d in designs if isinstance(d, DesignResult)]
    sizes = {"race": 2, "direction": 3, "component": len(COMPONENTS),
             "roller": max((d.geometry.Z for d in computed), default=0),
             "slice": max((d.geometry.n_slices for d in computed), default=0)}
    # data variables, in order of first appearance (as the single-design Datasets hold them)
    names = []
    for d in designs:
        if isinstance(d, DesignFailure):
            names.append("converged")
            continue
        names += [n for n in CASE_VARIABLES if n not in OPTIONAL_VARIABLES or n in d.optional]
        names += ["C", "C0"]
    names = list(dict.fromkeys(names))
    arrays = {}
    for name in names:
        if name in RATING_ATTRS:
            arrays[name] = np.full(n_designs, np.nan)
            continue
        dims = CASE_VARIABLES[name][0]
        shape = (n_designs, n_cases) + tuple(sizes[dim] for dim in dims)
        kind = INTEGER_OR_BOOL.get(name)
        arrays[name] = np.full(shape, FILL_VALUES[name], dtype=kind) if kind else np.full(shape, np.nan)
    rows = []
    for i, (d, ks) in enumerate(zip(designs, keys)):
        positions = [index[k] for k in ks]
        if isinstance(d, DesignFailure):
            rows += [{"design": i, "case": c, "reason": "error", "message": d.message} for c in positions or [-1]]
            continue
        for name, value in _design_parts(d.geometry)[1].items():
            arrays[name][i] = value
        for c, res in zip(positions, d.results):
            for name, value in res.items():
                target = arrays.get(name) if name in CASE_VARIABLES else None
                if target is None:
                    continue
                value = np.asarray(value)
                target[(i, c) + tuple(slice(0, n) for n in value.shape)] = value
            if not res["converged"]:
                rows.append({"design": i, "case": c, "reason": "not converged", "message": failure_message(res)})
    data = {}
    for name in names:
        dims, units, long_name = CASE_VARIABLES.get(name) or ((), None, None)
        attrs = RATING_ATTRS[name] if name in RATING_ATTRS else {"units": units, "long_name": long_name}
        full_dims = ("design",) if name in RATING_ATTRS else ("design", "case") + dims
        data[name] = xr.Variable(full_dims, arrays[name], attrs)
    data["design_config"] = _var("design", [d.config_yaml for d in designs],
                                 {"long_name": "resolved config of the design (YAML), its load included"})
    coords, indexes = {}, {}
    if computed:
        index_vars, indexes = _dimension_coords(sizes["roller"], sizes["slice"])
        coords.update(index_vars)
        x_slices = {tuple(d.geometry.x_slice_from_large_end.tolist()) for d in computed}
        if len(x_slices) == 1:
            coords["x_slice"] = _var("slice", computed[0].geometry.x_slice_from_large_end, X_SLICE_ATTRS)
        else:
            x = np.full((sizes["slice"], n_designs), np.nan)
            for i, d in enumerate(designs):
                if isinstance(d, DesignResult):
                    x[:d.geometry.n_slices, i] = d.geometry.x_slice_from_large_end
            coords["x_slice"] = _var(("slice", "design"), x, X_SLICE_ATTRS)     # DATA.md: (slice), design trailing
    for name, (units, long_name) in CASE_COORD_ATTRS.items():
        coords[name] = _var("case", [k[CASE_COORDS.index(name)] for k in union],
                            {"units": units, "long_name": long_name})
    values = [_design_coordinates(d) for d in designs]
    for name in dict.fromkeys(n for v in values for n in v):
        sample = next(v[name] for v in values if name in v)   # the first design's sets the fill
        missing = "" if np.asarray([sample]).dtype.kind in "OUS" else np.nan
        attrs = {"long_name": "bearing type"} if name == "bearing_type" else dict(
            zip(("units", "long_name"), DESIGN_COORDS[name]))
        coords[name] = _var("design", [v.get(name, missing) for v in values], attrs)
    first = computed[0] if computed else None
    attrs = provenance_attrs(f"batch of {n_designs} designs x {n_cases} cases",
                             (first or designs[0]).config_yaml, first.settings if first else "none: no design computed")
    data.update(_failure_variables(rows, ("design", "case", "reason", "message")))
    return _dataset(data, coords, indexes, attrs)

"""The only builder of result Datasets and writer of NetCDF files (DATA.md).

Every variable carries ``units`` and ``long_name``; the dataset carries CF conventions and
provenance (package version, git commit, resolved config, solver, creation time). A case
that did not converge keeps its slot with ``converged = False`` and NaN data.
"""
import datetime as _dt
import os
import subprocess
import tempfile
from importlib import metadata
from pathlib import Path

import numpy as np
import xarray as xr

from sim import ratings
from sim.friction import COMPONENTS

RACES = ["outer", "inner"]

# name: (dims after design/case, units, long_name)
CASE_VARIABLES = {
    "pmax": (("race",), "MPa", "maximum contact pressure over all rollers and slices"),
    "axial_displacement": ((), "mm", "shift of the most loaded roller along its axis relative to the inner ring, + towards the large end (rib side)"),
    "contact_length_ratio": (("race",), "1", "loaded length / Lwe of the most loaded roller"),
    "L_eff": ((), "mm", "effective (loaded) roller length, shorter of the two raceway contacts"),
    "edge_stress": ((), "1", "end-slice pressure peak above output.edge_stress_ratio times the interior maximum"),
    "ring_displacement": (("direction",), "mm", "inner-ring displacement (axial along Fa, radial along Fr)"),
    "Q": (("roller", "race"), "N", "roller-raceway normal load"),
    "Q_rib": (("roller",), "N", "roller-end / rib normal load"),
    "pressure": (("race", "slice"), "MPa", "Hertz line-contact pressure along the most loaded roller"),
    "roller_tilt": (("roller",), "deg", "roller tilt in its meridian plane"),
    "roller_axial_displacement": (("roller",), "mm", "roller shift along its axis relative to the inner ring, + towards the large end"),
    "C_eff": ((), "N", "ISO 281 dynamic load rating with L_eff, thesis (7.1)"),
    "P": ((), "N", "ISO 281 equivalent dynamic load (2.12)"),
    "P0": ((), "N", "ISO 281 equivalent static load (2.8)"),
    "L10": ((), "1e6 rev", "basic rating life with C_eff (2.15)"),
    "cage_speed": ((), "rpm", "cage speed: from the traction balance with friction, else rolling without slip (2.20)"),
    "torque": ((), "N*mm", "frictional torque of the bearing (on the outer ring)"),
    "torque_component": (("component",), "N*mm", "torque breakdown by loss mechanism (power / inner-ring speed)"),
    "power_loss": ((), "W", "frictional power loss"),
    "srr": (("race", "slice"), "1", "slide-to-roll ratio along the most loaded roller, roller against ring (2.25)"),
    "film_thickness": (("race", "slice"), "um", "central EHL film thickness along the most loaded roller"),
    "lambda_ratio": (("race",), "1", "specific film thickness at the most loaded slice (2.27)"),
    "residual": (("direction",), "N", "inner-ring force residual at the solution"),
    "converged": ((), "1", "solver converged"),
    "iterations": ((), "1", "ring Newton iterations"),
    "wall_time": ((), "s", "solver wall time of the case"),
}
# written only when some case computed them (friction enabled)
OPTIONAL_VARIABLES = {"torque", "torque_component", "power_loss", "srr", "film_thickness", "lambda_ratio"}
INTEGER_OR_BOOL = {"converged": bool, "edge_stress": bool, "iterations": np.int32}


def _git_commit():
    try:
        root = Path(__file__).resolve().parent.parent
        out = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True, text=True, timeout=5)
        return out.stdout.strip() if out.returncode == 0 else "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def _version():
    try:
        return metadata.version("tsrb-workbench")
    except metadata.PackageNotFoundError:
        return "0.1.0+source"


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


def build_dataset(geometry, ops, results, config_yaml, settings):
    """Assemble the DATA.md Dataset of one bearing (design dim of length 1) over its cases.

    Parameters
    ----------
    geometry : sim.geometry.Geometry
    ops : list of sim.simulation.OperatingPoint
    results : list of dict
        Per-case outputs of :func:`sim.simulation.case_results` (output units).
    config_yaml : str
        The full resolved config.
    settings : sim.simulation.SolverSettings
    """
    g = geometry
    sizes = {"race": 2, "slice": g.n_slices, "roller": g.Z, "direction": 2, "component": len(COMPONENTS)}
    data = {}
    for name, (dims, units, long_name) in CASE_VARIABLES.items():
        if name in OPTIONAL_VARIABLES and not any(name in res for res in results):
            continue    # friction disabled: no torque variables, never placeholders
        arr = _case_array(name, dims, results, sizes)
        data[name] = xr.Variable(("design", "case") + dims, arr, {"units": units, "long_name": long_name})
    C = ratings.dynamic_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha, g.b_m)
    C0 = ratings.static_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, g.ratings_alpha)
    data["C"] = xr.Variable(("design",), [C], {"units": "N", "long_name": "ISO 281 dynamic load rating (2.14)"})
    data["C0"] = xr.Variable(("design",), [C0], {"units": "N", "long_name": "ISO 281 static load rating (2.10)"})
    coords = {
        "race": ("race", RACES, {"long_name": "raceway"}),
        "direction": ("direction", ["axial", "radial"], {"long_name": "inner-ring direction"}),
        "component": ("component", COMPONENTS, {"long_name": "friction loss mechanism"}),
        "roller": ("roller", np.arange(g.Z), {"long_name": "roller index by azimuth, 0 under Fr", "units": "1"}),
        "slice": ("slice", np.arange(g.n_slices), {"long_name": "slice index from the large end", "units": "1"}),
        "x_slice": ("slice", g.x_slice_from_large_end, {"units": "mm", "long_name": "slice centre from the large end"}),
        "Fa": ("case", [o.Fa for o in ops], {"units": "N", "long_name": "axial load"}),
        "Fr": ("case", [o.Fr for o in ops], {"units": "N", "long_name": "radial load"}),
        "speed": ("case", [o.speed for o in ops], {"units": "rpm", "long_name": "inner-ring speed"}),
        "tilt": ("case", [o.tilt for o in ops], {"units": "deg", "long_name": "imposed inner-ring tilt"}),
        "oil_temperature": ("case", [o.oil_temperature for o in ops], {"units": "degC", "long_name": "oil temperature"}),
        "bearing_type": ("design", [g.type], {"long_name": "bearing type"}),
    }
    design_params = {"alpha": ("deg", np.degrees(g.alpha), "roller-axis (mean contact) angle"),
                     "gamma": ("deg", np.degrees(g.gamma), "taper angle (2.1)"),
                     "Dpw": ("mm", g.Dpw, "pitch diameter"), "Dwe": ("mm", g.Dwe, "roller diameter"),
                     "Lwe": ("mm", g.Lwe, "roller length"), "Z": ("1", g.Z, "number of rollers")}
    if g.type == "TSRB":
        design_params.update({"PCR": ("mm", g.PCR, "profile curve radius of the roller"),
                              "kappa": ("1", g.kappa, "osculation (2.7)"),
                              "aP": ("mm", g.aP, "distance between the contact points"),
                              "aPk": ("mm", g.aPk, "small end face to the first contact point"),
                              "aA": ("mm", g.aA, "bearing axis to the centre of PCR (derived)"),
                              "PCR_LB": ("mm", g.PCR_LB, "raceway profile curve radius (derived)")})
    for name, (units, value, long_name) in design_params.items():
        coords[name] = ("design", [value], {"units": units, "long_name": long_name})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({
        "Conventions": "CF-1.10",
        "title": f"{g.type} quasi-static load distribution and friction",
        "package_version": _version(),
        "git_commit": _git_commit(),
        "config": config_yaml,
        "solver": "quasi_static",
        "solver_settings": str(settings),
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "sources": ("thesis; ISO281; ISO/TS16281; Johnson1985; TeutschSauer2004; ZhouHoeprich1991; PanHamrock1989; "
                    "HamrockDowson1977; BairWiner1979; JohnsonTevaarwerk1977"),
    })
    return ds


def write_netcdf_atomic(ds, path):
    """Write ``ds`` to ``path`` via a temporary file in the same folder and an atomic rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
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

"""From a composed config to a result Dataset: validation, kernel inputs, solve, post-processing.

``simulate(cfg)`` is the public entry point (re-exported as ``sim.simulate``). It validates
every input before any numerics run, solves each load case with the quasi-static solver and
hands plain arrays to :mod:`sim.io`, the only builder of Datasets.
"""
import time
from dataclasses import dataclass

import numpy as np
from omegaconf import OmegaConf

from sim import ratings
from sim.contact import contact_modulus, hertz_line_pressure
from sim.elasticity import ELASTICITY_MODES, influence_matrix
from sim.geometry import Geometry
from sim.kinematics import angular_speed, cage_speed_rolling, roller_speed_rolling
from sim.solvers.quasi_static import solve_bearing


class InputError(ValueError):
    """Invalid load or solver input; the message names the key, its value and the allowed range."""


def _check_range(name, value, low, high, low_open=False):
    value = float(value)
    ok = np.isfinite(value) and (value > low if low_open else value >= low) and value <= high
    if not ok:
        bracket = "(" if low_open else "["
        raise InputError(f"{name} = {value!r} is outside the allowed range {bracket}{low}, {high}]")
    return value


@dataclass(frozen=True)
class OperatingPoint:
    """One load case (degrees and rpm at this edge; converted for the kernels)."""

    Fa: float
    Fr: float
    speed: float
    tilt: float
    oil_temperature: float

    @classmethod
    def from_config(cls, load):
        Fa = _check_range("load.Fa", load["Fa"], 0.0, 1e7, low_open=True)
        Fr = _check_range("load.Fr", load["Fr"], 0.0, 1e7)
        speed = _check_range("load.speed", load["speed"], 0.0, 1e5)
        tilt = _check_range("load.tilt", load["tilt"], -2.0, 2.0)
        temp = _check_range("load.oil_temperature", load.get("oil_temperature", 40.0), -40.0, 200.0)
        return cls(Fa, Fr, speed, tilt, temp)


@dataclass(frozen=True)
class SolverSettings:
    n_slices: int
    elasticity: str
    tolerance: float
    max_iterations: int
    roller_max_iterations: int
    centrifugal: bool
    gyroscopic: bool

    @classmethod
    def from_config(cls, solver):
        el = str(solver["elasticity"])
        if el not in ELASTICITY_MODES:
            raise InputError(f"solver.elasticity = {el!r} is not one of {sorted(ELASTICITY_MODES)}")
        n = solver["n_slices"]
        if not (isinstance(n, (int, np.integer)) and 2 <= int(n) <= 400):
            raise InputError(f"solver.n_slices = {n!r} is outside the allowed range [2, 400] (integer)")
        tol = _check_range("solver.tolerance", solver["tolerance"], 1e-14, 1e-3, low_open=True)
        mi = int(_check_range("solver.max_iterations", solver["max_iterations"], 1, 10000))
        rmi = int(_check_range("solver.roller_max_iterations", solver["roller_max_iterations"], 1, 10000))
        return cls(int(n), el, tol, mi, rmi, bool(solver["centrifugal"]), bool(solver["gyroscopic"]))


class BearingModel:
    """Kernel inputs of one bearing, built once and reused for every load case."""

    def __init__(self, geometry: Geometry, material, settings: SolverSettings):
        self.geometry = g = geometry
        self.settings = settings
        a = g.arrays
        self.E_star = contact_modulus(g.E, g.nu)
        self.C = influence_matrix(a["x"], a["w"], self.E_star)
        # ISO/TS 16281: a roller with both raceway contacts in series carries
        # Q = c_L Lwe^(8/9) delta^(10/9); one contact takes half the approach, so its line
        # load is q = 2^(10/9) c_L Lwe^(-1/9) delta^(10/9).
        self.k_line = 2.0 ** (10.0 / 9.0) * float(material["slice_stiffness_iso16281"]) * g.Lwe ** (-1.0 / 9.0)
        self.mode = ELASTICITY_MODES[settings.elasticity]

    def body_loads(self, op: OperatingPoint):
        """Centrifugal force [N] and gyroscopic moment [N mm] of a roller, rolling kinematics (2.20), (2.22)."""
        g = self.geometry
        omega_c = angular_speed(cage_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha))
        omega_r = angular_speed(roller_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha))
        Fc = g.arrays["mass"] * omega_c**2 * 0.5 * g.Dpw if self.settings.centrifugal else 0.0
        Mg = g.arrays["inertia_axial"] * omega_r * omega_c * np.sin(g.alpha) if self.settings.gyroscopic else 0.0
        return np.array([Fc, Mg, g.Lwe])

    def initial_ring(self, op: OperatingPoint):
        """Start value of the inner-ring displacement: line-contact approach of an equal share (Johnson 4.3)."""
        g = self.geometry
        Q = max(op.Fa, op.Fr) / (g.Z * np.sin(g.alpha))
        q = Q / (0.5 * g.Lwe)
        approach = 2.0 * 2.0 * q / (np.pi * self.E_star) * 8.0
        return np.array([approach / np.sin(g.alpha), 0.0])

    def solve(self, op: OperatingPoint):
        """Solve one case; returns a dict of plain arrays (kernel units) and the status."""
        g = self.geometry
        a = g.arrays
        s = self.settings
        n = g.n_slices
        poses = np.zeros((g.Z, 3))
        q = np.zeros((g.Z, 2, n))
        active = np.zeros((g.Z, 2, n), dtype=np.bool_)
        Q = np.zeros((g.Z, 2))
        Qrib = np.zeros(g.Z)
        info = np.zeros(5)
        ring = self.initial_ring(op)
        t0 = time.perf_counter()
        converged = solve_bearing(op.Fa, op.Fr, np.radians(op.tilt), self.body_loads(op), g.alpha, g.Dpw, g.Z,
                                  a["x"], a["rho"], a["w"], a["race_kind"], a["race_par"], a["R_eq"], self.C,
                                  self.E_star, self.mode, self.k_line, a["rib"], g.type == "TRB",
                                  s.tolerance, s.max_iterations, s.roller_max_iterations, ring,
                                  poses, q, active, Q, Qrib, info)
        wall = time.perf_counter() - t0
        pressure = np.where(q > 0.0, hertz_line_pressure(np.maximum(q, 0.0), a["R_eq"][None, :, :], self.E_star), 0.0)
        return dict(converged=bool(converged), iterations=int(info[0]), residual=info[1:3].copy(),
                    wall_time=wall, ring=ring, poses=poses, line_load=q, pressure=pressure, Q=Q, Q_rib=Qrib)


def roller_shift_relative_to_inner_ring(g, xi, ring, tilt):
    """Roller shift along its axis relative to the inner ring (where a TRB has its rib) [mm].

    xi is measured in the fixed (outer-ring) frame; the inner-ring material point at the
    nominal roller centre (Dpw/2, 0) moves by Rot(phi) P0 + Delta - P0 in each meridian plane
    (phi = tilt cos(psi), Delta = (delta_r cos(psi), delta_a)); its component along the roller
    axis u = (sin(alpha), -cos(alpha)) is subtracted. Positive: towards the large end.
    """
    psi = 2.0 * np.pi * np.arange(g.Z) / g.Z
    phi = tilt * np.cos(psi)
    r0 = 0.5 * g.Dpw
    dr = r0 * (np.cos(phi) - 1.0) + ring[1] * np.cos(psi)
    dz = r0 * np.sin(phi) + ring[0]
    return xi - (dr * np.sin(g.alpha) - dz * np.cos(g.alpha))


def case_results(model: BearingModel, op: OperatingPoint, raw, output_cfg):
    """Derived per-case outputs of DATA.md from a solved state (all in output units)."""
    g = model.geometry
    n = g.n_slices
    w = g.slice_width
    res = {"converged": raw["converged"], "iterations": raw["iterations"], "wall_time": raw["wall_time"]}
    P = float(ratings.equivalent_dynamic_load(op.Fr, op.Fa, g.ratings_alpha))
    P0 = float(ratings.equivalent_static_load(op.Fr, op.Fa, g.ratings_alpha))
    res.update(P=P, P0=P0)
    if not raw["converged"]:
        return res
    p = raw["pressure"]                       # (Z, 2, N) MPa
    j = int(np.argmax(raw["Q"].sum(axis=1)))  # most loaded roller
    xi_rel = roller_shift_relative_to_inner_ring(g, raw["poses"][:, 0], raw["ring"], np.radians(op.tilt))
    thr = float(output_cfg["contact_pressure_threshold"])
    loaded = p[j] > thr                       # (2, N)
    length = loaded.sum(axis=1) * w           # (2,) mm
    L_eff = float(length.min())
    interior = p[j][:, 1:-1].max(axis=1) if n > 2 else p[j].max(axis=1)
    ends = np.maximum(p[j][:, 0], p[j][:, -1])
    edge = bool(np.any((ends > thr) & (ends > float(output_cfg["edge_stress_ratio"]) * interior)))
    C_eff = float(ratings.dynamic_load_rating(g.Dwe, g.Dpw, L_eff, g.Z, g.ratings_alpha, g.b_m)) if L_eff > 0 else 0.0
    res.update(
        pmax=p.max(axis=(0, 2)),
        axial_displacement=float(xi_rel[j]),
        contact_length_ratio=length / g.Lwe,
        L_eff=L_eff,
        edge_stress=edge,
        ring_displacement=raw["ring"].copy(),
        Q=raw["Q"],
        Q_rib=raw["Q_rib"],
        pressure=p[j],
        roller_tilt=np.degrees(raw["poses"][:, 2]),
        roller_axial_displacement=xi_rel,
        C_eff=C_eff,
        L10=float(ratings.basic_rating_life(C_eff, P)) if C_eff > 0 else 0.0,
        cage_speed=float(cage_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha)),
        residual=raw["residual"],
    )
    return res


def operating_points(load_cfg):
    """The load cases of a ``load`` config node (one case for now)."""
    return [OperatingPoint.from_config(load_cfg)]


def build_model(cfg):
    """Validated :class:`BearingModel` of a composed config (bearing, material, solver)."""
    settings = SolverSettings.from_config(cfg.solver)
    geometry = Geometry.from_config(cfg.bearing, cfg.material, settings.n_slices)
    if "slice_stiffness_iso16281" not in cfg.material:
        raise InputError("material.slice_stiffness_iso16281 is missing (ISO/TS 16281 line-contact stiffness)")
    return BearingModel(geometry, cfg.material, settings)


def build_friction(cfg, model):
    """Validated :class:`sim.friction.FrictionModel` of a composed config, or None when
    ``friction.enabled`` is false (then no torque variable is written)."""
    from sim.friction import FrictionModel
    from sim.lubricant import Lubricant

    if not bool(cfg.friction.enabled):
        return None
    if "surface" not in cfg.bearing:
        raise InputError("bearing.surface is missing (roughness sigma and Zhou-Hoeprich B_ZH, C_ZH, thesis (5.16))")
    return FrictionModel(model.geometry, model.E_star, Lubricant.from_config(cfg.lubricant), cfg.friction,
                         cfg.bearing.surface)


def solve_case(model, friction, op, output_cfg):
    """Load distribution, then kinematics and friction of one case; DATA.md outputs (output units).

    A case counts as converged only when both the load distribution and the traction
    kinematics converged; otherwise only its status and the load-derived P, P0 are kept.
    """
    raw = model.solve(op)
    res = case_results(model, op, raw, output_cfg)
    if friction is None or not res["converged"]:
        return res
    t0 = time.perf_counter()
    fr = friction.evaluate(op, raw)
    if not fr.pop("friction_converged"):
        return {key: res[key] for key in ("iterations", "wall_time", "P", "P0")} | {"converged": False}
    res.update(fr)
    res["wall_time"] += time.perf_counter() - t0
    return res


def simulate(cfg):
    """Run the configured bearing through every load case of ``cfg.load``.

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed config (``sim.load_config``): bearing, material, lubricant, friction, load, solver, output.

    Returns
    -------
    xarray.Dataset
        The result following DATA.md, dims ``design`` (1) and ``case``.
    """
    from sim.io import build_dataset

    model = build_model(cfg)
    friction = build_friction(cfg, model)
    ops = operating_points(cfg.load)
    results = [solve_case(model, friction, op, cfg.output) for op in ops]
    return build_dataset(model.geometry, ops, results, OmegaConf.to_yaml(cfg, resolve=True), model.settings)

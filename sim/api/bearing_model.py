"""Kernel inputs of one bearing and one load case, the quasi-static solve of a case, and the
DATA.md outputs derived from it (PyBaMM-style: the model holds parameters, the solver lives in
:mod:`sim.solvers.quasi_static`, :mod:`sim.api.simulation` joins them).
"""
import logging
from dataclasses import dataclass, fields
from functools import partial

import numpy as np

from sim import io
from sim._math.jit import clock, solver_seconds
from sim.config_schema import LoadConfig, SolverConfig, check_node
from sim.errors import InputError, OutOfRangeError
from sim.geometry import ROLLER_END_CLIP, Geometry
from sim.physics import ratings
from sim.physics.contact import contact_modulus, hertz_line_pressure, hertz_point_radii, slice_contact_meridian
from sim.physics.elasticity import (ELASTICITY_MODES, SliceElasticity, edge_interference, end_profile_drop,
                                   influence_matrix, loaded_lengths)
from sim.physics.kinematics import angular_speed, cage_speed_rolling, roller_speed_rolling
from sim.physics.roller_contact import BearingArrays, empty_frames
from sim.solvers.quasi_static import BodyLoads, NewtonSettings, QuasiStaticProblem, RollerSet, solve_bearing

log = logging.getLogger(__name__)

# Start of the inner-ring displacement (BearingModel.initial_ring): the line-contact approach of
# both raceway contacts of an equally loaded roller, 2 x (2 q / (pi E*)) x (ln(L/b) + 1/2 + ln 2)
# (sim.physics.elasticity, Johnson 1985, Contact Mechanics, 4.3), with q the roller load over
# half the roller length. ASSUMED: the log term taken as APPROACH_LOG_TERM = 8, at the top of its
# values for the bearings here (5.3-7.3 at L/b 60-440), so that the start mostly lies beyond the
# solution, where Newton on the stiffening contacts comes from above (0.8-3.4x the solved axial
# displacement for tsrb_reference, tsrb_prototype and trb_32208 at 4.5-40 kN); its size is the
# ring's length scale in sim.solvers.quasi_static.
APPROACH_LOG_TERM = 8.0
# Continuation fallback of BearingModel.solve (Allgower & Georg 2003): first increment of the
# load parameter lam in [0, 1]; an accepted increment doubles, a failed one halves, down to
# 1 / continuation_steps, and at most 2 x continuation_steps solves.
CONTINUATION_FIRST_STEP = 0.25

#: Keys of one load case in the config and the Dataset (DATA.md case coordinates), in the order
#: of OperatingPoint's fields.
LOAD_CASE_KEYS = io.CASE_COORDS


@dataclass(frozen=True)
class OperatingPoint:
    """One load case at the user's edge, in the config's units (N, rpm, deg, degC); the field
    names carry the units that differ from the kernels' SI (rad/s, rad), which are converted
    where the kernels are called."""

    Fa: float               # N
    Fr: float               # N
    speed_rpm: float        # inner-ring speed
    tilt_deg: float         # imposed inner-ring tilt
    oil_temperature: float  # degC

    @classmethod
    def from_config(cls, load):
        """One load case from a mapping with one number per key (:data:`LOAD_CASE_KEYS`); each
        checked against the ``load`` schema (:mod:`sim.config_schema`): InputError naming key,
        value and allowed range."""
        check_node(LoadConfig, load, "load", keys=LOAD_CASE_KEYS, scalar=True, error=InputError)
        return cls(*(float(load[k]) for k in LOAD_CASE_KEYS))

    def values(self):
        """The case as a tuple of floats in :data:`LOAD_CASE_KEYS` order (its config/Dataset keys)."""
        return tuple(float(getattr(self, f.name)) for f in fields(self))


@dataclass(frozen=True)
class SolverSettings:
    n_slices: int
    elasticity: str
    tolerance: float
    max_iterations: int
    roller_max_iterations: int
    centrifugal: bool
    gyroscopic: bool
    # Newton limits of sim.solvers.quasi_static (conf/solver/quasi_static.yaml gives the reasons,
    # sim.config_schema.SolverConfig the ranges)
    roller_tolerance_ratio: float
    forcing: float
    roller_step_interference: float
    roller_step_length: float
    line_search_halvings: int
    ring_step_fraction: float
    continuation_steps: int
    # validity limits of the model (check_limits; reasons in conf/solver/quasi_static.yaml)
    max_static_load_ratio: float
    max_speed_dm: float

    @classmethod
    def from_config(cls, solver):
        """From the ``solver`` config node; every key checked against its schema
        (:mod:`sim.config_schema`): InputError naming key, value and allowed range."""
        check_node(SolverConfig, solver, "solver", error=InputError)
        kinds = {f.name: f.type for f in fields(cls)}
        return cls(**{name: kind(solver[name]) for name, kind in kinds.items()})


def nominal_gap(geometry, kind, par, side, x):
    """Unloaded rigid gap [mm] between the roller and one raceway at positions x along the roller
    axis [mm] (array), the bearing at its nominal pose (the negative penetration of
    sim.physics.contact.slice_contact_meridian; side +1 outer, -1 inner), within
    sim.geometry.ROLLER_END_CLIP of the roller ends."""
    half = 0.5 * geometry.Lwe * (1.0 - ROLLER_END_CLIP)
    x = np.clip(np.asarray(x, dtype=float), -half, half)
    n = x.shape[0]
    d = np.empty(n)
    slice_contact_meridian(x, np.asarray(geometry.roller_radius(x), dtype=float), side, np.zeros(3), geometry.alpha,
                           geometry.Dpw, (kind, par), (0.0, 0.0, 0.0), (d, np.empty((n, 2)), np.empty((n, 2))))
    return -d


class BearingModel:
    """Kernel inputs of one bearing, built once and reused for every load case."""

    def __init__(self, geometry: Geometry, material, settings: SolverSettings):
        self.geometry = g = geometry
        self.settings = s = settings
        self._static = None     # static load limit's angles and C0 (_static_ratings)
        a = g.arrays
        self.E_star = contact_modulus(g.E, g.nu)
        # ISO/TS 16281: a roller with both raceway contacts in series carries
        # Q = c_L Lwe^(8/9) delta^(10/9); one contact takes half the approach, so its line
        # load is q = 2^(10/9) c_L Lwe^(-1/9) delta^(10/9).
        k_line = 2.0 ** (10.0 / 9.0) * float(material["slice_stiffness_iso16281"]) * g.Lwe ** (-1.0 / 9.0)
        self.elasticity = SliceElasticity(influence_matrix(a["x"], a["w"], self.E_star), float(self.E_star),
                                          ELASTICITY_MODES[s.elasticity], float(k_line))
        contiguous = np.ascontiguousarray
        # the rib contact's Hertz load law depends on the geometry only: its equivalent sphere
        # radius once here, not per contact evaluation (sim.physics.roller_contact.BearingArrays)
        rib = np.array(a["rib"], dtype=float)
        if g.type == "TRB":
            rib[5] = hertz_point_radii(rib[5], rib[2])[0]
        x = contiguous(a["x"], dtype=float)
        race_kind, race_par = contiguous(a["race_kind"], dtype=np.int64), contiguous(a["race_par"], dtype=float)
        # the contact ends beyond the end slice centres follow the profile (elasticity.loaded_lengths)
        end_drop = np.stack([end_profile_drop(x, partial(nominal_gap, g, race_kind[s], race_par[s], side),
                                              float(a["w"])) for s, side in enumerate((+1, -1))])
        self.bearing = BearingArrays(x, contiguous(a["rho"], dtype=float), float(a["w"]), race_kind, race_par,
                                     contiguous(a["R_eq"], dtype=float), rib,
                                     float(g.alpha), float(g.Dpw), float(g.Lwe), int(g.Z), g.type == "TRB", end_drop)
        self.newton = NewtonSettings(float(s.tolerance), int(s.max_iterations), int(s.roller_max_iterations),
                                     float(s.roller_tolerance_ratio), float(s.forcing),
                                     float(s.roller_step_interference), float(s.roller_step_length),
                                     int(s.line_search_halvings), float(s.ring_step_fraction))

    def _static_ratings(self):
        """(angle [deg], its source, C0 [N]) of the static load limit of :meth:`check_limits`, the
        cup angle alpha + gamma and ratings_alpha; computed on the first call (they depend on the
        geometry alone), InputError when an angle is not below 90 deg."""
        if self._static is None:
            g = self.geometry
            angles = {float(np.degrees(g.cup_angle)): "the cup angle alpha + gamma",
                      float(g.ratings_alpha): "bearing.ratings_alpha" if g.type == "TSRB" else
                      "the cup angle alpha + gamma"}
            for angle in angles:
                if not angle < 90.0:   # alpha + gamma: ISO 76 rates radial bearings only
                    raise InputError(f"bearing.alpha = {float(np.degrees(g.alpha)):g} deg is outside the allowed "
                                     f"range for this bearing: its cup angle alpha + gamma = {angle:g} deg must be "
                                     "< 90 deg, where ISO 76 / ISO 281 rate a radial roller bearing (the static "
                                     "load limit needs C0)")
            self._static = [(angle, source, float(ratings.static_load_rating(g.Dwe, g.Dpw, g.Lwe, g.Z, angle)))
                            for angle, source in angles.items()]
        return self._static

    def axial_static_limit(self):
        """The pure axial load [N] at which P0 = Y0 Fa reaches C0 of eq. (2.10) (ISO 76) at the angle of
        :meth:`check_limits` that binds: the largest Fa it accepts at solver.max_static_load_ratio = 1."""
        return min(C0 / float(ratings.equivalent_static_load(0.0, 1.0, angle)) for angle, _, C0 in self._static_ratings())

    def static_limit(self, raw):
        """The static load limit of :meth:`check_limits` on a solved contact (``raw``: a converged
        :meth:`solve` result): (s0, status). s0 = (4000 MPa / pmax)^2
        (sim.physics.ratings.static_safety_from_pressure); status None within the limit, else the
        reason the case is no result of the elastic model: s0 < 1 / solver.max_static_load_ratio (eq.
        (2.10)'s C0, which :meth:`check_limits` uses before the solve, assumes a line contact along
        the whole roller; a crowned TSRB roller has 2.2-3.7 times less static capacity)."""
        pmax = float(raw["pressure"].max())
        s0 = float(ratings.static_safety_from_pressure(pmax))
        limit = self.settings.max_static_load_ratio
        if s0 * limit >= 1.0:
            return s0, None
        return s0, (f"pmax = {pmax:.0f} MPa: static safety s0 = (4000 MPa / pmax)^2 = {s0:.3g} < 1 / "
                    f"solver.max_static_load_ratio = {1.0 / limit:.3g} (ISO 76: 4000 MPa at the most loaded contact "
                    "defines C0; beyond it the steel yields and the elastic contact model does not hold)")

    def load_failure(self, raw, op: OperatingPoint):
        """Why a :meth:`solve` result ``raw`` that did not converge has no load distribution, from its
        last iterate: the rollers it loads, the largest load and contact pressure, the ring's
        displacement, the residual, and with a radial load Fa / Fr beside the single-row bound
        tan(beta) of :meth:`check_limits` (near it the load zone closes to one roller and the ring's
        place is barely determined: the ring then moves by tenths of a millimetre, README "Heavy and
        near-bound random cases")."""
        Q = raw["Q"].sum(axis=1) + raw["Q_rib"]
        ring = raw["ring"]
        text = (f"no load equilibrium found after {raw['iterations']} ring iterations; its last "
                f"iterate loads {int(np.count_nonzero(Q > 0.0))} of {Q.shape[0]} rollers (the largest {Q.max():.6g} "
                f"N, pmax {float(raw['pressure'].max()):.0f} MPa), moves the inner ring {ring[0]:.4g} mm axially and "
                f"{ring[1]:.4g} mm radially and leaves a residual of {float(np.abs(raw['residual']).max()):.4g} N")
        if op.Fr > 0.0:
            text += (f"; Fa / Fr = {op.Fa / op.Fr:.4g} against the single-row bound tan(beta) = "
                     f"{float(np.tan(self.geometry.single_row_thrust_angle)):.4g}")
        return text

    def check_limits(self, op: OperatingPoint):
        """Refuse a load case beyond the validity of the model, before any solve: OutOfRangeError
        (an InputError) naming the load key, its value, the allowed range for this bearing and the reason.

        - speed x Dpw <= solver.max_speed_dm (quasi-static model, no roller / cage dynamics, no
          heat balance of the bearing);
        - P0 <= solver.max_static_load_ratio x C0 (ISO 76; elastic contacts), with P0 and C0 at
          ratings_alpha (the reported P0, C0) and at the cup angle alpha + gamma, which carries
          the axial load (for a TRB both are the same angle): a configured TSRB ratings_alpha does
          not hide a roller-axis angle too flat to carry Fa elastically;
        - Fa > Fr tan(beta) with Fr > 0, beta the angle at which each roller presses the inner ring
          (:attr:`sim.geometry.Geometry.single_row_thrust_angle`: the TRB's cup angle, the TSRB's
          roller-axis angle), so a single row carries Fa / Fr > tan(beta) only, the bound reached
          with one loaded roller (Sjovall's load zone epsilon -> 0; Harris & Kotzalas 2007, Rolling
          Bearing Analysis, 7.4); below it the inner ring has no equilibrium with its axial position
          free (an opposed bearing would take the rest, which the model lacks), or, for the TSRB, one
          only with its rollers tilted by degrees and the ring millimetres off its place.
        """
        g = self.geometry
        s = self.settings
        if op.speed_rpm > s.max_speed_dm / g.Dpw:
            raise OutOfRangeError(f"load.speed = {op.speed_rpm:g} rpm is outside the allowed range for this bearing: "
                             f"<= solver.max_speed_dm / Dpw = {s.max_speed_dm:g} / {g.Dpw:g} = "
                             f"{s.max_speed_dm / g.Dpw:g} rpm (beyond it roller and cage dynamics and the bearing's "
                             "heat balance govern, which the quasi-static model lacks; conf/solver/quasi_static.yaml)")
        k = s.max_static_load_ratio
        worst = None
        for angle, source, C0 in self._static_ratings():
            with np.errstate(divide="ignore"):    # Y0 = 0.22 cot(angle) is infinite at an angle of 0
                P0 = float(ratings.equivalent_static_load(op.Fr, op.Fa, angle))
            if worst is None or P0 / C0 > worst[0]:
                worst = (P0 / C0, P0, C0, angle, source)
        ratio, P0, C0, angle, source = worst
        if ratio <= k:
            self._check_axial_share(op)
            return
        with np.errstate(divide="ignore"):
            f = ratings.load_factors(angle)
        why = (f"P0 = max(X0 Fr + Y0 Fa, Fr) = {P0:.6g} N at contact angle {angle:.4g} deg ({source}) exceeds "
               f"solver.max_static_load_ratio x C0 = {k:g} x {C0:.6g} N: ISO 76's C0 is the load of 4000 MPa contact "
               "stress, beyond which the steel yields and the elastic contact model is invalid; "
               "conf/solver/quasi_static.yaml")
        if op.Fr > k * C0:
            raise OutOfRangeError(f"load.Fr = {op.Fr:g} N is outside the allowed range for this bearing: "
                             f"<= {k * C0:.6g} N ({why})")
        raise OutOfRangeError(f"load.Fa = {op.Fa:g} N is outside the allowed range for this bearing at load.Fr = "
                         f"{op.Fr:g} N: <= {(k * C0 - f['X0'] * op.Fr) / f['Y0']:.6g} N ({why})")

    def _check_axial_share(self, op: OperatingPoint):
        """The single-row equilibrium bound Fa > Fr tan(beta) of :meth:`check_limits`."""
        g = self.geometry
        angle = g.single_row_thrust_angle
        bound = op.Fr * float(np.tan(angle))
        if op.Fr > 0.0 and not op.Fa > bound:
            why = ("each roller presses the inner ring at the cup angle (its rib and inner raceway balance the cup's "
                   "normal force), so below it the inner ring has no equilibrium with its axial position free"
                   if g.type == "TRB" else
                   "each roller presses the inner ring normal to its own axis (its raceway forces act through the "
                   "centres of its two crown circles, which lie on a normal to the axis), so below it the inner ring "
                   "has no equilibrium at the rollers' place, only one with the rollers tilted by degrees in their "
                   "osculating raceways and the ring millimetres off")
            raise OutOfRangeError(
                f"load.Fa = {op.Fa:.8g} N is outside the allowed range for this bearing at load.Fr = {op.Fr:g} N: "
                f"> Fr tan({float(np.degrees(angle)):.4g} deg) = {bound:.8g} N, the single row's axial share: "
                f"{why} (an opposed bearing would take the rest)")

    def body_loads(self, op: OperatingPoint):
        """Body loads on a loaded roller, rolling kinematics (2.20), (2.22): BodyLoads(centrifugal
        force m omega_c^2 Dpw/2 [N], gyroscopic moment I_x omega_R omega_c sin(alpha) [N mm])."""
        g = self.geometry
        omega_c = angular_speed(cage_speed_rolling(op.speed_rpm, 0.0, g.Dwe, g.Dpw, g.alpha))
        omega_r = angular_speed(roller_speed_rolling(op.speed_rpm, 0.0, g.Dwe, g.Dpw, g.alpha))
        Fc = g.arrays["mass"] * omega_c**2 * 0.5 * g.Dpw if self.settings.centrifugal else 0.0
        Mg = g.arrays["inertia_axial"] * omega_r * omega_c * np.sin(g.alpha) if self.settings.gyroscopic else 0.0
        return BodyLoads(float(Fc), float(Mg))

    def hertz_pressure(self, q):
        """Hertz pressure [MPa] of every slice of line loads q (Z, 2, N) [N/mm]: the kernel's
        formula evaluated by numpy (py_func), so that no array signature of it is compiled."""
        p0 = getattr(hertz_line_pressure, "py_func", hertz_line_pressure)
        return np.where(q > 0.0, p0(np.maximum(q, 0.0), self.geometry.arrays["R_eq"][None, :, :], self.E_star), 0.0)

    def initial_ring(self, op: OperatingPoint):
        """Start value of the inner-ring displacement (delta_a, delta_r, delta_y) [mm]: the line-contact
        approach of an equal share of max(Fa, Fr) along the roller axis normal (APPROACH_LOG_TERM)."""
        g = self.geometry
        Q = max(op.Fa, op.Fr) / (g.Z * np.sin(g.alpha))
        q = Q / (0.5 * g.Lwe)
        approach = 2.0 * 2.0 * q / (np.pi * self.E_star) * APPROACH_LOG_TERM
        return np.array([approach / np.sin(g.alpha), 0.0, 0.0])

    def solve(self, op: OperatingPoint, roller_loads=None, ring_loads=None, start=None):
        """Solve one case; returns a dict of plain arrays (kernel units) and the status.

        Parameters
        ----------
        op : OperatingPoint
            The load case.
        roller_loads : array_like (Z, 3), optional
            External generalised load on each roller (friction, :mod:`sim.physics.friction`), in the
            roller's own tilted frame (u' along its axis towards the large end, v' normal to
            it in its meridian plane, outwards to the outer ring) and added to the roller
            equilibrium like the body loads:
            [0] force along u' [N], positive towards the large end;
            [1] force along v' [N], positive outwards (towards the outer raceway);
            [2] moment about u' x v' = -e_t through the roller centre [N mm], positive when it
            turns u' towards v' (increases the roller tilt theta).
            None means zeros. Loads on rollers the rings do not squeeze are ignored (the cage
            holds them). Unequal loads on rollers psi and -psi switch off the mirror symmetry
            (all Z rollers are solved, and the ring's lateral displacement delta_y with them,
            :func:`sim.solvers.quasi_static.solve_bearing`).
        ring_loads : array_like (Z, 3), optional
            External load on the inner ring at each roller (the reaction of the friction of that
            roller's inner-raceway and rib contacts, :func:`sim.physics.friction.friction_loads`)
            in the roller's frame: [0] along e_r [N], [1] along e_t [N], [2] along e_z [N]. The ring
            balances them with Fa and Fr: they are added to Fa (their sum along z), to Fr (their
            sum along x, sum of [0] cos(psi_j) - [1] sin(psi_j), of either sign: under an imposed
            tilt with Fr = 0 the ring then takes a small radial load) and make a lateral load Fy
            (their sum along y, sum of [0] sin(psi_j) + [1] cos(psi_j): the tangential tractions of
            the load zone add up along y), which the ring balances with its lateral displacement;
            both sums are exactly 0 when all rollers carry the same (the axisymmetric case). None
            means zeros.
        start : dict, optional
            A converged result of ``solve`` for the same ``op`` (other roller loads): its ring
            displacement, poses and slice loads are the start (a warm start of a few
            iterations instead of one from rigid poses); without convergence from there the
            case is solved from the usual start.

        Returns
        -------
        dict
            converged, iterations (ring), residual (axial, radial, lateral) [N], wall_time [s], ring
            (delta_a, delta_r, delta_y) [mm], ring_load (Fa, Fr, Fy) [N] as balanced (with the
            ring_loads' sums), poses (Z, 3) (xi [mm], eta [mm], theta [rad]),
            line_load (Z, 2, N) [N/mm], pressure (Z, 2, N) [MPa], Q (Z, 2) [N], Q_rib (Z,) [N],
            rib_contact (Z, 4) (rib contact point (r, z) [mm] on the roller end and unit rib
            normal (r, z) into the rib in the roller's meridian plane; the rib load acts on the
            roller along -normal; zeros for the TSRB), roller_loads (Z, 3) as applied, free (Z, 2, N)
            free penetrations of the slices [mm] (:func:`sim.physics.elasticity.coupled_slice_loads`), frames
            (:data:`sim.physics.roller_contact.ContactFrames` of the Z rollers at the returned
            poses when converged: slice contact points and normals, roller centres and axes,
            roller-end / rib points), and solver_info (roller iterations, contact evaluations,
            ring backtracks, continuation steps, roller classes solved, rollers outside the load zone
            left unloaded where no rest on the outer raceway was found: released by the rest's solve,
            or all of them where that solve found no equilibrium and the solution without the rest
            stands, with a warning).
        """
        g = self.geometry
        s = self.settings
        n = g.n_slices
        if roller_loads is None:
            ext = np.zeros((g.Z, 3))
        else:
            ext = np.ascontiguousarray(roller_loads, dtype=float)
            if ext.shape != (g.Z, 3) or not np.all(np.isfinite(ext)):
                raise InputError(f"roller_loads must be a finite array of shape ({g.Z}, 3), got shape {ext.shape}")
        Fa, Fr, Fy = op.Fa, op.Fr, 0.0
        if ring_loads is not None:
            ring_ext = np.asarray(ring_loads, dtype=float)
            if ring_ext.shape != (g.Z, 3) or not np.all(np.isfinite(ring_ext)):
                raise InputError(f"ring_loads must be a finite array of shape ({g.Z}, 3), got shape {ring_ext.shape}")
            Fa += float(ring_ext[:, 2].sum())
            if np.any(ring_ext[:, :2] != ring_ext[0, :2]):
                psi = 2.0 * np.pi * np.arange(g.Z) / g.Z
                cos_psi, sin_psi = np.cos(psi), np.sin(psi)   # not s: the solver settings below
                Fr += float(ring_ext[:, 0] @ cos_psi - ring_ext[:, 1] @ sin_psi)
                Fy = float(ring_ext[:, 0] @ sin_psi + ring_ext[:, 1] @ cos_psi)
            if Fa <= 0.0:
                raise InputError(f"the friction loads on the inner ring reverse the applied axial load: load.Fa = "
                                 f"{op.Fa} N -> {Fa} N (allowed: > 0)")
        body = self.body_loads(op)
        problem = QuasiStaticProblem(self.bearing, self.elasticity, self.newton, body, False)
        # with the centrifugal force the rollers outside the load zone rest, a TRB's on the cup and the
        # rib, a TSRB's in the wedge between both raceways (sim.solvers.quasi_static, module docstring):
        # a second solve from the converged one
        resting = problem._replace(rest=True) if body.centrifugal > 0.0 else None
        rollers = RollerSet(np.zeros((g.Z, 3)), np.zeros((g.Z, 2, n)), np.zeros((g.Z, 2, n), dtype=np.bool_),
                            np.zeros((g.Z, 2)), np.zeros(g.Z), np.zeros((g.Z, 4)), empty_frames(g.Z, n),
                            np.zeros((g.Z, 2, n)))
        poses, q, active = rollers.poses, rollers.q, rollers.active
        totals = np.zeros(3, dtype=np.int64)  # roller iterations, contact evaluations, ring backtracks
        reports = []

        def run(Fa, Fr, tilt_rad, ring, warm, problem=problem, Fy=Fy):
            report = solve_bearing(Fa, Fr, Fy, tilt_rad, ext, problem, ring, rollers, warm)
            totals[:] += (report.roller_iterations, report.contact_evaluations, report.ring_backtracks)
            reports.append(report)
            return bool(report.converged)

        ext_case = ext.copy()
        tilt_rad = np.radians(op.tilt_deg)
        t0 = clock()
        converged = False
        rested = False
        iterations = 0
        steps = 0
        if start is not None and start["converged"]:
            ring = start["ring"].copy()
            poses[:] = start["poses"]
            q[:] = start["line_load"]
            active[:] = q > 0.0
            converged = run(Fa, Fr, tilt_rad, ring, True, resting or problem)
            iterations = reports[-1].iterations
            steps = 1
            rested = converged
        if not converged:
            ring = self.initial_ring(op)
            converged = run(Fa, Fr, tilt_rad, ring, False)
            iterations += reports[-1].iterations
            steps += 1
        if not converged and s.continuation_steps > 1 and (Fr != 0.0 or Fy != 0.0 or tilt_rad != 0.0
                                                           or np.any(ext_case != 0.0)):
            # continuation (Allgower & Georg 2003, Introduction to Numerical Continuation Methods,
            # ch. 1): from the axisymmetric case (Fa alone, solved with the ring under load
            # control) to the case along lam in [0, 1] (Fr, tilt and roller loads times lam), each
            # solution the start of the next; a failed increment is halved from the last solution,
            # down to 1 / continuation_steps
            saved = None
            lam, dlam = 0.0, CONTINUATION_FIRST_STEP
            ring = self.initial_ring(OperatingPoint(op.Fa, 0.0, op.speed_rpm, 0.0, op.oil_temperature))
            ext[:] = 0.0
            ok = run(Fa, 0.0, 0.0, ring, False, Fy=0.0)
            iterations += reports[-1].iterations
            steps += 1
            while ok and lam < 1.0 and steps < 2 * s.continuation_steps:
                saved = (lam, ring.copy(), poses.copy(), q.copy(), active.copy())
                trial = min(1.0, lam + dlam)
                ext[:] = trial * ext_case
                ok = run(Fa, trial * Fr, trial * tilt_rad, ring, True, Fy=trial * Fy)
                iterations += reports[-1].iterations
                steps += 1
                if ok:
                    lam = trial
                    dlam *= 2.0
                    continue
                lam, ring[:], poses[:], q[:], active[:] = saved
                dlam *= 0.5
                ok = dlam * s.continuation_steps >= 1.0
            converged = ok and lam == 1.0
            if not converged:
                ext[:] = ext_case
        unrested = 0
        if converged and resting is not None and not rested and np.any(rollers.Q.sum(axis=1) == 0.0):
            without_rest = (ring.copy(), _copy_rollers(rollers), reports[-1])
            converged = run(Fa, Fr, tilt_rad, ring, True, resting)
            iterations += reports[-1].iterations
            steps += 1
            if not converged:
                # no equilibrium with the rest (a TSRB roller's shallow wedge, a ring iteration that
                # stalls on the rests' contacts): the converged solution without it stands, and its
                # unloaded rollers are reported as left unrested (solver_info)
                ring[:] = without_rest[0]
                _restore_rollers(rollers, without_rest[1])
                reports.append(without_rest[2])
                unrested = int(np.count_nonzero(rollers.Q.sum(axis=1) == 0.0))
                converged = True
        wall_time_s = solver_seconds(t0)
        pressure = self.hertz_pressure(q)
        last = reports[-1]
        solver_info = dict(roller_iterations=int(totals[0]), contact_evaluations=int(totals[1]),
                           ring_backtracks=int(totals[2]), continuation_steps=steps,
                           roller_classes=int(last.roller_classes),
                           unrested_rollers=max(unrested, int(last.unrested_rollers)))
        raw = dict(converged=bool(converged), iterations=int(iterations),
                   residual=np.array([last.residual_axial, last.residual_radial, last.residual_lateral]),
                   wall_time=wall_time_s, ring=ring, ring_load=np.array([Fa, Fr, Fy]),
                   poses=poses, line_load=q, pressure=pressure, Q=rollers.Q, Q_rib=rollers.Q_rib,
                   rib_contact=rollers.rib_contact, roller_loads=ext, frames=rollers.frames, free=rollers.free,
                   solver_info=solver_info)
        if not converged:
            raw["status"] = self.load_failure(raw, op)
        return raw


def _copy_rollers(rollers):
    """A copy of the arrays of a :data:`sim.solvers.quasi_static.RollerSet` (its frames included)."""
    return [a.copy() for a in _roller_arrays(rollers)]


def _restore_rollers(rollers, saved):
    """Write the arrays of :func:`_copy_rollers` back into ``rollers`` (in place)."""
    for a, b in zip(_roller_arrays(rollers), saved):
        a[...] = b


def _roller_arrays(rollers):
    return [a for a in rollers if isinstance(a, np.ndarray)] + list(rollers.frames)


def roller_shift_relative_to_inner_ring(g, xi, ring, tilt):
    """Roller shift along its axis relative to the inner ring (where a TRB has its rib) [mm].

    xi is measured in the fixed (outer-ring) frame; the inner-ring material point at the
    nominal roller centre (Dpw/2, 0) moves by Rot(phi) P0 + Delta - P0 in each meridian plane
    (phi = tilt cos(psi), Delta = (delta_r cos(psi) + delta_y sin(psi), delta_a)); its component along the roller
    axis u = (sin(alpha), -cos(alpha)) is subtracted. Positive: towards the large end.
    """
    psi = 2.0 * np.pi * np.arange(g.Z) / g.Z
    phi = tilt * np.cos(psi)
    r0 = 0.5 * g.Dpw
    dr = r0 * (np.cos(phi) - 1.0) + ring[1] * np.cos(psi) + ring[2] * np.sin(psi)
    dz = r0 * np.sin(phi) + ring[0]
    return xi - (dr * np.sin(g.alpha) - dz * np.cos(g.alpha))


def case_results(model: BearingModel, op: OperatingPoint, raw, output_cfg):
    """Derived per-case outputs of DATA.md from a solved state (all in output units)."""
    g = model.geometry
    n = g.n_slices
    w = g.slice_width
    res = {"converged": raw["converged"], "iterations": raw["iterations"], "wall_time": raw["wall_time"],
           "unrested_rollers": raw["solver_info"]["unrested_rollers"]}
    P = float(ratings.equivalent_dynamic_load(op.Fr, op.Fa, g.ratings_alpha))
    P0 = float(ratings.equivalent_static_load(op.Fr, op.Fa, g.ratings_alpha))
    res.update(P=P, P0=P0)
    if not raw["converged"]:    # the solver's reason (BearingModel.load_failure; the dynamic run sets its own)
        return res | ({"status": raw["status"]} if "status" in raw else {})
    p = raw["pressure"]                       # (Z, 2, N) MPa
    s0, status = model.static_limit(raw)      # a case beyond it is no result of the elastic model
    if status is not None:
        log.warning("%s at Fa = %g N, Fr = %g N, %g rpm, tilt %g deg: %s; reported as not converged",
                    g.type, op.Fa, op.Fr, op.speed_rpm, op.tilt_deg, status)
        return res | {"converged": False, "status": status}
    if res["unrested_rollers"]:
        # said of the case's final solve (the friction-load coupling solves it again, and a later solve
        # may rest rollers the first one left unloaded: the warning then contradicted the result)
        log.warning("%s at Fa = %g N, Fr = %g N, %g rpm, tilt %g deg: no equilibrium with the %d rollers outside "
                    "the load zone resting; they are left unloaded (their centrifugal contact and its rolling loss "
                    "neglected)", g.type, op.Fa, op.Fr, op.speed_rpm, op.tilt_deg, res["unrested_rollers"])
    j = int(np.argmax(raw["Q"].sum(axis=1)))  # most loaded roller
    xi_rel = roller_shift_relative_to_inner_ring(g, raw["poses"][:, 0], raw["ring"], np.radians(op.tilt_deg))
    thr = float(output_cfg["contact_pressure_threshold"])
    # loaded length (2,) [mm]: slices above the threshold pressure, the contact ends placed between
    # slice centres (sim.physics.elasticity.loaded_lengths), continuous where a slice enters contact
    strips = np.zeros(n)
    length = np.zeros(2)
    for s in range(2):
        loaded_lengths(np.ascontiguousarray(raw["free"][j, s]), p[j, s] > thr, w, model.bearing.end_drop[s], strips)
        length[s] = strips.sum()
    L_eff = float(length.min())
    # edge contact (2,) [1]: interference at the roller ends over the contact's largest elastic
    # approach, worst roller (sim.physics.elasticity.edge_interference); > 0: the contact runs
    # onto a roller end, whose sharp edge concentrates the pressure (edge stress)
    edge_int = np.empty(2)
    edge_interference(np.ascontiguousarray(raw["free"]), p > thr, model.bearing.end_drop, edge_int)
    C_eff = float(ratings.dynamic_load_rating(g.Dwe, g.Dpw, L_eff, g.Z, g.ratings_alpha, g.b_m)) if L_eff > 0 else 0.0
    res.update(
        pmax=p.max(axis=(0, 2)),
        static_safety_factor=s0,
        axial_displacement=float(xi_rel[j]),
        contact_length_ratio=length / g.Lwe,
        L_eff=L_eff,
        edge_stress=bool(np.any(edge_int > 0.0)),
        edge_interference=edge_int,
        ring_displacement=raw["ring"].copy(),
        Q=raw["Q"],
        Q_rib=raw["Q_rib"],
        pressure=p[j],
        roller_tilt=np.degrees(raw["poses"][:, 2]),
        roller_axial_displacement=xi_rel,
        C_eff=C_eff,
        L10=float(ratings.basic_rating_life(C_eff, P)) if C_eff > 0 else 0.0,
        cage_speed=float(cage_speed_rolling(op.speed_rpm, 0.0, g.Dwe, g.Dpw, g.alpha)),
        residual=raw["residual"],
    )
    return res

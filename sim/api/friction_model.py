"""Friction parameters of one bearing, lubricant and friction config, and the evaluation of a
solved case: film, kinematics from the traction balance, torque and its breakdown
(MODEL.md 5, thesis 5.4; the kernels are in :mod:`sim.physics.friction` and
:mod:`sim.solvers.kinematics`).
"""
from collections import namedtuple

import numpy as np

from sim.io import RPM_PER_RAD_S, UM_PER_MM, W_PER_N_MM_PER_S
from sim.physics.contact import hertz_point_radii
from sim.physics.ehl import FILM_FORMULAS, PRESSURE_VISCOSITY_MODELS, FilmRheology, SolidFriction, roelands_index
from sim.physics.friction import (TRACTION_LAWS, EV_MU, EV_P0, EV_PSKEW, EV_TRING, EV_TZ, FL_RING_R, FL_RING_T,
                                  FL_RING_Z, FL_U, FL_W, NC, NEV, NFL, NRP, RP_COS, RP_DA, RP_DR, RP_SIN, ContactLoads,
                                  FilmState, FrictionCase, FrictionParams, lubrication_state, ring_surface_speed,
                                  roller_friction, width_quadrature)
from sim.physics.kinematics import angular_speed, cage_speed_rolling, roller_speed_rolling
from sim.physics.lubricant import MPA_S_PER_PA_S
from sim.solvers.symmetry import mirror_mean, symmetry_classes
from sim.solvers.kinematics import FreeRollers, KinematicsSettings, empty_jacobian, free_roller_speeds, solve_friction

# unit conversions of the config (SI, um) to kernel units (mm, N, s, MPa) and of results to output units
MM_PER_M = 1e3
MM_PER_UM = 1e-3
MM2_PER_M2 = 1e6
T_PER_MM3_PER_KG_PER_M3 = 1e-12     # density: 1 kg/m^3 = 1e-12 t/mm^3

# Speed 0 (``load.speed = 0``): the zero-speed breakaway (starting) torque, the speed -> 0 limit of
# the model without a film. No entrainment, hence no EHL film and no EHL rolling loss; no rolling,
# hence no hysteresis loss and no drag; every raceway and rib contact in boundary friction (solid
# load share 1, Coulomb mu = friction.solid_friction_coefficient) along the slip directions at the
# onset of motion: with friction.kinematics = traction the roller and cage speeds that balance
# those Coulomb forces (free rollers start to roll where their moments vanish), with rolling the
# directions of rolling kinematics (2.20), (2.22). This is the SKF (2004) starting torque, the
# sliding frictional moment with the boundary-lubrication coefficient and no rolling moment, and
# Harris & Kotzalas (2007, Advanced Concepts, ch. 4: friction at start-up, boundary lubrication
# without an EHL film). Coulomb forces do not depend on the slip speed, so every loss power is
# proportional to the speed and power / inner-ring speed is the same at any speed: the kernels run
# at the nominal speed BREAKAWAY_NOMINAL_SPEED with the solid friction's regularising speed v_s
# (tanh(|v| / v_s), sim.physics.ehl) replaced by BREAKAWAY_SLIP_RESOLUTION times the pitch surface
# speed, so that it is saturated wherever a contact slips. Measured: the raceway slips of the TRB
# 32208 are 1e-8 to 1e-7 of the surface speed, its breakaway torque changes by < 1e-8 relative
# between resolutions 1e-10 and 1e-12 (3.4 % at 1e-6); the TSRBs' slips are 1e-3 to 1e-1.
BREAKAWAY_NOMINAL_SPEED = 1.0       # rpm: sets the slip directions only
BREAKAWAY_SLIP_RESOLUTION = 1e-10   # 1, v_s of the breakaway case over the pitch surface speed


# The kinematic problem of one solved case (FrictionModel.problem): the kernel bundle and settings,
# start values (cage speed wc, roller speeds wR (Z,) [rad/s], skews psi (Z,) [rad], Jacobian jac),
# inner-ring speed wi [rad/s], whether the start is rolling kinematics (fresh) and the case static
# (speed 0), the symmetry classes (weight, source: sim.solvers.symmetry) and the roller loads (Z,) [N].
FrictionProblem = namedtuple("FrictionProblem", ["case", "settings", "wc", "wR", "psi", "wi", "jac", "fresh", "static",
                                                 "weight", "source", "load"])


def rib_end_hertz(rib_end):
    """The friction kernels' roller-end array (:data:`sim.physics.friction.ContactLoads` ``rib_end``,
    (6,)): the geometry's (R_n, x_n, R_t, R_m) [mm] followed by the equivalent-circle radius of the
    Hertz contact area [mm] and its ellipticity along e_t [1]
    (:func:`sim.physics.contact.hertz_point_radii`)."""
    R_t, R_m = float(rib_end[2]), float(rib_end[3])
    _, R_area, kappa = hertz_point_radii(R_t, R_m) if R_t > 0.0 else (0.0, 0.0, 0.0)   # 0: no rib (TSRB)
    return np.array([*(float(v) for v in rib_end), R_area, kappa])


class FrictionModel:
    """Friction parameters of one bearing, lubricant and friction config; evaluates solved cases.

    Parameters
    ----------
    geometry : sim.geometry.Geometry
    E_star : float
        Contact modulus [MPa].
    lubricant : sim.physics.lubricant.Lubricant
    friction : mapping
        The ``friction`` config node (conf/friction/default.yaml).
    surface : mapping
        ``bearing.surface``: sigma [um], B_ZH, C_ZH (and the rib's for a TRB).
    material : mapping
        The ``material`` config node: density [kg/m^3], and for ``friction.thermal`` the
        thermal conductivity [W/(m K)] and specific heat [J/(kg K)] of the steel.
    """

    def __init__(self, geometry, E_star, end_drop, lubricant, friction, surface, material):
        g = self.geometry = geometry
        self.E_star = E_star
        self.end_drop = end_drop      # (2, 2, M) mm: the contact ends beyond the end slice centres (BearingArrays)
        self.lubricant = lubricant
        # every value below passed the schema (sim.config_schema) in sim.api.simulation
        film = str(friction["film_thickness"])
        self.traction_kinematics = str(friction["kinematics"]) == "traction"
        self.free_rollers = str(friction["cage_guidance"]) == "free"
        self.tolerance = float(friction["tolerance"])
        self.max_iterations = int(friction["max_iterations"])
        self.seed_tolerance_factor = float(friction["seed_tolerance_factor"])
        self.load_coupling_tolerance = float(friction["load_coupling_tolerance"])
        self.load_coupling_passes = int(friction["load_coupling_passes"])
        self.load_coupling_depth = int(friction["load_coupling_depth"])
        drag = friction["drag"]
        model = str(drag["model"])
        mu_s = float(friction["solid_friction_coefficient"])
        v_s = MM_PER_M * float(friction["solid_slip_velocity"])
        self.solid_slip_ratio = float(friction["solid_slip_ratio"])
        hysteresis = float(friction["hysteresis_loss_factor"])
        mu_cage = float(friction["cage_friction_coefficient"])
        sigma = MM_PER_UM * float(surface["sigma"])
        B_ZH = float(surface["B_ZH"])
        C_ZH = float(surface["C_ZH"])
        sigma_rib = B_ZH_rib = C_ZH_rib = 0.0       # no roller-end / rib contact in a TSRB
        if g.type == "TRB":
            sigma_rib = MM_PER_UM * float(surface["sigma_rib"])
            B_ZH_rib = float(surface["B_ZH_rib"])
            C_ZH_rib = float(surface["C_ZH_rib"])
        thermal = bool(friction["thermal"])
        k_steel = kappa_steel = 0.0                 # unused when isothermal
        if thermal:
            k_steel = float(material["thermal_conductivity"])
            # kappa = k / (rho c) [m^2/s] with rho [kg/m^3], c [J/(kg K)]
            kappa_steel = MM2_PER_M2 * k_steel / (float(material["density"]) * float(material["specific_heat"]))
        dT_tol = float(friction["temperature_tolerance"])
        self.inner_ring_temperature_rise = float(friction["inner_ring_temperature_rise"])     # K
        self.drag_factor = 0.0
        if model == "roller_drag":
            cd = float(drag["drag_coefficient"])
            X = float(drag["oil_volume_fraction"])
            # F_D = 1/2 rho X C_D Dwe Lwe (omega_c Dpw/2)^2 with rho [kg/m^3] as [t/mm^3]
            self.drag_factor = 0.5 * X * cd * g.Dwe * g.Lwe * (0.5 * g.Dpw) ** 2 * T_PER_MM3_PER_KG_PER_M3
        self.drag_model = model
        # cage pocket that holds a skewed roller (sim.physics.friction, "Roller skew"): clearance c and
        # stiffness k of the pocket at each roller end give the skew at contact atan(c / Lwe) and the
        # couple per skew beyond it, k Lwe^2 / 2 (two end contacts at +-Lwe/2, each k (Lwe/2) dpsi)
        skew = friction["skew"]
        skew_on = bool(skew["enabled"])
        skew_clearance = float(np.arctan(float(skew["pocket_clearance"]) / g.Lwe))
        skew_stiffness = 0.5 * float(skew["pocket_stiffness"]) * g.Lwe ** 2
        self.pocket_clearance = float(skew["pocket_clearance"])     # mm, the dynamic solver's pocket too
        self.pocket_stiffness = float(skew["pocket_stiffness"])     # N/mm per roller end
        self.pocket_transition = float(skew["pocket_transition"])   # mm, the walls' onset (sim.physics.friction.pocket_wall_force)
        # the per-case fields (eta0, eta0_inner, alpha, Z, rheology.tau_E0, beta, drag_k: oil temperature) are set by
        # problem()
        self.par = FrictionParams(
            eta0=np.nan, eta0_inner=np.nan, alpha=np.nan, Z=np.nan,
            pv_model=PRESSURE_VISCOSITY_MODELS[lubricant.pressure_viscosity_model], beta=np.nan,
            traction_law=TRACTION_LAWS[str(friction["traction_law"])],
            rheology=FilmRheology(tau_E0=np.nan,
                                  tau_L0=float(lubricant.limiting_shear_stress_0),
                                  c_tau=float(lubricant.limiting_shear_coefficient), G=float(lubricant.shear_modulus)),
            solid=SolidFriction(mu_s=mu_s, v_s=v_s), hysteresis=hysteresis, mu_cage=mu_cage,
            sigma=sigma, B_ZH=B_ZH, C_ZH=C_ZH, sigma_rib=sigma_rib, B_ZH_rib=B_ZH_rib, C_ZH_rib=C_ZH_rib,
            film=FILM_FORMULAS[film], drag_k=np.nan, thermal=thermal, k_oil=float(lubricant.thermal_conductivity),
            k_steel=k_steel, kappa_steel=kappa_steel, dT_tol=dT_tol,
            inlet_heating=bool(friction["inlet_shear_heating"]), boundary_only=False, skew=skew_on,
            skew_clearance=skew_clearance, skew_stiffness=skew_stiffness)
        self.quad = width_quadrature(friction["width_points"])
        self.rib_end = rib_end_hertz(g.arrays["rib_end"])     # geometry only: once, not per case
        # the roller's moment of inertia about its axis [t mm^2] (sim.geometry, from its profile and
        # material.density): the free rollers' spin inertia along the orbit (evaluate)
        self.roller_spin_inertia = float(g.arrays["inertia_axial"])

    def problem(self, op, raw, start=None, final=True):
        """The kinematic problem of one solved case (raw: BearingModel.solve output), as
        :meth:`evaluate` hands it to :func:`sim.solvers.kinematics.solve_friction`: a
        :data:`FrictionProblem` whose arrays are the solve's start values (``start``, ``final`` as in
        :meth:`evaluate`) and whose ``case.film`` the solve writes.
        """
        g = self.geometry
        a = g.arrays
        Z, n = g.Z, g.n_slices
        eta0 = float(self.lubricant.dynamic_viscosity(op.oil_temperature)) * MPA_S_PER_PA_S
        alpha = float(self.lubricant.pressure_viscosity_at(op.oil_temperature))
        eta0_inner = float(self.lubricant.dynamic_viscosity(op.oil_temperature + self.inner_ring_temperature_rise)) \
            * MPA_S_PER_PA_S
        par = self.par._replace(
            eta0=eta0, eta0_inner=eta0_inner, alpha=alpha, Z=float(roelands_index(eta0, alpha)),
            rheology=self.par.rheology._replace(tau_E0=float(self.lubricant.eyring_stress_at(op.oil_temperature))),
            beta=float(self.lubricant.temperature_viscosity_coefficient(op.oil_temperature)),
            drag_k=self.drag_factor * float(self.lubricant.density(op.oil_temperature)))
        static = op.speed_rpm == 0.0
        speed = BREAKAWAY_NOMINAL_SPEED if static else op.speed_rpm
        wi = float(angular_speed(speed))
        # the boundary friction's regularising slip: at most a share of the pitch surface speed, a creepage
        # (conf/friction/default.yaml, solid_slip_ratio; so that the torque tends to the breakaway torque as the
        # speed falls to 0), and for the breakaway case its resolution (Coulomb friction wherever a contact slips)
        ratio = BREAKAWAY_SLIP_RESOLUTION if static else self.solid_slip_ratio
        par = par._replace(solid=par.solid._replace(v_s=min(par.solid.v_s, ratio * wi * 0.5 * g.Dpw)))
        if static:   # no film; no drag (it goes as the speed squared)
            par = par._replace(drag_k=0.0, boundary_only=True)
        frames = raw["frames"]          # contact frames at the solution, from the quasi-static solve
        bearing = ContactLoads(q=raw["line_load"], Qrib=raw["Q_rib"], R_eq=a["R_eq"], w=float(g.slice_width),
                                E_star=float(self.E_star), rib_end=self.rib_end,
                                nrib=np.ascontiguousarray(raw["rib_contact"][:, 2:4]), rho_m=0.5 * g.Dwe,
                                free=raw["free"], end_drop=self.end_drop,
                                ring=inner_ring_poses(Z, raw["ring"], float(np.radians(op.tilt_deg))))
        wc = float(angular_speed(cage_speed_rolling(speed, 0.0, g.Dwe, g.Dpw, g.alpha)))
        wR = np.full(Z, float(angular_speed(roller_speed_rolling(speed, 0.0, g.Dwe, g.Dpw, g.alpha))))
        psi = np.zeros(Z)               # roller skews [rad] (stay 0 without friction.skew)
        jac = empty_jacobian(Z)
        if start is not None and not static:
            wc, wR, psi, jac = start[0], start[1].copy(), start[2].copy(), start[3]
        load = raw["Q"].sum(axis=1)
        # the rollers one solution stands for: the classes of the quasi-static solve (sim.solvers.symmetry)
        _, weight, source = symmetry_classes(Z, float(raw["ring_load"][1]), float(raw["ring_load"][2]),
                                             float(np.radians(op.tilt_deg)), raw["roller_loads"])
        # rollers below the kinematic tolerance of the most loaded one cannot move the balances
        active = (load > self.tolerance * load.max()) & (weight > 0.0)
        shape = (Z, 2, n)
        film = FilmState(*(np.zeros(shape) for _ in range(6)), np.zeros(shape + (self.quad.wq.shape[0],)),
                         *(np.zeros(Z) for _ in range(4)))
        case = FrictionCase(frames, bearing, film, par, self.quad)
        mu_ref = max(par.solid.mu_s, par.rheology.c_tau)
        tol_M = self.tolerance * mu_ref * float(load.max()) * bearing.rho_m
        tol_T = self.tolerance * mu_ref * float(load.sum()) * 0.5 * g.Dpw      # at the pitch radius
        # rollers on the outer raceway alone (outside the load zone, sim.solvers.quasi_static): the cage drives
        # them; the rigid solve holds their spin (sim.solvers.kinematics)
        held = active & (raw["Q"][:, 1] == 0.0)
        settings = KinematicsSettings(active, weight, tol_M, tol_T, self.max_iterations, self.traction_kinematics,
                                      self.seed_tolerance_factor, final, held)
        return FrictionProblem(case, settings, wc, wR, psi, wi, jac, start is None or static, static, weight, source,
                               load)

    def evaluate(self, op, raw, start=None, final=True):
        """Kinematics, film and friction of one solved case (raw: BearingModel.solve output).

        ``start``: the ``kinematics`` entry of a previous evaluation of the same case (cage and
        roller speeds [rad/s], roller skews [rad], the kinematic Jacobian, the free rollers' start);
        the film is then taken at those speeds and one Newton solve follows, starting with that
        Jacobian, instead of starting from rolling kinematics (with free rollers: their solve,
        from their earlier solution, at the earlier cage speed). ``final`` False: an iterate of
        :func:`coupled_solution`, whose speeds only start the next pass
        (:data:`sim.solvers.kinematics.KinematicsSettings` ``final``).

        Returns a dict of DATA.md outputs in output units (torque N mm, power W, film um,
        cage speed rpm; with ``friction.skew`` also ``roller_skew`` (Z,) deg and ``skew_sliding``
        N mm), ``friction_converged`` and ``friction_failure`` (why not, or None), the friction
        ``roller_loads`` (Z, 3) [N, N, N mm] and their
        reaction ``ring_loads`` (Z, 3) [N] (:meth:`sim.api.bearing_model.BearingModel.solve`), and
        ``kinematics`` (omega_c [rad/s], omega_R (Z,) [rad/s], psi (Z,) [rad],
        :data:`sim.solvers.kinematics.KinematicJacobian`, and with free rollers their orbit speeds
        (:data:`sim.solvers.kinematics.FreeRollers`), else None).

        At ``op.speed_rpm == 0`` the torque is the zero-speed breakaway torque (BREAKAWAY_NOMINAL_SPEED):
        boundary friction along the slip directions at the onset of motion, power loss 0, cage
        and roller speeds 0, no film; ``start`` is not used.
        """
        g = self.geometry
        pb = self.problem(op, raw, start, final)
        case, settings, wR, psi, wi, static, source, load = (pb.case, pb.settings, pb.wR, pb.psi, pb.wi, pb.static,
                                                              pb.source, pb.load)
        par = case.par
        totals = np.zeros(NEV)
        # cage pocket friction on each roller, force along v', and with skew the lateral raceway
        # tractions, and their reaction on the inner ring (sim.physics.friction.cage_pocket_loads):
        # the friction loads the quasi-static balance takes back (BearingModel.solve(op,
        # roller_loads, ring_loads))
        loads = np.zeros((g.Z, NFL))
        # free rollers (friction.cage_guidance): each loaded roller at its own orbit speed, moving along its
        # pocket and held by the pocket walls beyond the play, its spin changing along the orbit with its
        # inertia (sim.solvers.kinematics, "Spin inertia" and "Pocket play"); the cage speed balances the
        # walls' z-moments. The free solve starts from the rigid cage's solution; a later pass of the load
        # coupling starts from the free solution of the earlier one (``start``'s fifth entry; the rigid solve
        # is skipped: the friction loads it feeds back are 1e-5 of the roller loads).
        warm = (start is not None and len(start) > 4 and start[4] is not None and self.free_rollers
                and self.traction_kinematics and not static)
        if warm:
            wc, converged = pb.wc, True
        else:
            wc, converged = solve_friction(pb.wc, wR, psi, wi, pb.fresh, case, settings, totals, loads, pb.jac)
        # With one roller class (a pure axial load) the rigid balance, Z times the roller's z-moment, is
        # the roller's own and no spin changes along the orbit: the rigid solution stands (solved again to
        # the free rollers' tolerance it moved the torque by up to 1.3e-5, 3 of 25 random pinion designs)
        free = (self.free_rollers and self.traction_kinematics and not static and converged
                and np.count_nonzero(settings.active) > 1)
        free_start = None
        if free:
            # neighbours differ, so every roller is solved on its own: the mirror classes' solution is
            # spread to the rollers it stands for, with their film
            Z = g.Z
            represented = (pb.weight == 0.0) & (load > self.tolerance * load.max())
            full = settings.active | represented
            # N mm s^2; mm; N/mm, both roller ends (as the time domain's, sim.api.dynamic_model); mm
            pocket = (self.roller_spin_inertia, 0.5 * self.pocket_clearance, 2.0 * self.pocket_stiffness,
                      self.pocket_transition, 0.5 * g.Dpw)
            if warm:
                free_start = FreeRollers(start[4].orbit.copy(), start[4].gap.copy(), np.array([wc]), start[4].J.copy(),
                                         start[4].known.copy(), *pocket)
                lubrication_state(wR, free_start.orbit, wi, full, case)
            else:
                wR[:] = wR[source]
                psi[:] = psi[source]
                m = 3 if par.skew else 2
                free_start = FreeRollers(np.full(Z, wc), np.zeros(Z), np.array([wc]), np.zeros((Z, m, m)),
                                         np.zeros(Z, dtype=np.bool_), *pocket)
                lubrication_state(wR, free_start.orbit, wi, represented, case)
            # the rigid solve's Jacobian per roller: its cage-moment rows are weighted by the classes
            jac = pb.jac._replace(**{name: getattr(pb.jac, name)[source] / (pb.weight[source] if name.startswith("dT")
                                                                              else 1.0)
                                     for name in pb.jac._fields[:-1]})
            settings = settings._replace(active=full, weight=np.ones(Z))
            source = np.arange(Z)
            converged = free_roller_speeds(wi, wR, psi, free_start, case, settings, totals, loads, jac)
            wc = float(free_start.wc[0])
        # Gupta's inlet-heating factor is floored at 0 where its pressure term outgrows 1, far beyond its
        # fitted range (thermal loading L of several hundred: FVA 3 below about -30 degC): no film and no
        # rolling loss there is no result, so the case counts as not converged rather than report that torque
        evaluated = settings.active             # the rollers whose film was taken
        film_lost = not static and bool(np.any((case.film.h[evaluated] == 0.0) & (case.bearing.q[evaluated] > 0.0)))
        wR[:] = wR[source]
        psi[:] = psi[source]
        loads[:] = loads[source]
        # N mm/s; with free rollers the sliding power holds their spin-up slip (sim.solvers.kinematics,
        # "Spin inertia": the tractions spin each roller from the speed it arrives with to its own) and the
        # cage power the pocket walls' work on the rollers moving into them ("Pocket play")
        power = totals[EV_P0:EV_P0 + NC]
        srr, film_um, lam = film_outputs(case, load, wc, wR, wi)
        # the torque is power / omega_i where the speeds are imposed: at speed 0 (Coulomb friction, the
        # same at any speed: that of the nominal speed) and with rolling kinematics (2.20), (2.22), whose
        # speeds leave the roller and cage moments unbalanced, so that the outer-ring torque is not the
        # friction torque (TRB 32208, 4.5 / 3 kN, 2000 rpm: -1197 N mm on the outer ring, +776 from the
        # power); with the traction balance, the outer-ring torque, and the breakdown in proportion to
        # each mechanism's power sums to it exactly (it equals power / omega_i up to the kinematic
        # tolerance, module docstring)
        if self.traction_kinematics and not static:
            # with a rigid cage, held rollers (sim.solvers.kinematics) lose spin to their friction moment M
            # at the rate -sum(M omega_R), which the inner ring puts back in the load zone: the torque is
            # the outer ring's plus that rate over the speed (with held rollers, the power loss over the
            # speed); free rollers hold no spin (their spin inertia is solved: the outer ring's torque)
            torque = drive_torque(totals)
            if not free:
                torque -= held_spin_power(settings, wR, psi, wc, wi, case) / wi
            components = torque * power / power.sum()
            skew_sliding = torque * totals[EV_PSKEW] / power.sum()
        else:
            components = power / wi
            skew_sliding = totals[EV_PSKEW] / wi
            torque = float(components.sum())
        if static:
            power_loss = 0.0
            wc = 0.0
            wR[:] = 0.0
        else:
            power_loss = float(power.sum()) * W_PER_N_MM_PER_S
        if film_lost:
            failure = ("no EHL film at a loaded contact: Gupta's inlet-heating factor is 0 there (thermal loading "
                       "far beyond its range: the oil far too viscous for the speed)")
        elif not converged:
            failure = "roller and cage speeds: no traction balance within friction.max_iterations"
        else:
            failure = None
        return {
            "friction_converged": failure is None,
            "friction_failure": failure,
            "torque": torque,
            "torque_component": components,
            "power_loss": power_loss,
            "srr": srr,
            "film_thickness": film_um,
            "lambda_ratio": lam,
            "cage_speed": wc * RPM_PER_RAD_S,
            "roller_loads": loads[:, FL_U:FL_W + 1].copy(),
            "ring_loads": loads[:, FL_RING_R:FL_RING_Z + 1].copy(),
            "kinematics": (wc, wR.copy(), psi.copy(), pb.jac, free_start),
        } | ({"roller_skew": np.degrees(psi), "skew_sliding": float(skew_sliding)} if par.skew else {})


def held_spin_power(settings, wR, psi, wc, wi, case):
    """Rate sum(weight M omega_R) [N mm/s] at which the friction moments M about their axes change
    the spin energy of the held rollers (:data:`sim.solvers.kinematics.KinematicsSettings`
    ``held``) at roller speeds wR, skews psi, cage speed wc and inner-ring speed wi [rad/s]."""
    ev = np.empty(NEV)
    rate = 0.0
    for j in np.flatnonzero(settings.held):
        roller_friction(int(j), float(wR[j]), float(psi[j]), wc, wi, case, ev)
        rate += settings.weight[j] * ev[EV_MU] * wR[j]
    return rate


def drive_torque(totals):
    """The drive's torque [N mm] from the rollers' summed kernel evaluations ``totals`` (NEV,) at a
    traction balance: the outer ring's, plus the inner contacts' moment about the inner ring's own
    axis less theirs about the bearing axis (sim.physics.friction, "Inner ring"; equal where the ring
    is centred and untilted). Times omega_i it is the power the drive puts in, the power loss at the
    balance (module docstring of sim.physics.friction)."""
    return float(totals[EV_TRING] - totals[EV_TZ])     # EV_TOUT cancels: T_out + T_ring - (T_z + T_out)


def inner_ring_poses(Z, ring, tilt):
    """The inner ring's pose in the meridian plane of each roller (Z, NRP), layout RP_* of
    sim.physics.friction (module docstring, "Inner ring"), for the quasi-static solution: ring (delta_a,
    delta_x, delta_y) [mm] (raw["ring"]), imposed tilt [rad] about the y axis; roller j at psi_j =
    2 pi j / Z (sim.solvers.symmetry). Its radial displacement delta_x cos(psi) + delta_y sin(psi) and
    turn tilt cos(psi) there, as the load distribution's contact geometry
    (sim.solvers.quasi_static.solve_bearing); no offset across the plane (e_perp 0: the quasi-static
    solution leaves out its lateral slip, sim.physics.friction, "Inner ring")."""
    psi = 2.0 * np.pi * np.arange(Z) / Z
    poses = np.zeros((Z, NRP))
    poses[:, RP_DR] = ring[1] * np.cos(psi) + ring[2] * np.sin(psi)
    poses[:, RP_DA] = ring[0]
    poses[:, RP_COS] = np.cos(tilt * np.cos(psi))
    poses[:, RP_SIN] = np.sin(tilt * np.cos(psi))
    return poses


def film_outputs(case, load, wc, wR, wi):
    """Slide-to-roll ratio (2.25) [1] and film thickness [um] along the most loaded roller (race,
    slice; NaN where unloaded) and the specific film thickness at its most loaded slices (race,)
    [1], from a FrictionCase with its film at cage speed wc, roller speeds wR (Z,) and inner-ring
    speed wi [rad/s]; ``load`` (Z,): roller loads that pick the most loaded roller."""
    X, Cen, Ax = case.frames.X, case.frames.Cen, case.frames.Ax
    film, q = case.film, case.bearing.q
    n = q.shape[2]
    j = int(np.argmax(load))
    v_roll = np.zeros((2, n))
    v_ring = np.zeros((2, n))
    for s in range(2):
        v_roll[s] = wR[j] * (Ax[j, 1] * (X[j, s, :, 0] - Cen[j, 0]) - Ax[j, 0] * (X[j, s, :, 1] - Cen[j, 1]))
        for k in range(n):     # the ring's surface about its own axis (sim.physics.friction, "Inner ring")
            v_ring[s, k] = ring_surface_speed(wi if s == 1 else 0.0, wc, case.bearing.ring[j], X[j, s, k, 0],
                                              X[j, s, k, 1])
    loaded = film.p0[j] > 0.0
    srr = np.where(loaded, 2.0 * (v_roll - v_ring) / (v_roll + v_ring), np.nan)   # eq. (2.25)
    film_um = np.where(loaded, film.h[j] * UM_PER_MM, np.nan)
    kmax = np.argmax(q[j], axis=1)
    lam = np.array([film.h[j, s, kmax[s]] / case.par.sigma for s in range(2)])
    return srr, film_um, lam


def coupled_solution(model, friction, op):
    """Load distribution and friction of one case with the friction loads fed back: the friction
    loads on the rollers and their reaction on the inner ring (:meth:`FrictionModel.evaluate`:
    ``roller_loads``, ``ring_loads``) enter :meth:`sim.api.bearing_model.BearingModel.solve`, whose
    solution gives the next friction loads g(x) of the applied ones x; iterated until they change
    by less than ``friction.load_coupling_tolerance`` x the largest roller load (the moments over
    Lwe) between passes, at most ``friction.load_coupling_passes`` passes. The next applied loads
    are Anderson-mixed (Anderson 1965, J. ACM 12, 547; Walker & Ni 2011, SIAM J. Numer. Anal. 49,
    1715, their mixing parameter 1) over the last m = ``friction.load_coupling_depth`` differences:
    x' = g_k - dG gamma, gamma = argmin |f_k - dF gamma| (least squares), with f = g(x) - x (moments
    over Lwe) and the columns of dF, dG the differences of successive f and g; depth 1 is the secant
    method, theta = f_k.(f_k - f_(k-1)) / |f_k - f_(k-1)|^2. From the first pass on, whose predecessor
    is the first solve (applied loads x = 0, f = g). Measured: the plain iteration contracts by
    0.07-0.1 per pass on the skewed cases of the tests and by -0.5 (alternating) on a TRB 32208
    under an imposed tilt with skew, which it did not settle in 8 passes; mixing (depth 1) from the
    second pass settled both in 3-4, from the first the combined TRB 32208 and the pinion TSRB in 2
    instead of 3 (bench_skew_cost.py), the tilted TRB 32208 in 4-5 as before. Depth 2 (session 18):
    of 9 random skewed TSRB cases that depth 1 left unsettled after 8 passes (period-2 swings of the
    loads by ~1 %, gain near -1), 4 settle within 8 passes and 5 within 16 (depth 1: 3 within 16;
    depth 3 no better); the cases of the tests settle in the same 2-3 passes. Over 600 random
    skewed cases (7 bearings, loads, speeds 30-8000 rpm, 20-110 degC) 558 converge with depth 1 and
    8 passes, 563 with depth 2, 569 with depth 2 and 16 passes (the defaults).

    Returns (raw, fr): the last solve and the friction evaluation at it, with
    ``fr["coupling_converged"]`` whether the fixed point settled (it may not: a skewed TSRB whose
    skew moment changes sign with the loads its own lateral tractions cause flips its rollers
    between the pocket walls from pass to pass). ``fr`` is None when the first solve did not
    converge or is beyond the static limit (below); ``fr["friction_converged"]`` is False when a
    kinematic solve or a load solve with the friction loads did not converge (a pass's kinematic
    solve starts from the previous pass's speeds and Jacobian and, where that fails, once more from
    rolling kinematics).

    Free rollers (``friction.cage_guidance = free``) at high speed can have more than one periodic
    state of their places in the pockets (which rollers ride on a wall), and a pass's free solve
    starts from the previous pass's places: it may step from one such state to the next from pass to
    pass, so that the friction loads drift and the coupling does not settle (pinion_alpha at 35.4 /
    3.1 kN, 7140 rpm: the torque walked from 5885 to 5921 N mm over 16 passes; the same raw
    evaluated cold, warm from that and warm from the last pass gave 5880.8, 5889.9 and 5921.8 N mm).
    Where the warm passes do not settle, the coupling is run once more with every pass's kinematics
    from rolling kinematics and the rigid cage's solution (``warm`` False): a map of the applied
    loads alone, which settles there in 2 passes (5880.8 N mm). It is not run for a rigid cage, whose
    passes carry only speeds and a Jacobian between them, whose solve has one solution.

    Both runs start from the first solve (without friction loads). Where that one did not converge,
    or its contact is already beyond the static limit (:meth:`BearingModel.static_limit`; the
    friction loads move pmax by ~1e-5), no friction is computed: (that solve, None).
    """
    raw = model.solve(op)
    if not raw["converged"] or model.static_limit(raw)[1] is not None:
        return raw, None
    # With skew the friction loads of this first evaluation change the load distribution by
    # 2e-4 - 1e-3 of the roller loads (conf/friction/default.yaml, load_coupling_tolerance), so at
    # least one further pass follows, whose film is taken at these speeds: its kinematics need only
    # seed them (FrictionModel.evaluate, final). Without skew (loads ~1e-5 of the roller loads,
    # changing by < 4e-8) it is solved as before, bit for bit.
    fr = friction.evaluate(op, raw, final=not friction.par.skew)
    solution = _coupled(model, friction, op, raw, fr, warm=True)
    if solution[1]["friction_converged"] and not solution[1]["coupling_converged"] and friction.free_rollers:
        solution = _coupled(model, friction, op, raw, fr, warm=False)
    return solution


def _coupled(model, friction, op, raw, fr, warm):
    """:func:`coupled_solution`'s passes from its first solve ``raw`` (converged) and the friction
    evaluated there, ``fr`` (from rolling kinematics); ``warm``: each later pass's kinematics start
    from the previous pass's (else from rolling kinematics)."""
    scale = np.ones(NFL)
    scale[FL_W] = 1.0 / model.geometry.Lwe          # moments [N mm] over Lwe: forces [N]

    def loads(res):
        # all of them: the tangential tractions on the inner ring add up along y over the load zone, so
        # a load case with friction is not mirror-symmetric about the x-z plane; the ring's lateral
        # displacement balances them (sim.solvers.quasi_static.solve_bearing, every roller solved).
        # With skew, their mirror-symmetric part without the tangential ring loads (no lateral load, as
        # until session 26): fed as they are, the skewed rollers' flips between their pocket walls kept
        # the reference TSRB at 1.13 / 1.61 kN, 7128 rpm (tests/balance/test_equilibrium.py, Anderson
        # depth two) from settling in 32 passes (session 27; with skew, mirror images' friction loads differ
        # by ~3e-6 of the lateral tractions, session 25)
        x = np.hstack([res["roller_loads"], res["ring_loads"]])
        if not friction.par.skew:
            return x
        x = mirror_mean(x)
        x[:, FL_RING_T] = 0.0
        return x

    x = loads(fr)               # the next applied loads (Z, NFL)
    # (g, f) of the passes so far, newest last: the first solve is the pass with applied loads 0, g = x
    history = [(x, x * scale)]
    if not fr["friction_converged"]:
        return raw, fr | {"coupling_converged": False}
    for _ in range(friction.load_coupling_passes):
        raw = model.solve(op, roller_loads=x[:, FL_U:FL_W + 1], ring_loads=x[:, FL_RING_R:FL_RING_Z + 1], start=raw)
        if not raw["converged"]:
            return raw, fr | {"friction_converged": False, "coupling_converged": False}
        fr = friction.evaluate(op, raw, start=fr["kinematics"] if warm else None)
        if warm and not fr["friction_converged"]:
            # the previous pass's speeds and Jacobian are only a start: a Newton solve from them can
            # fail where one from rolling kinematics converges (prototype TSRB, Fa 1.5 kN, Fr 2 kN, 40
            # slices: the second pass, a load change of 4e-4 N, failed warm and converged cold)
            fr = friction.evaluate(op, raw)
        if not fr["friction_converged"]:
            return raw, fr | {"coupling_converged": False}
        g = loads(fr)
        f = (g - x) * scale
        if np.abs(f).max() <= friction.load_coupling_tolerance * raw["Q"].max():
            return raw, fr | {"coupling_converged": True}
        history = (history + [(g, f)])[-(friction.load_coupling_depth + 1):]
        x = anderson_mix(history)
    return raw, fr | {"coupling_converged": False}


def anderson_mix(history):
    """The next iterate of Anderson mixing (:func:`coupled_solution`) from ``history``, the (g, f)
    pairs of the last passes, oldest first (g the map's values, f the scaled residuals; arrays of one
    shape): g_k - dG gamma with gamma the least-squares solution of dF gamma = f_k; g_k alone from a
    history of one pass, or where the differences vanish."""
    g, f = history[-1]
    if len(history) < 2:
        return g
    dG, dF = (np.diff(np.stack([h[i].ravel() for h in history], axis=1), axis=1) for i in (0, 1))
    if not np.any(dF):
        return g
    gamma = np.linalg.lstsq(dF, f.ravel(), rcond=None)[0]
    return g - (dG @ gamma).reshape(g.shape)

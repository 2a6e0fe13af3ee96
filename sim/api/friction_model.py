"""Friction parameters of one bearing, lubricant and friction config, and the evaluation of a
solved case: film, kinematics from the traction balance, torque and its breakdown
(MODEL.md 5, thesis 5.4; the kernels are in :mod:`sim.physics.friction` and
:mod:`sim.solvers.kinematics`).
"""
import numpy as np

from sim.errors import InputError, check_range
from sim.physics.ehl import FILM_FORMULAS, PRESSURE_VISCOSITY_MODELS, roelands_index
from sim.physics.friction import (EV_FT, EV_P0, EV_TOUT, NC, NEV, NPAR, PAR_ALPHA, PAR_B, PAR_B_RIB, PAR_BETA,
                                  PAR_C, PAR_C_RIB, PAR_CTAU, PAR_DRAG_K, PAR_DT_TOL, PAR_EPRIME, PAR_ETA0, PAR_FILM,
                                  PAR_G, PAR_HYST, PAR_K_OIL, PAR_K_STEEL, PAR_KAPPA_STEEL, PAR_MU_CAGE, PAR_MU_S,
                                  PAR_PV_MODEL, PAR_RHO_M, PAR_SIGMA, PAR_SIGMA_RIB, PAR_TAU0, PAR_THERMAL, PAR_V_S,
                                  PAR_Z, lubrication_state, roller_friction)
from sim.physics.kinematics import angular_speed, cage_speed_rolling, roller_speed_rolling
from sim.physics.roller_contact import contact_frames, empty_frames
from sim.solvers.kinematics import solve_kinematics, solve_kinematics_newton


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
    """

    def __init__(self, geometry, E_star, lubricant, friction, surface, material):
        g = self.geometry = geometry
        self.E_star = E_star
        self.lubricant = lubricant
        film = str(friction["film_thickness"])
        if film not in FILM_FORMULAS:
            raise InputError(f"friction.film_thickness = {film!r} is not one of {sorted(FILM_FORMULAS)}")
        kin = str(friction["kinematics"])
        if kin not in ("traction", "rolling"):
            raise InputError(f"friction.kinematics = {kin!r} is not one of ['rolling', 'traction']")
        self.traction_kinematics = kin == "traction"
        npts = friction["width_points"]
        if not (isinstance(npts, (int, np.integer)) and 2 <= int(npts) <= 64):
            raise InputError(f"friction.width_points = {npts!r} is outside the allowed range [2, 64] (integer)")
        t, wt = np.polynomial.legendre.leggauss(int(npts))
        self.tq = 0.25 * np.pi * (t + 1.0)          # nodes on (0, pi/2)
        self.wq = 0.25 * np.pi * wt
        self.tolerance = check_range("friction.tolerance", friction["tolerance"], 1e-14, 1e-2, low_open=True)
        self.max_iterations = int(check_range("friction.max_iterations", friction["max_iterations"], 1, 10000))
        self.seed_tolerance_factor = check_range("friction.seed_tolerance_factor", friction["seed_tolerance_factor"],
                                                  1.0, 1e4)
        drag = friction["drag"]
        model = str(drag["model"])
        if model not in ("none", "roller_drag"):
            raise InputError(f"friction.drag.model = {model!r} is not one of ['none', 'roller_drag']")
        par = np.zeros(NPAR)
        par[PAR_ALPHA] = lubricant.pressure_viscosity
        par[PAR_PV_MODEL] = PRESSURE_VISCOSITY_MODELS[lubricant.pressure_viscosity_model]
        par[PAR_TAU0] = lubricant.limiting_shear_stress_0
        par[PAR_CTAU] = lubricant.limiting_shear_coefficient
        par[PAR_G] = lubricant.shear_modulus
        par[PAR_MU_S] = check_range("friction.solid_friction_coefficient", friction["solid_friction_coefficient"], 0.0, 1.0)
        par[PAR_V_S] = 1e3 * check_range("friction.solid_slip_velocity", friction["solid_slip_velocity"], 0.0, 1.0, low_open=True)
        par[PAR_HYST] = check_range("friction.hysteresis_loss_factor", friction["hysteresis_loss_factor"], 0.0, 0.5)
        par[PAR_MU_CAGE] = check_range("friction.cage_friction_coefficient", friction["cage_friction_coefficient"], 0.0, 1.0)
        sigma = 1e-3 * check_range("bearing.surface.sigma", surface["sigma"], 0.0, 10.0, low_open=True)
        par[PAR_SIGMA] = sigma
        par[PAR_B] = check_range("bearing.surface.B_ZH", surface["B_ZH"], 0.0, 20.0, low_open=True)
        par[PAR_C] = check_range("bearing.surface.C_ZH", surface["C_ZH"], 0.0, 5.0, low_open=True)
        if g.type == "TRB":
            for key in ("sigma_rib", "B_ZH_rib", "C_ZH_rib"):
                if key not in surface:
                    raise InputError(f"bearing.surface.{key} is missing (roller-end / rib mixed friction of a TRB)")
            par[PAR_SIGMA_RIB] = 1e-3 * check_range("bearing.surface.sigma_rib", surface["sigma_rib"], 0.0, 10.0, low_open=True)
            par[PAR_B_RIB] = check_range("bearing.surface.B_ZH_rib", surface["B_ZH_rib"], 0.0, 20.0, low_open=True)
            par[PAR_C_RIB] = check_range("bearing.surface.C_ZH_rib", surface["C_ZH_rib"], 0.0, 5.0, low_open=True)
        par[PAR_THERMAL] = 1.0 if bool(friction["thermal"]) else 0.0
        par[PAR_K_OIL] = lubricant.thermal_conductivity
        if friction["thermal"]:
            for key in ("thermal_conductivity", "specific_heat"):
                if key not in material:
                    raise InputError(f"material.{key} is missing (flash temperature of friction.thermal)")
            k_s = check_range("material.thermal_conductivity", material["thermal_conductivity"], 1.0, 500.0)
            c_s = check_range("material.specific_heat", material["specific_heat"], 100.0, 5000.0)
            par[PAR_K_STEEL] = k_s
            par[PAR_KAPPA_STEEL] = 1e6 * k_s / (float(material["density"]) * c_s)     # mm^2/s
        par[PAR_DT_TOL] = check_range("friction.temperature_tolerance", friction["temperature_tolerance"], 0.0, 10.0,
                                       low_open=True)
        par[PAR_EPRIME] = 2.0 * E_star
        par[PAR_FILM] = FILM_FORMULAS[film]
        par[PAR_RHO_M] = 0.5 * g.Dwe
        self.drag_factor = 0.0
        if model == "roller_drag":
            cd = check_range("friction.drag.drag_coefficient", drag["drag_coefficient"], 0.0, 10.0)
            X = check_range("friction.drag.oil_volume_fraction", drag["oil_volume_fraction"], 0.0, 1.0)
            # F_D = 1/2 rho X C_D Dwe Lwe (omega_c Dpw/2)^2; rho [t/mm^3] = 1e-12 rho [kg/m^3]
            self.drag_factor = 0.5 * X * cd * g.Dwe * g.Lwe * (0.5 * g.Dpw) ** 2 * 1e-12
        self.drag_model = model
        self.par = par

    def evaluate(self, op, raw, start=None):
        """Kinematics, film and friction of one solved case (raw: BearingModel.solve output).

        ``start``: the ``kinematics`` entry of a previous evaluation of the same case (cage and
        roller speeds [rad/s]); the film is then taken at those speeds and one Newton solve
        follows, instead of starting from rolling kinematics.

        Returns a dict of DATA.md outputs in output units (torque N mm, power W, film um,
        cage speed rpm), ``friction_converged``, the cage pocket ``roller_loads`` (Z, 3) [N]
        and ``kinematics`` (omega_c, omega_R (Z,)) [rad/s].
        """
        g = self.geometry
        a = g.arrays
        Z, n = g.Z, g.n_slices
        par = self.par.copy()
        eta0 = self.lubricant.dynamic_viscosity(op.oil_temperature) * 1e-6      # MPa s
        par[PAR_ETA0] = eta0
        par[PAR_BETA] = float(self.lubricant.temperature_viscosity_coefficient(op.oil_temperature))
        par[PAR_Z] = roelands_index(eta0, par[PAR_ALPHA])
        par[PAR_DRAG_K] = self.drag_factor * float(self.lubricant.density(op.oil_temperature))
        X, Nrm, Cen, Ax, Xrib = empty_frames(Z, n)
        contact_frames(raw["poses"], raw["ring"], np.radians(op.tilt), g.alpha, g.Dpw, a["x"], a["rho"],
                       a["race_kind"], a["race_par"], a["rib"], X, Nrm, Cen, Ax, Xrib)
        q = raw["line_load"]
        Qrib = raw["Q_rib"]
        wi = float(angular_speed(op.speed))
        wc = float(angular_speed(cage_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha)))
        wR = np.full(Z, float(angular_speed(roller_speed_rolling(op.speed, 0.0, g.Dwe, g.Dpw, g.alpha))))
        if start is not None:
            wc, wR = start[0], start[1].copy()
        load = raw["Q"].sum(axis=1)
        # symmetry: pure axial untilted, every roller alike; untilted, roller j mirrors roller Z - j
        symmetric = op.Fr == 0.0 and op.tilt == 0.0
        mirrored = op.tilt == 0.0
        # rollers below the kinematic tolerance of the most loaded one cannot move the balances
        active = load > self.tolerance * load.max()
        weight = np.ones(Z)
        if symmetric:
            active[1:] = False
            weight[0] = Z
        elif mirrored:
            active[Z // 2 + 1:] = False
            weight[1:(Z + 1) // 2] = 2.0
        shape = (Z, 2, n)
        h, Phi, Fh, Fy, p0, b = (np.zeros(shape) for _ in range(6))
        Eta = np.zeros(shape + (self.tq.shape[0],))
        hrib, Phirib, prib, Etarib = np.zeros(Z), np.zeros(Z), np.zeros(Z), np.zeros(Z)
        totals = np.zeros(NEV)
        ev = np.zeros(NEV)
        mu_ref = max(par[PAR_MU_S], par[PAR_CTAU])
        tol_M = self.tolerance * mu_ref * float(load.max()) * par[PAR_RHO_M]
        tol_T = self.tolerance * mu_ref * float(load.sum()) * 0.5 * g.Dpw
        converged = True
        # film from the speeds of the previous pass: rolling kinematics, then the traction solution
        passes = 2 if self.traction_kinematics and start is None else 1
        for film_pass in range(passes):
            lubrication_state(wR, wc, wi, active, q, Qrib, X, Nrm, Cen, Ax, Xrib, a["R_eq"], g.slice_width, self.E_star,
                              a["rib"], par, self.tq, self.wq, h, Phi, Fh, Fy, p0, b, hrib, Phirib, prib, Eta, Etarib)
            if self.traction_kinematics:
                # a pass followed by another only sets the film of the next: looser tolerance
                loose = self.seed_tolerance_factor if film_pass < passes - 1 else 1.0
                args = (wi, wR, active, weight, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, a["R_eq"],
                        g.slice_width, prib, hrib, Phirib, Eta, Etarib, par, self.tq, self.wq, loose * tol_M,
                        loose * tol_T, self.max_iterations, totals)
                start_c, start_R = wc, wR.copy()
                wc, converged = solve_kinematics_newton(wc, film_pass == 0 and start is None, *args)
                if not converged:   # bracketing is slower but cannot leave the bracket
                    wR[:] = start_R
                    wc, converged = solve_kinematics(start_c, *args)
        if not self.traction_kinematics:
            for j in np.flatnonzero(active):
                roller_friction(j, wR[j], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, a["R_eq"],
                                g.slice_width, prib, hrib, Phirib, Eta, Etarib, par, self.tq, self.wq, ev)
                totals += weight[j] * ev
        # cage pocket friction on each roller, force along v' (module docstring): the friction
        # load the quasi-static balance takes back (BearingModel.solve(op, roller_loads))
        roller_loads = np.zeros((Z, 3))
        for jj in np.flatnonzero(active):
            roller_friction(jj, wR[jj], wc, wi, X, Nrm, Cen, Ax, Xrib, Qrib, p0, b, h, Phi, Fh, Fy, a["R_eq"],
                            g.slice_width, prib, hrib, Phirib, Eta, Etarib, par, self.tq, self.wq, ev)
            F_cage = par[PAR_DRAG_K] * wc * wc - ev[EV_FT]
            roller_loads[jj, 1] = par[PAR_MU_CAGE] * F_cage * np.sign(wR[jj])
        if symmetric:
            wR[:] = wR[0]
            roller_loads[:] = roller_loads[0]
        elif mirrored:
            wR[Z // 2 + 1:] = wR[1:(Z + 1) // 2][::-1]
            roller_loads[Z // 2 + 1:] = roller_loads[1:(Z + 1) // 2][::-1]
        power = totals[EV_P0:EV_P0 + NC]                       # N mm/s
        j = int(np.argmax(load))
        v_roll = np.zeros((2, n))
        v_ring = np.zeros((2, n))
        for s in range(2):
            Om = -wc if s == 0 else wi - wc
            v_roll[s] = wR[j] * (Ax[j, 1] * (X[j, s, :, 0] - Cen[j, 0]) - Ax[j, 0] * (X[j, s, :, 1] - Cen[j, 1]))
            v_ring[s] = Om * X[j, s, :, 0]
        loaded = p0[j] > 0.0
        srr = np.where(loaded, 2.0 * (v_roll - v_ring) / (v_roll + v_ring), np.nan)   # eq. (2.25)
        film = np.where(loaded, h[j] * 1e3, np.nan)                                   # um
        kmax = np.argmax(q[j], axis=1)
        lam = np.array([h[j, s, kmax[s]] / par[PAR_SIGMA] for s in range(2)])
        return {
            "friction_converged": bool(converged),
            "torque": float(totals[EV_TOUT]),
            # breakdown in proportion to each mechanism's power: sums to the outer-ring torque exactly
            # (which itself equals power / omega_i up to the kinematic tolerance, module docstring)
            "torque_component": totals[EV_TOUT] * power / power.sum(),
            "power_loss": float(power.sum()) * 1e-3,
            "srr": srr,
            "film_thickness": film,
            "lambda_ratio": lam,
            "cage_speed": wc * 30.0 / np.pi,
            "roller_loads": roller_loads,
            "kinematics": (wc, wR.copy()),
        }

"""Free rollers along the orbit, their spin inertia and their pocket play: the quasi-static solver
against an independent solution of its equations and against the time domain (session 23's
experiment, in the solver since session 24; the pocket play since session 25).

The quasi-static free rollers (sim.solvers.kinematics, "Spin inertia" and "Pocket play") carry each
roller's spin and its place in its cage pocket along the orbit: over the Z roller azimuths of the
steady state (roller j at 2 pi j / Z, arriving from j - 1 after dt = 2 pi / (Z omega_c)) backward
Euler on I_x d omega / dt = M and on the place g along the pocket,

    M_j(omega_j) = c (omega_j - omega_j-1),   c = I_x omega_c Z / (2 pi)            [N mm]
    g_j = g_j-1 + r_p (Omega_j - omega_c) dt,  T_z,j + r_p P(g_j) = 0              [mm, N mm]

(I_x the roller's moment of inertia about its axis, Omega_j its orbit speed, T_z,j the z-moment of
its contacts about the bearing axis, P the pocket walls' spring, r_p the pitch radius), and the
cage's balance sum_j T_z,j = 0, the places periodic over the lap. Summed over the closed orbit,
sum_j M_j omega_j = c/2 sum_j (omega_j - omega_j-1)^2 is the spin energy the tractions put in per
unit time (dissipated as slip where a roller is spun up again), and sum_j T_z,j (Omega_j - omega_c)
the walls' work on the rollers' motion along their pockets. The torque is the contacts' power at
the solved speeds plus both terms, over the inner-ring speed; the outer ring's reaction torque is
printed beside it as a check of the balance.

This script solves the same equations on its own, on the solver's load distribution without the
friction loads fed back (sim.api.friction_model.FrictionModel.evaluate): the Z spins, the Z orbit
speeds, the cage speed and the first roller's place at once (scipy.optimize.root, Levenberg-
Marquardt: without a wall contact the places' common offset is free), from the solver's solution
(from the rigid cage's speeds, friction.cage_guidance = rigid, the walls' kinks left it far from a
solution in the fast TRB case: so this checks that the solver's speeds, places and cage speed solve
the equations as written here, all at once, and stay there through the film passes), with
the film of every loaded roller (sim.physics.friction.lubrication_state) recomputed at the spins
and orbit speeds of the previous pass until they no longer change. The solver sweeps the rollers
one by one along the orbit instead and moves the cage speed between sweeps
(sim.solvers.kinematics.free_roller_speeds). Each case is run by the time-domain solver too
(steady state from rolling kinematics). Writes orbit_inertia.md beside this file.

    python docs/figures/orbit_inertia.py            # about 20 min on one core, most of it the dynamic runs
"""
import pathlib
import sys

import numpy as np
from scipy.optimize import root

REPO = pathlib.Path(__file__).resolve().parents[2]
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))  # run from a checkout: this sim/, not an installed one

import sim  # noqa: E402
from sim.api import dynamic_model  # noqa: E402
from sim.api.cases import operating_points  # noqa: E402
from sim.api.simulation import build_models, resolved  # noqa: E402
from sim.physics.friction import (EV_MU, EV_P0, EV_TOUT, EV_TZ, NC, NEV, lubrication_state,  # noqa: E402
                                  pocket_wall_force, roller_friction)

OUT = pathlib.Path(__file__).with_suffix(".md")
FILM_PASSES = 20          # film passes at most
FILM_TOLERANCE = 1e-6     # relative change of the spins between passes that ends them
RESIDUAL_TOLERANCE = 1e-3  # N mm, on every moment balance: 1e-5 of a light roller's friction moment here
CASES = {   # the cases of session 23's comparisons (README, dynamic solver)
    "TRB 32208 3 / 8 kN, 6000 rpm": ["bearing=trb_32208", "load.Fa=3000", "load.Fr=8000", "load.speed=6000"],
    "TRB 31313 21.2 / 22.0 kN, 3390 rpm, 45 degC": ["bearing=trb_31313", "load.Fa=21230", "load.Fr=21970",
                                                    "load.speed=3390", "load.oil_temperature=45"],
    "TRB 31313 32.1 / 48.0 kN, 3821 rpm, 47 degC": ["bearing=trb_31313", "load.Fa=32100", "load.Fr=48000",
                                                    "load.speed=3821", "load.oil_temperature=47"],
    "TRB 31313 31.6 / 40.5 kN, 800 rpm, 39 degC": ["bearing=trb_31313", "load.Fa=31600", "load.Fr=40460",
                                                   "load.speed=800", "load.oil_temperature=39"],
    "prototype TSRB 1.5 / 2 kN, 2000 rpm, 40 slices": ["bearing=tsrb_prototype", "load.Fa=1500", "load.Fr=2000",
                                                       "load.speed=2000", "solver.n_slices=40"],
    "pinion_alpha TSRB 11.4 / 14.4 kN, 1660 rpm, 86 degC": ["bearing=tsrb_pinion_alpha", "lubricant=pinion_oil",
                                                           "load.Fa=11410", "load.Fr=14380", "load.speed=1660",
                                                           "load.oil_temperature=86"],
    "pinion_alpha TSRB 7.16 / 6.41 kN, 3910 rpm, 52 degC": ["bearing=tsrb_pinion_alpha", "lubricant=pinion_oil",
                                                           "load.Fa=7160", "load.Fr=6410", "load.speed=3910",
                                                           "load.oil_temperature=52"],
}


def orbit_experiment(overrides):
    """(the solver's torque without the friction loads fed back, this script's torque, its
    outer-ring torque, the rigid cage's spins, this script's spins, the rollers on pocket walls in
    this script's solution and in the solver's) [N mm, N mm, N mm, rad/s, rad/s, 1, 1] of one case
    (module docstring)."""
    cfg = sim.load_config(overrides)
    plain = resolved(cfg)
    model, friction = build_models(cfg, plain)
    op = operating_points(plain["load"])[0]
    raw = model.solve(op)
    res = friction.evaluate(op, raw)
    rigid_cfg = sim.load_config(overrides + ["friction.cage_guidance=rigid"])
    _, rigid = build_models(rigid_cfg, resolved(rigid_cfg))
    wc0, wR, _, _, _ = rigid.evaluate(op, raw)["kinematics"]
    wi = np.pi * op.speed_rpm / 30.0
    case = friction.problem(op, raw).case
    Z = wR.shape[0]
    loaded = raw["Q"].sum(axis=1) + raw["Q_rib"] > 0.0
    lubrication_state(wR.copy(), np.full(Z, wc0), wi, loaded, case)
    dyn = resolved(sim.load_config(overrides + ["solver=dynamic"]))["solver"]["dynamic"]
    body = dynamic_model.prepare(model, friction, op, dyn).problem.body
    Ix, rp, h, k, d_s = body.Ix, body.r_pocket, body.half_play, body.k_pocket, body.pocket_transition
    ev = np.zeros(NEV)

    def evaluate(w, orbit):
        M, P, T, C = np.zeros(Z), np.zeros(Z), np.zeros(Z), np.zeros(Z)
        for j in np.flatnonzero(loaded):
            roller_friction(int(j), float(w[j]), 0.0, float(orbit[j]), wi, case, ev)
            M[j], P[j], T[j], C[j] = ev[EV_MU], ev[EV_P0:EV_P0 + NC].sum(), ev[EV_TOUT], ev[EV_TZ]
        return M, P, T, C

    def places(orbit, wc, g0):
        """The rollers' places along their pockets from roller 0's, g0, and the place roller 0 arrives
        with after the lap [mm]; a roller that carries nothing orbits with the cage within the play."""
        dt = 2.0 * np.pi / (Z * wc)
        g = np.empty(Z)
        prev = g0
        for j in list(range(1, Z)) + [0]:
            g[j] = prev + rp * (orbit[j] - wc) * dt if loaded[j] else min(h, max(-h, prev))
            prev = g[j]
        return g, g0

    def residual(x):
        w, orbit, wc, g0 = x[:Z], x[Z:2 * Z], x[2 * Z], x[2 * Z + 1]
        M, _, _, C = evaluate(w, orbit)
        g, _ = places(orbit, wc, g0)
        wall = np.array([rp * pocket_wall_force(gj, h, k, d_s)[0] for gj in g])
        r = np.empty(2 * Z + 2)
        r[:Z] = np.where(loaded, M - Ix * wc * Z / (2.0 * np.pi) * (w - np.roll(w, 1)), w - np.roll(w, 1))
        r[Z:2 * Z] = np.where(loaded, C + wall, orbit - wc)
        r[2 * Z] = C[loaded].sum()                       # the cage
        r[2 * Z + 1] = (g[0] - g0) / h                   # the lap closes
        return r

    # film passes: the film (thermal viscosity, entrainment) at the spins and orbit speeds of the previous
    # pass, as the quasi-static kinematics iterate it (sim.solvers.kinematics)
    free = res["kinematics"][4]
    x = np.concatenate([res["kinematics"][1], free.orbit, [free.wc[0], free.gap[0]]])
    lubrication_state(x[:Z].copy(), x[Z:2 * Z].copy(), wi, loaded, case)
    for _ in range(FILM_PASSES):
        sol = root(residual, x, method="lm", options={"xtol": 1e-14, "ftol": 1e-14, "maxiter": 40000})
        # Levenberg-Marquardt may stop at its call limit near a solution (the walls' kinks; without a wall the
        # places' offset is free): accepted where every moment balance holds to RESIDUAL_TOLERANCE
        worst = np.abs(residual(sol.x)[:2 * Z + 1]).max()
        if worst > RESIDUAL_TOLERANCE:      # reported as not solved (the table's last column), not dropped
            return float(res["torque"]), np.nan, np.nan, wR.copy(), np.full(Z, np.nan), -1, \
                int((np.abs(free.gap) > h).sum()), f"not solved: {sol.message} (moment residual {worst:.1e} N mm)"
        change = np.abs(sol.x[:2 * Z + 1] - x[:2 * Z + 1]).max() / np.abs(sol.x[:2 * Z + 1]).max()
        x = sol.x
        lubrication_state(x[:Z].copy(), x[Z:2 * Z].copy(), wi, loaded, case)
        if change < FILM_TOLERANCE:
            break
    w, orbit, wc, g0 = x[:Z], x[Z:2 * Z], x[2 * Z], x[2 * Z + 1]
    _, P, T, C = evaluate(w, orbit)
    c = Ix * wc * Z / (2.0 * np.pi)
    spin_up = 0.5 * c * float(((w - np.roll(w, 1)) ** 2).sum())
    walls = float(C[loaded] @ (orbit - wc)[loaded])
    on_walls = int((np.abs(places(orbit, wc, g0)[0]) > h).sum())
    solver_walls = int((np.abs(res["kinematics"][4].gap) > h).sum())
    return float(res["torque"]), (P.sum() + spin_up + walls) / wi, float(T.sum()), wR.copy(), w, on_walls, \
        solver_walls, "solved"


def main():
    rows = []
    for name, overrides in CASES.items():
        solver, exp, t_out, w_rigid, w_exp, walls, solver_walls, status = orbit_experiment(overrides)
        default = float(sim.simulate(sim.load_config(overrides)).isel(design=0, case=0).torque)
        d = sim.simulate(sim.load_config(overrides + ["solver=dynamic"])).isel(design=0, case=0)
        dyn = float(d.torque)
        spin = d.roller_speed_t.values * np.pi / 30.0
        dyn_cfg = resolved(sim.load_config(overrides + ["solver=dynamic"]))["solver"]["dynamic"]
        samples = int(dyn_cfg["samples_per_window"])
        last = spin[-samples:]          # the last window
        rows.append((name, default, solver, exp, t_out, dyn, bool(d.converged), w_rigid.min() / w_rigid.max(),
                     w_exp.min() / w_exp.max(), last.min() / last.max(), walls, solver_walls, status))
        print(rows[-1], flush=True)
    lines = ["# Free rollers along the orbit (spin inertia, pocket play): the solver, an independent solution and the "
             "time domain", "",
             "Generated by `python docs/figures/orbit_inertia.py` (method in its docstring). Torques in N mm.",
             "Solver: the quasi-static default (`sim.simulate`, friction loads fed back), and its friction",
             "evaluation without that feedback, on which the independent solution runs. Time domain: steady state",
             "from rolling kinematics. Spin ratio: slowest over fastest roller (time domain: over the last window's",
             "samples); the rigid cage balances each roller at its azimuth, as the free rollers did before session 24.",
             "Rollers on walls: beyond the pocket play at the end of their slot (independent / solver).",
             "",
             "| case | solver | solver without feedback | independent | its outer-ring torque | time domain "
             "| solver vs time domain | independent vs solver without feedback | spin ratio rigid cage / independent "
             "/ time domain | rollers on walls | independent solution |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, default, solver, exp, t_out, dyn, steady, r_rigid, r_exp, r_dyn, walls, solver_walls, status in rows:
        lines.append(f"| {name} | {default:.1f} | {solver:.1f} | {exp:.1f} | {t_out:.1f} | "
                     f"{dyn:.1f}{'' if steady else ' (not steady)'} | {default / dyn - 1:+.2%} | "
                     f"{exp / solver - 1:+.1e} | {r_rigid:.3f} / {r_exp:.3f} / {r_dyn:.3f} | {walls} / {solver_walls} | "
                     f"{status} |")
    OUT.write_text("\n".join(lines) + "\n")
    print(OUT.read_text())


if __name__ == "__main__":
    main()

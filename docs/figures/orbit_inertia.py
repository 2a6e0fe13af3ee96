"""Roller spin inertia along the orbit: the quasi-static solver against an independent solution of
its equations and against the time domain (session 23's experiment, in the solver since session 24).

The quasi-static free rollers (sim.solvers.kinematics, "Spin inertia") carry each roller's spin
along the orbit: over the Z roller azimuths of the steady state (roller j at 2 pi j / Z, arriving
from j - 1) the backward-Euler form of I_x d omega / dt = M(psi, omega) with dpsi / dt = omega_c,

    M_j(omega_j) = c (omega_j - omega_j-1),   c = I_x omega_c Z / (2 pi)            [N mm]

(I_x the roller's moment of inertia about its axis). Summed with weights omega_j over the closed
orbit, sum_j M_j omega_j = c/2 sum_j (omega_j - omega_j-1)^2: the spin energy the tractions put in
per unit time, which the contacts dissipate as slip where a roller is spun up again (1/2 I_x dw^2
per pass). The torque is the contacts' power at the solved speeds plus that term, over the
inner-ring speed; the outer ring's reaction torque is printed beside it as a check of the balance.

This script solves the same equations on its own, on the solver's load distribution without the
friction loads fed back (sim.api.friction_model.FrictionModel.evaluate) and with its cage speed:
the Z spins and each loaded roller's own orbit speed at once (scipy.optimize.root), from the
rigid cage's speeds (friction.cage_guidance = rigid: each roller balanced at its azimuth, no
inertia), with the film of every loaded roller (sim.physics.friction.lubrication_state)
recomputed at the spins of the previous pass until they no longer change. The solver sweeps the
rollers one by one along the orbit instead (sim.solvers.kinematics.free_roller_speeds). Each case
is run by the time-domain solver too (steady state from rolling kinematics). Writes
orbit_inertia.md beside this file.

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
from sim.physics.friction import EV_MU, EV_P0, EV_TOUT, EV_TZ, NC, NEV, lubrication_state, roller_friction  # noqa: E402

OUT = pathlib.Path(__file__).with_suffix(".md")
FILM_PASSES = 20          # film passes at most
FILM_TOLERANCE = 1e-6     # relative change of the spins between passes that ends them
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
}


def orbit_experiment(overrides):
    """(the solver's torque without the friction loads fed back, this script's torque, its
    outer-ring torque, the rigid cage's spins, this script's spins) [N mm, N mm, N mm, rad/s,
    rad/s] of one case (module docstring)."""
    cfg = sim.load_config(overrides)
    plain = resolved(cfg)
    model, friction = build_models(cfg, plain)
    op = operating_points(plain["load"])[0]
    raw = model.solve(op)
    res = friction.evaluate(op, raw)
    rigid_cfg = sim.load_config(overrides + ["friction.cage_guidance=rigid"])
    _, rigid = build_models(rigid_cfg, resolved(rigid_cfg))
    _, wR, _, _, _ = rigid.evaluate(op, raw)["kinematics"]
    wc = res["kinematics"][0]
    wi = np.pi * op.speed_rpm / 30.0
    case = friction.problem(op, raw).case
    Z = wR.shape[0]
    loaded = raw["Q"].sum(axis=1) + raw["Q_rib"] > 0.0
    lubrication_state(wR.copy(), wc, wi, loaded, case)
    dyn = resolved(sim.load_config(overrides + ["solver=dynamic"]))["solver"]["dynamic"]
    Ix = dynamic_model.prepare(model, friction, op, dyn).problem.body.Ix
    ev = np.zeros(NEV)
    held = loaded & (raw["Q"][:, 1] == 0.0)       # on the outer raceway alone: the cage drives their orbit
    pushers = loaded & ~held
    share = np.where(pushers, case.bearing.q.sum(axis=(1, 2)), 0.0)
    share /= share.sum()

    def evaluate(w, orbit):
        M, P, T, C = np.zeros(Z), np.zeros(Z), np.zeros(Z), np.zeros(Z)
        for j in np.flatnonzero(loaded):
            roller_friction(int(j), float(w[j]), 0.0, float(orbit[j]), wi, case, ev)
            M[j], P[j], T[j], C[j] = ev[EV_MU], ev[EV_P0:EV_P0 + NC].sum(), ev[EV_TOUT], ev[EV_TZ]
        return M, P, T, C

    def residual(x):
        w, orbit = x[:Z], x[Z:]
        M, _, _, C = evaluate(w, orbit)
        r = np.empty(2 * Z)
        r[:Z] = np.where(loaded, M - Ix * wc * Z / (2.0 * np.pi) * (w - np.roll(w, 1)), w - wR)
        # free rollers (the quasi-static default, sim.solvers.kinematics.free_roller_speeds): each loaded
        # roller at the orbit speed where its contacts' z-moment about the bearing axis balances its share
        # of driving the rollers on the outer raceway alone, which orbit with the cage
        r[Z:] = np.where(pushers, C + share * C[held].sum(), orbit - wc)
        return r

    # film passes: the film (thermal viscosity, entrainment) at the speeds of the previous pass, as
    # the quasi-static kinematics iterate it (sim.solvers.kinematics)
    x = np.concatenate([wR, np.full(Z, wc)])
    for _ in range(FILM_PASSES):
        sol = root(residual, x, method="hybr")
        if not sol.success:
            raise RuntimeError(f"{overrides}: {sol.message}")
        change = np.abs(sol.x - x).max() / np.abs(sol.x).max()
        x = sol.x
        lubrication_state(x[:Z].copy(), wc, wi, loaded, case)
        if change < FILM_TOLERANCE:
            break
    w, orbit = x[:Z], x[Z:]
    _, P, T, _ = evaluate(w, orbit)
    c = Ix * wc * Z / (2.0 * np.pi)
    spin_up = 0.5 * c * float(((w - np.roll(w, 1)) ** 2).sum())
    return float(res["torque"]), (P.sum() + spin_up) / wi, float(T.sum()), wR.copy(), w


def main():
    rows = []
    for name, overrides in CASES.items():
        solver, exp, t_out, w_rigid, w_exp = orbit_experiment(overrides)
        default = float(sim.simulate(sim.load_config(overrides)).isel(design=0, case=0).torque)
        d = sim.simulate(sim.load_config(overrides + ["solver=dynamic"])).isel(design=0, case=0)
        dyn = float(d.torque)
        spin = d.roller_speed_t.values * np.pi / 30.0
        dyn_cfg = resolved(sim.load_config(overrides + ["solver=dynamic"]))["solver"]["dynamic"]
        samples = int(dyn_cfg["samples_per_window"])
        last = spin[-samples:]          # the last window
        rows.append((name, default, solver, exp, t_out, dyn, bool(d.converged), w_rigid.min() / w_rigid.max(),
                     w_exp.min() / w_exp.max(), last.min() / last.max()))
        print(rows[-1], flush=True)
    lines = ["# Roller spin inertia along the orbit: the solver, an independent solution and the time domain", "",
             "Generated by `python docs/figures/orbit_inertia.py` (method in its docstring). Torques in N mm.",
             "Solver: the quasi-static default (`sim.simulate`, friction loads fed back), and its friction",
             "evaluation without that feedback, on which the independent solution runs. Time domain: steady state",
             "from rolling kinematics. Spin ratio: slowest over fastest roller (time domain: over the last window's",
             "samples); the rigid cage balances each roller at its azimuth, as the free rollers did before session 24.",
             "",
             "| case | solver | solver without feedback | independent | its outer-ring torque | time domain "
             "| solver vs time domain | independent vs solver without feedback | spin ratio rigid cage / independent "
             "/ time domain |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, default, solver, exp, t_out, dyn, steady, r_rigid, r_exp, r_dyn in rows:
        lines.append(f"| {name} | {default:.1f} | {solver:.1f} | {exp:.1f} | {t_out:.1f} | "
                     f"{dyn:.1f}{'' if steady else ' (not steady)'} | {default / dyn - 1:+.2%} | "
                     f"{exp / solver - 1:+.1e} | {r_rigid:.3f} / {r_exp:.3f} / {r_dyn:.3f} |")
    OUT.write_text("\n".join(lines) + "\n")
    print(OUT.read_text())


if __name__ == "__main__":
    main()

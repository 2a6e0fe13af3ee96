"""Wall-clock cost of the time-domain solver (sim.solvers.dynamic) on one thread (issue 18 item 5).

Cases: the TRB 32208 rig case (Fa 4500 N, Fr 0, 2000 rpm) and the pinion TSRB (conf bearing
tsrb_pinion, lubricant pinion_oil, Fa 35 kN, Fr 0, 1100 rpm, oil 50 degC as conf/study/pinion.yaml).
For each it reports the median of ``--repeats`` right-hand-side evaluations at the start state
(target < 1 ms), and the wall time of ``--revolutions`` inner-ring revolutions from rolling
kinematics (the steady-state detector switched off so that every revolution runs; target 60 s
for 10, goal 20 s) with the steps' work: right-hand sides and Jacobians. The start (the
quasi-static solution and the numba compile or cache load) is timed apart.

Run from the repository root::

    python benchmarks/bench_dynamic.py [--revolutions 10] [--repeats 201]
"""
import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))  # run from a checkout: this sim/, not an installed one

import sim  # noqa: E402
from sim.api import dynamic_model  # noqa: E402
from sim.api.cases import operating_points  # noqa: E402
from sim.api.simulation import build_models, resolved  # noqa: E402
from sim.solvers.dynamic import Integration  # noqa: E402

CASES = {
    "trb_32208 4.5 kN 2000 rpm": ["bearing=trb_32208", "load.Fa=4500", "load.Fr=0", "load.speed=2000"],
    "tsrb_pinion 35 kN 1100 rpm": ["bearing=tsrb_pinion", "lubricant=pinion_oil", "load.Fa=35000", "load.Fr=0",
                                   "load.speed=1100", "load.oil_temperature=50"],
}
RHS_TARGET_MS = 1.0
RUN_TARGET_S = 60.0


def bench(overrides, revolutions, repeats):
    cfg = sim.load_config(["solver=dynamic", "solver.dynamic.start=rolling"] + overrides)
    plain = resolved(cfg)
    t0 = time.perf_counter()
    model, friction = build_models(cfg, plain)
    op = operating_points(plain["load"])[0]
    dc = dynamic_model.prepare(model, friction, op, plain["solver"]["dynamic"])
    t_start = time.perf_counter() - t0
    probe = Integration(dc.problem, dc.settings)
    probe.f(0.0, dc.y0)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        probe.f(0.0, dc.y0)
        times.append(time.perf_counter() - t)
    rhs_ms = 1e3 * statistics.median(times)
    # every window runs: no steady-state stop
    settings = dc.settings._replace(max_windows=revolutions, tol_speed=0.0, tol_torque=0.0, tol_load=0.0, tol_skew=0.0,
                                    window=2.0 * np.pi / dc.problem.body.wi)
    t = time.perf_counter()
    integ = dynamic_model.run(dc._replace(settings=settings))
    wall = time.perf_counter() - t
    return dict(start_s=t_start, rhs_ms=rhs_ms, wall_s=wall, per_rev_s=wall / revolutions, rhs=integ.rhs_calls,
                jac=integ.jac_calls, torque=float(integ.tot_t[-1, 0]), qs_torque=dc.quasi_static["torque"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--revolutions", type=int, default=10)
    ap.add_argument("--repeats", type=int, default=201)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores (shared machine: timings are upper bounds)")
    for name, overrides in CASES.items():
        r = bench(overrides, args.revolutions, args.repeats)
        print(f"{name}: start {r['start_s']:.1f} s; rhs median {r['rhs_ms']:.3f} ms (target < {RHS_TARGET_MS} ms); "
              f"{args.revolutions} revolutions {r['wall_s']:.1f} s (target {RUN_TARGET_S:.0f} s), "
              f"{r['per_rev_s']:.2f} s/rev, {r['rhs']} rhs, {r['jac']} Jacobians; torque at the end "
              f"{r['torque']:.1f} N mm (quasi-static {r['qs_torque']:.1f})")


if __name__ == "__main__":
    main()

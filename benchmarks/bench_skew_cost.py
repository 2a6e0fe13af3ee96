"""CPU time of a quasi-static solve with friction, roller skew off and on (issue 18, item 1: "a
combined case with friction and roller skew stays below 2x today's time").

For four cases, built from the configs the repository ships as the tests build them
(tests/friction/test_skew.py, tests/balance/test_equilibrium.py):

- tsrb_reference and trb_32208, combined case (Fa 4500 N, Fr 2000 N, 2000 rpm, tilt 0, oil 55 degC);
- tsrb_pinion and trb_31313, 35 kN pure axial at 1100 rpm, lubricant pinion_oil (oil 55 degC);

it reports the median and minimum CPU time (``time.process_time``) of ``--repeats`` full solves
(``sim.api.simulation.solve_case``: load distribution, kinematics, friction and the coupling of the
friction loads, ``sim.api.friction_model.coupled_solution``) after one warm-up, with
``friction.skew.enabled`` false and true, and their ratio. For each case one further, untimed-for-
the-table solve with skew counts the coupling passes (``BearingModel.solve`` calls after the first)
and splits the CPU time into the load solves (``BearingModel.solve``) and the friction evaluations
(``FrictionModel.evaluate``: film, kinematics, friction loads) of each pass; numba kernels are
opaque to cProfile, so these phases are timed from Python.

Run from the repository root::

    python benchmarks/bench_skew_cost.py [--repeats 15] [--slices 20]

Exit code 0 when every solve converged, 1 otherwise. Pin it to one core on a shared machine
(``taskset -c 1``); the thread variables are set to 1 here.

Measured (2026-11-27, the shared 2-core machine pinned to one core, load average 1.0, 15 repeats,
two alternating runs of each commit; CPU ms no skew / skew, ratio, coupling passes):

    case                      9153499 (before)              4c084df (after)
    tsrb_reference combined   7.54 / 13.40  1.78x  3        7.56 /  9.88  1.31x  2
    trb_32208 combined        5.86 / 15.12  2.58x  3        5.89 / 11.06  1.88x  2
    tsrb_pinion 35 kN         1.87 /  2.98  1.60x  3        1.90 /  2.79  1.47x  3
    trb_31313 35 kN           1.42 /  2.78  1.96x  2        1.43 /  2.64  1.85x  2

Where the skewed time went before (trb_32208): first load solve 2.0 ms, first friction evaluation
6.2 ms (film at rolling kinematics and the seed solve, film at its speeds and the final solve: 8
evaluations of all rollers at 0.43 ms each, 0.25 ms without skew, which integrates one width half),
then per coupling pass a load solve of 0.5-0.8 ms and an evaluation of 1.3-1.8 ms (film 0.23 ms, 3-4
all-roller evaluations). After: the coupling is Anderson-mixed from its first pass (one pass fewer
on the combined cases) and the first evaluation stops at its seed solve (3.2 ms).
"""
import argparse
import os
import statistics
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

PINION = ["lubricant=pinion_oil", "load.Fa=35000", "load.Fr=0", "load.speed=1100"]
COMBINED = ["load.Fa=4500", "load.Fr=2000", "load.speed=2000", "load.tilt=0", "load.oil_temperature=55"]
CASES = {
    "tsrb_reference combined": ["bearing=tsrb_reference", *COMBINED],
    "trb_32208 combined": ["bearing=trb_32208", *COMBINED],
    "tsrb_pinion 35 kN": ["bearing=tsrb_pinion", *PINION],
    "trb_31313 35 kN": ["bearing=trb_31313", *PINION],
}
TARGET_RATIO = 2.0   # skew / no skew (issue 18, item 1)


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=15, help="timed solves per case and setting after one warm-up")
    p.add_argument("--slices", type=int, default=20, help="slices per roller-raceway contact (default 20)")
    args = p.parse_args(argv)
    if args.repeats < 1:
        p.error("--repeats must be >= 1")
    return args


def build(name, skew, slices):
    import sim
    from sim.api.cases import operating_points
    from sim.api.simulation import build_friction, build_model

    cfg = sim.load_config([*CASES[name], f"solver.n_slices={slices}", f"friction.skew.enabled={str(skew).lower()}"])
    model = build_model(cfg)
    return model, build_friction(cfg, model), next(iter(operating_points(cfg.load))), cfg.output


def timed(model, friction, op, output, repeats):
    """Median and minimum CPU ms of ``repeats`` solve_case calls after one warm-up, all converged."""
    from sim.api.simulation import solve_case

    res = solve_case(model, friction, op, output)          # warm-up (and compile)
    converged = bool(res["converged"])
    cpu = []
    for _ in range(repeats):
        c0 = time.process_time()
        res = solve_case(model, friction, op, output)
        cpu.append(time.process_time() - c0)
        converged &= bool(res["converged"])
    return 1e3 * statistics.median(cpu), 1e3 * min(cpu), converged, res


def phases(model, friction, op, output):
    """One solve_case with its load solves and friction evaluations timed (CPU ms): the list of
    (solve ms, evaluate ms) per pass, pass 0 the uncoupled one."""
    from sim.api.simulation import solve_case

    log = []
    solve, evaluate = model.solve, friction.evaluate

    def timed_solve(*a, **k):
        c0 = time.process_time()
        out = solve(*a, **k)
        log.append(["solve", 1e3 * (time.process_time() - c0)])
        return out

    def timed_evaluate(*a, **k):
        c0 = time.process_time()
        out = evaluate(*a, **k)
        log.append(["evaluate", 1e3 * (time.process_time() - c0)])
        return out

    model.solve, friction.evaluate = timed_solve, timed_evaluate
    try:
        solve_case(model, friction, op, output)
    finally:
        del model.solve, friction.evaluate          # back to the class methods
    passes = []
    for kind, ms in log:
        if kind == "solve":
            passes.append([ms, 0.0])
        else:
            passes[-1][1] = ms
    return passes


def main(argv=None):
    args = parse_args(argv)
    for var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    if str(REPO) not in sys.path:
        sys.path.insert(0, str(REPO))   # run from a checkout without an installed package
    import numba
    import numpy as np
    from sim.io import git_commit

    print("skew cost benchmark: CPU time (time.process_time) of sim.api.simulation.solve_case with friction")
    print(f"  git commit : {git_commit()}")
    print(f"  numba/numpy: {numba.__version__} / {np.__version__}")
    print(f"  slices     : {args.slices}; repeats {args.repeats} after 1 warm-up; load average "
          f"{os.getloadavg()[0]:.2f}")
    print()
    head = (f"{'case':<24} {'no skew ms':>10} {'(min)':>7} {'skew ms':>8} {'(min)':>7} {'ratio':>6}  "
            f"{'passes':>6}  {'torque no skew':>14} {'skew N mm':>10}")
    print(head)
    print("-" * len(head))
    ok = True
    split = {}
    for name in CASES:
        row = {}
        for skew in (False, True):
            model, friction, op, output = build(name, skew, args.slices)
            row[skew] = timed(model, friction, op, output, args.repeats)
            ok &= row[skew][2]
            if skew:
                split[name] = phases(model, friction, op, output)
        (m0, n0, _, r0), (m1, n1, _, r1) = row[False], row[True]
        ratio = m1 / m0
        print(f"{name:<24} {m0:10.2f} {n0:7.2f} {m1:8.2f} {n1:7.2f} {ratio:6.2f}{'' if ratio < TARGET_RATIO else '!'} "
              f"{len(split[name]) - 1:6d}  {r0.get('torque', float('nan')):14.2f} {r1.get('torque', float('nan')):10.2f}")
    print(f"passes: coupling passes of the skewed solve after the uncoupled one; '!' ratio >= {TARGET_RATIO}")
    print()
    print("skewed solve, CPU ms per pass (one instrumented solve_case): load solve + friction evaluation")
    for name, passes in split.items():
        text = ", ".join(f"{s:.2f}+{e:.2f}" for s, e in passes)
        total = sum(s + e for s, e in passes)
        print(f"  {name:<24} {text}   (sum {total:.2f})")
    print(f"all solves converged: {ok}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

"""Report of a design search (issue 5, item 5): verified results only.

Writes into the study folder:

- ``verified.nc``: every full simulation of the search with its constraint margins and
  feasibility (DATA.md names; ``source`` tells the initial design from verification runs);
- ``best_design.nc``: the full result of the verified best design (pressure included);
- ``history.png``, ``parity.png``, ``pressure.png``;
- ``report.md``: the comparison with the reference TRB and the thesis design, and the
  cross-validation of the final surrogates (also printed);
- with ``study.verify.solver = dynamic`` also ``best_design_dynamic.nc``: the verified best by
  the time-domain solver with skew and tilt free, its torque and skew in report.md
  (:func:`studies.verify.dynamic_verification`).
"""
import shlex
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from sim.io import write_bytes_atomic, write_figure_atomic, write_netcdf_atomic  # noqa: E402
from studies.config import simulation_arguments  # noqa: E402
from studies.constraints import margins, violation  # noqa: E402
from studies.cycle import LOAD_KEYS, DutyCycle  # noqa: E402
from studies.evaluate import STATUS, case_values, design_config, design_matrix, simulate_point, table_to_file  # noqa: E402
from studies.verify import dynamic_verification  # noqa: E402
from surrogate import cross_validate_outputs  # noqa: E402

COLUMNS = ("pmax", "axial_displacement", "L_eff", "C_eff", "L10", "edge_stress")
TITLE_WIDTH = 90   # characters of a figure title line at fontsize 8-9 on the 7-10 inch wide figures here


def verified_dataset(search, ds):
    """``ds`` with the constraint margins (design, constraint) and the feasibility of every point."""
    M = search.point_margins(ds)
    return ds.assign(
        constraint_margin=(("design", "constraint"), M,
                           {"units": "1", "long_name": "normalised constraint margin, <= 0 satisfied"}),
        feasible=("design", np.all(M <= 0.0, axis=1), {"long_name": "all constraints satisfied (full simulation)"}),
    ).assign_coords(constraint=("constraint", list(search.limits.names), {"long_name": "constraint"}))


def comparison_rows(search, best):
    """(label, record, margins or None) of the verified best, the thesis design and the reference TRB.

    The TSRB constraints are evaluated for the TSRBs; the TRB (which has a rib) sets limits.
    """
    rows = [best]
    for ref in search.references.values():
        bearing = ref.cfg.bearing
        m = None
        if str(bearing.type) == "TSRB":
            m = margins(case_values(ref.records), {"PCR": float(bearing.PCR), "ratings_alpha": float(bearing.ratings_alpha)},
                        search.limits, 0.0 if ref.record["status"] == "ok" else 1.0)
        rows.append((f"{ref.label} {ref.bearing}", ref.record, m))
    return rows


def cross_validation(search, ds):
    """k-fold CV of every modelled output on the final training data: ({name: CrossValidation},
    {name: its units})."""
    s = search.study.surrogate
    sets = search.training_sets(ds)
    return (cross_validate_outputs(sets, search.space.bounds, search.settings, int(s.cv_folds), float(s.interval),
                                   lambda q, n: search.log(f"report: {int(s.cv_folds)}-fold cross-validation of the {q} "
                                                           f"surrogate on {n} points")),
            {q: units for q, (_, _, _, units) in sets.items()})


def load_case_label(study):
    """The study's load case in words for titles: 'Fa 35 kN, Fr 0 kN, 1100 rpm, tilt 0 deg, 50 degC',
    or its duty cycle: 'duty cycle Fa/Fr/speed/share: 60/0 kN 550 rpm 0.1; ...; tilt 0 deg, 50 degC'."""
    L = study.load
    if not study.get("duty_cycle"):
        return (f"Fa {float(L.Fa) / 1e3:g} kN, Fr {float(L.Fr) / 1e3:g} kN, {float(L.speed):g} rpm, "
                f"tilt {float(L.tilt):g} deg, oil {float(L.oil_temperature):g} degC")
    cycle = DutyCycle.from_config(study)
    # tilt and oil once where every case shares them (a cycle's entries may set their own), else per case
    shared = all(c[k] == cycle.cases[0][k] for c in cycle.cases for k in ("tilt", "oil_temperature"))
    cases = "; ".join(f"{c['Fa'] / 1e3:g}/{c['Fr'] / 1e3:g} kN {c['speed']:g} rpm {w:g}"
                      + ("" if shared else f" (tilt {c['tilt']:g} deg, oil {c['oil_temperature']:g} degC)")
                      for c, w in zip(cycle.cases, cycle.share))
    return (f"duty cycle Fa/Fr, speed, share: {cases}"
            + (f"; tilt {cycle.cases[0]['tilt']:g} deg, oil {cycle.cases[0]['oil_temperature']:g} degC" if shared else ""))


def ratio_in_words(name, value, reference_label, reference_value):
    """'torque 4.6 % below the reference TRB trb_31313 (ratio 0.954)', or '' without both values."""
    if not (np.isfinite(value) and np.isfinite(reference_value)) or reference_value == 0.0:
        return ""
    r = value / reference_value
    side = "below" if r < 1.0 else "above"
    return f"{name} {abs(100.0 * (r - 1.0)):.1f} % {side} the {reference_label} (ratio {r:.3f})"


# ---------------------------------------------------------------------------- plots
def wrapped(label):
    """A title line broken to the width of a figure (a duty cycle's label is long)."""
    return textwrap.fill(label, TITLE_WIDTH)


def plot_history(search, vds, refs, path):
    """Objective of every full simulation in run order, numbered as training.nc's designs, the report
    and the log (from 0); running best feasible; references (an infeasible TSRB reference, e.g. the
    thesis design under the study's constraints, is marked). The legend sits beside the axes, where
    it hides no point."""
    obj = search.objective
    y = search.objective_values(vds)
    feas = vds.feasible.values
    n = np.arange(len(y))
    fig, ax = plt.subplots(figsize=(9, 4), layout="constrained")
    ax.plot(n[feas], y[feas], "o", color="C0", label="feasible")
    ax.plot(n[~feas], y[~feas], "o", mfc="none", color="C7", label="infeasible")
    best = np.minimum.accumulate(np.where(feas, y, np.inf))
    if np.isfinite(best).any():
        ax.step(n[np.isfinite(best)], best[np.isfinite(best)], where="post", color="C3", label="verified best")
    n0 = int(np.sum(vds.source.values == "initial"))
    ax.axvline(n0 - 0.5, color="k", lw=0.8, ls=":", label="end of initial design")
    for i, (label, record, m) in enumerate(refs):
        if np.isfinite(record["values"][obj]):
            infeasible = m is not None and violation(m) > 0.0
            ax.axhline(record["values"][obj], color=f"C{i + 1}", ls=":" if infeasible else "--", lw=1,
                       label=f"{label} (INFEASIBLE here)" if infeasible else label)
    several = len(search.cycle) > 1
    ax.set_xlabel(f"full simulation (design index of training.nc){', a design at every case' if several else ''}")
    ax.set_ylabel(f"{obj}{', time-weighted' if several else ''} "
                  f"[{vds[obj].attrs.get('units', '')}]")
    ax.set_title(f"{search.study.name}: optimisation history\n{wrapped(load_case_label(search.study))}", fontsize=9)
    fig.legend(loc="outside right upper", fontsize=7)
    write_figure_atomic(fig, path, 120)
    plt.close(fig)


PARITY_COLUMNS = 4      # panels per row of the parity figure (a duty cycle has one per output and case)


def plot_parity(cv, units, path, load_label):
    """Out-of-fold prediction against simulation, with the prediction intervals; ``units`` by name.
    Each panel's axes span the simulated and predicted values (5 % margin): an interval reaching
    beyond them (a log output's upper bound at a point far outside the data, up to 1e31 N seen) is
    cut at the frame rather than setting the scale."""
    names = list(cv)
    cols = min(PARITY_COLUMNS, len(names))
    rows = -(-len(names) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.4 * cols, 3.4 * rows + 0.4), squeeze=False, layout="constrained")
    for ax, q in zip(axes.ravel(), names):
        c = cv[q]
        ax.errorbar(c.y, c.mean, yerr=[c.mean - c.lower, c.upper - c.mean], fmt="o", ms=3, lw=0.6, alpha=0.7)
        lo = min(c.y.min(), c.mean.min())
        hi = max(c.y.max(), c.mean.max())
        pad = 0.05 * (hi - lo) if hi > lo else 0.05 * max(abs(hi), 1.0)
        lim = [lo - pad, hi + pad]
        ax.plot(lim, lim, "k-", lw=0.8)
        ax.set_xlim(lim)
        ax.set_ylim(lim)
        ax.set_xlabel(f"simulated {q} [{units.get(q, '1')}]", fontsize=8)
        ax.set_ylabel(f"predicted {q} [{units.get(q, '1')}]", fontsize=8)
        ax.set_title(f"R2 {c.r2:.3f}, cover {c.coverage:.2f}\nRMSE {c.rmse:.3g}", fontsize=8)
    for ax in axes.ravel()[len(names):]:
        ax.set_visible(False)
    level = int(round(100 * next(iter(cv.values())).level))
    fig.suptitle(wrapped(f"surrogate parity, {level} % intervals (k-fold CV; intervals beyond the frame cut); "
                         f"{load_label}"), fontsize=9)
    write_figure_atomic(fig, path, 120)
    plt.close(fig)


def plot_pressure(datasets, path, load_label):
    """Pressure along the most loaded roller (outer, inner race) of the labelled results."""
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), sharey=True)
    for ax, race in zip(axes, ("outer", "inner")):
        for label, ds in datasets:
            if ds is None or not bool(ds.converged.all()):
                continue
            p = ds.pressure.isel(design=0, case=0).sel(race=race)
            ax.plot(ds.x_slice.values, p.values, marker=".", label=label)
        ax.set_title(f"{race} race; {load_label}", fontsize=8)
        ax.set_xlabel("x from the large end [mm]")
    axes[0].set_ylabel("pressure [MPa]")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    write_figure_atomic(fig, path, 120)
    plt.close(fig)


# ---------------------------------------------------------------------------- text
def _fmt(v):
    return "-" if v is None or (isinstance(v, float) and not np.isfinite(v)) else f"{v:.4g}"


def comparison_table(search, rows, attrs):
    cols = tuple(dict.fromkeys((search.objective, *COLUMNS)))
    head = "| design | " + " | ".join(f"{c} [{attrs.get(c, {}).get('units', '')}]" for c in cols) + \
        " | feasible | tightest constraint (margin) |"
    lines = [head, "|" + " --- |" * (len(cols) + 3)]
    for label, record, m in rows:
        vals = [_fmt(record["values"].get(c)) for c in cols]
        if m is None:
            feas, worst = "(reference)", "-"
        else:
            feas = "yes" if violation(m) == 0.0 else "no"
            j = 1 + int(np.argmax(m[1:]))  # margins[0] is the simulation's own
            worst = f"{search.limits.names[j]} {m[j]:+.3f}"
        if record["status"] != "ok":
            feas, vals = record["status"], ["-"] * len(cols)
        lines.append(f"| {label} | " + " | ".join(vals) + f" | {feas} | {worst} |")
    return "\n".join(lines)


#: Half width of the coverage target around the intervals' probability: issue 16 item 1 asks 95 % intervals
#: to cover 0.92-0.98 of the points in cross-validation.
COVERAGE_TOLERANCE = 0.03


def cv_table(cv):
    """Markdown table of the cross-validation of each output, with its coverage against the target
    (level +- COVERAGE_TOLERANCE), and a line naming the outputs outside it ('' lines when none)."""
    lines = ["| output | n | R^2 | RMSE | coverage | target |", "| --- | --- | --- | --- | --- | --- |"]
    outside = []
    for q, c in cv.items():
        low, high = c.level - COVERAGE_TOLERANCE, c.level + COVERAGE_TOLERANCE
        verdict = "met" if low <= c.coverage <= high else ("below" if c.coverage < low else "above")
        if verdict != "met":
            outside.append(f"{q} {c.coverage:.3f}")
        lines.append(f"| {q} | {len(c.y)} | {c.r2:.4f} | {c.rmse:.4g} | {c.coverage:.3f} | {low:.2f}-{high:.2f}: "
                     f"{verdict} |")
    if outside:
        lines += ["", f"Coverage outside the target (its intervals too narrow below, too wide above; with n points "
                      f"the coverage itself scatters by about sqrt(0.05 x 0.95 / n)): {', '.join(outside)}."]
    return "\n".join(lines)


def local_stage_text(search):
    """What the final local stage (studies.refine) found, in words: start, end, active constraints
    and active search bounds ('' when the stage did not run)."""
    L = search.local
    if L is None:
        return ""
    s = search.study
    names = search.space.names
    others = (f" and {L.starts - 1} other distinct verified design(s) (one screening run each)"
              if L.starts > 1 else "")
    lines = [f"Final local stage (COBYLA on the full simulation from the loop's verified best{others}, {L.runs} "
             f"run(s) in all, {L.evaluations} points incl. the starts; last run: {L.message.strip()}): "
             f"{search.objective} {L.start_value:.6g} -> {L.value:.6g} "
             f"({100.0 * (L.value / L.start_value - 1.0):+.2f} %), {'feasible' if L.feasible else 'INFEASIBLE'}."]
    if not L.feasible:    # an infeasible end: what it violates first (session 32: pmax was left out)
        lines.append("Violated constraints (margin > 0): " + ", ".join(
            f"{n} {m:+.3g}" for n, m in zip(search.limits.names, L.margins) if m > 0.0) + ".")
    lines.append("Active constraints (margin within refine.active_tolerance of its limit, or between it and the "
                 "refine.constraint_backoff that the local run which found the design kept from it): "
                 + (", ".join(L.active_constraints) or "none") + ".")
    if L.active_bounds and not L.feasible:
        parts = [f"{names[k]} at its {side} bound" for k, side in L.active_bounds]
        lines.append("The design sits on search bounds (" + "; ".join(parts) + "), but it violates constraints: no "
                     "feasible design was found, so the bounds say nothing about where the optimum lies.")
    elif L.active_bounds:
        parts = [f"{names[k]} at its {side} bound {float(s.bounds[names[k]][0 if side == 'low' else 1]):g}"
                 for k, side in L.active_bounds]
        lines.append("The optimum sits on search bounds: " + "; ".join(parts) + ". These bounds are study.bounds, "
                     "a search range chosen in conf/study (an engineering choice, not a physical limit): the "
                     "optimum is there or beyond, and widening the range may lower the objective further.")
    else:
        lines.append("No search bound is active: the optimum is inside study.bounds.")
    return " ".join(lines)


def case_table(search, best_runs):
    """Per-case results of the verified best beside the reference TRB's (markdown): torque and
    power loss from the full simulations, pmax against the case's limit, axial displacement, the
    edge-stress margin and the case's status."""
    trb = search.references["reference TRB"]
    lines = ["| case | Fa [N] | Fr [N] | speed [rpm] | share | torque [N*mm] | TRB torque [N*mm] | power loss [W] | "
             "TRB power loss [W] | pmax [MPa] | pmax limit [MPa] | axial displacement [mm] | edge-stress margin | status |",
             "|" + " --- |" * 14]
    for k, (case, share) in enumerate(zip(search.cycle.cases, search.cycle.share)):
        (ds, record), trb_ds = best_runs[k], trb.datasets[k]

        def result(d, q):
            return float(d[q].isel(design=0, case=0)) if d is not None and q in d else np.nan

        v = record["values"]
        lines.append(f"| {k} | {case['Fa']:g} | {case['Fr']:g} | {case['speed']:g} | {share:g} | "
                     f"{_fmt(result(ds, 'torque'))} | {_fmt(result(trb_ds, 'torque'))} | {_fmt(result(ds, 'power_loss'))} | "
                     f"{_fmt(result(trb_ds, 'power_loss'))} | {_fmt(v['pmax'])} | {_fmt(search.limits.pmax_max[k])} | "
                     f"{_fmt(v['axial_displacement'])} | {_fmt(v['edge_stress_margin'])} | {record['status']} |")
    return "\n".join(lines)


def resimulation_text(search, ds, i, best_record):
    """The verified best simulated once more at every case: its objective against the stored one."""
    stored = float(search.objective_values(ds)[i])
    again = float(best_record["values"].get(search.objective, np.nan))
    cases = f" at all {len(search.cycle)} cases" if len(search.cycle) > 1 else ""
    same = "identical" if again == stored else f"relative difference {again / stored - 1.0:+.2e}"
    return (f"Re-simulated{cases} for this report: {search.objective} {again:.6g} against {stored:.6g} stored "
            f"({same}); status {best_record['status']}.")


def resimulate_commands(search, bearing):
    """The command lines that simulate design ``bearing`` (name -> value) as the search did, one per
    load case of its duty cycle (one for a single case), every value to full precision (repr) and each
    token shell-quoted."""
    values = [f"bearing.{k}={float(v)!r}" for k, v in bearing.items() if v is not None]
    return [shlex.join(["python", "-m", "sim.run", *simulation_arguments(
                search.study, search.study.bearing, search.overrides,
                [*values, *(f"load.{k}={float(case[k])!r}" for k in LOAD_KEYS)])])
            for case in search.cycle.cases]


def life_text(search, best_record):
    """The rating life over the cycle in words: P_eq and L10 of the verified best and of the reference TRB."""
    trb = search.references["reference TRB"]
    parts = [f"{label}: P_eq = {_fmt(r['values'].get('P'))} N, L10 = {_fmt(r['values'].get('L10'))} 1e6 rev"
             for label, r in (("verified best", best_record), (f"reference TRB {trb.bearing}", trb.record))]
    return ("Rating life over the cycle (equivalent dynamic load P_eq = (sum share n P^p / sum share n)^(1/p), "
            "p = 10/3, ISO 281 / Harris & Kotzalas 2007; L10 = (least C_eff / P_eq)^p): " + "; ".join(parts) + ".")


def write_report(search, ds, reason):
    """Write the report files of a finished search; returns the report text (markdown)."""
    out = search.out
    vds = verified_dataset(search, ds)
    write_netcdf_atomic(table_to_file(vds), out / "verified.nc")
    i, key = search.best(ds)
    x = design_matrix(ds, search.space)[i]
    bearing = search.space.bearing_values(x)
    search.log(f"report: simulating the verified best at {len(search.case_cfgs)} load case(s)")
    best_runs = [simulate_point(design_config(cfg, bearing), search.quantities) for cfg in search.case_cfgs]
    best_records = [r for _, r in best_runs]
    results = [d for d, _ in best_runs]
    if all(d is not None for d in results):
        write_netcdf_atomic(results[0] if len(results) == 1 else
                            xr.concat(results, dim="case", data_vars="minimal", coords="minimal", compat="override",
                                      combine_attrs="override"), out / "best_design.nc")
    best_record = search.summary(best_records)
    best_m = margins(case_values(best_records), bearing, search.limits, 0.0 if best_record["status"] == "ok" else 1.0)
    rows = comparison_rows(search, ("verified best", best_record, best_m))
    attrs = {q: ds[q].attrs for q in ds.data_vars}
    cv, units = cross_validation(search, ds)
    search.log("report: figures")
    plot_history(search, vds, rows[1:], out / "history.png")
    label = load_case_label(search.study)
    if cv:      # outputs with fewer points than surrogate.cv_folds are not cross-validated
        plot_parity(cv, units, out / "parity.png", label)
    # the pressure of the case with the largest axial load (the only one of a one-case study)
    k = int(np.argmax(search.cycle.column("Fa")))
    plot_pressure([("verified best", results[k])] + [(f"{r.label} {r.bearing}", r.datasets[k])
                                                    for r in search.references.values()],
                  out / "pressure.png", label if len(search.cycle) == 1 else f"case {k}: {search.cycle.label(k)}")
    s = search.study
    dynamic = dynamic_verification(search, bearing, results) if s.verify.solver == "dynamic" else None
    several = len(search.cycle) > 1
    n_by = {k: int((ds.status == v).sum()) for k, v in STATUS.items()}
    feasible = "feasible" if key[0] == 0 else f"NO FEASIBLE DESIGN FOUND (least violation {key[1]:.4g})"
    params = ", ".join(f"{k} = {bearing[k]:.4g}" for k in (*search.space.names, "ratings_alpha"))
    local = local_stage_text(search)
    obj = search.objective
    words = [ratio_in_words(obj, best_record["values"].get(obj, np.nan), f"{r.label} {r.bearing}",
                            r.record["values"].get(obj, np.nan)) for r in search.references.values()]
    words = "; ".join(w for w in words if w)
    pmax_limits = "/".join(f"{v:.1f}" for v in search.limits.pmax_max)
    if several:
        load_text = (f"Duty cycle of {len(search.cycle)} load cases (title and table below); objective `{obj}` "
                     f"time-weighted over the cycle "
                     f"(sum of share x per-case value, minimised), constraints at every case, L10 over the cycle from "
                     f"the ISO 281 equivalent load (studies.cycle)")
    else:
        load_text = (f"Load case Fa = {s.load.Fa:g} N, Fr = {s.load.Fr:g} N, {s.load.speed:g} rpm, tilt {s.load.tilt:g} deg; "
                     f"objective `{obj}` (minimised)")
    text = "\n".join([
        f"# Design search `{s.name}`: {s.bearing} vs {s.reference_trb} and {s.thesis_design}, "
        f"{'over the ' if several else ''}{load_case_label(s)}",
        "",
        f"{load_text}; constrained Bayesian optimisation, "
        f"{s.budget.verify_per_round} designs a round; surrogate intervals "
        f"{'calibrated' if s.surrogate.calibrate else 'not calibrated'}.",
        f"Limits: |axial displacement| <= {search.limits.axial_displacement_max:g} mm, "
        f"pmax <= {pmax_limits} MPa{' (per case)' if several else ''}, L10 >= {search.limits.L10_min:.4g} 1e6 rev"
        f"{' (over the cycle)' if several else ''}, edge stress {'forbidden' if search.limits.edge_stress else 'allowed'}, "
        f"PCR/Lwe <= {search.limits.PCR_over_Lwe_max:g}.",
        f"Full simulations: {ds.sizes['design']}{f' designs x {len(search.cycle)} cases' if several else ''} ({n_by}); "
        f"stopped: {reason}.",
        "",
        f"Verified best ({feasible}), simulation #{i}: {params}",
        "",
        "Simulate it again (values to full precision; `best_design.nc` holds its results)"
        + (", case by case:" if several else ":"),
        "",
        *(f"    {command}" for command in resimulate_commands(search, bearing)),
        "",
        resimulation_text(search, ds, i, best_record),
        "",
        *([f"The verified best has{' over the duty cycle' if several else ''} its {words}.", ""] if words else []),
        *([life_text(search, best_record), ""] if several else []),
        *([local, ""] if local else []),
        *([f"## Per case of the {load_case_label(s)}", "", "Verified best at every case, beside the reference TRB "
           f"{s.reference_trb} (full simulations):", "", case_table(search, best_runs), "",
           "Cycle values (table below): objective time-weighted, pmax and edge stress the worst case, C_eff the least, "
           "L10 over the cycle.", ""] if several else []),
        comparison_table(search, rows, attrs),
        "",
        f"Surrogate cross-validation ({s.surrogate.cv_folds}-fold, {100 * s.surrogate.interval:g} % intervals, "
        f"final training data):",
        "",
        cv_table(cv),
        "",
        *([dynamic, ""] if dynamic else []),
        "Files: verified.nc, best_design.nc, history.png, parity.png, pressure.png, training.nc, surrogates/"
        + (", best_design_dynamic*.nc." if dynamic else "."),
    ])
    write_bytes_atomic(out / "report.md", (text + "\n").encode())
    return text

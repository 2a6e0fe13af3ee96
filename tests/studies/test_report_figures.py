"""The design-search report's figures (studies/report.py) read as an engineer reads them: units on
every axis, every point visible, numbering as in the report (an independent check of session 31
found per-case outputs labelled [1], 13 panels in one row, a 1e31 interval setting an axis, and
the history's points numbered from 1 where the report numbers from 0)."""
import numpy as np

from studies import report
from surrogate.validation import CrossValidation


def _captured(monkeypatch):
    figs = []
    monkeypatch.setattr(report, "write_figure_atomic", lambda fig, path, dpi: figs.append(fig))
    return figs


def test_parity_panels_in_rows_with_units_and_the_data_setting_the_scale(monkeypatch):
    figs = _captured(monkeypatch)
    y = np.linspace(1000.0, 1400.0, 9)
    far = CrossValidation(y, y * 1.01, y * 0.9, np.full(9, 1e31), 0.95, 0.9, 5.0, 0.9)
    names = ["torque"] + [f"{q}_case{k}" for k in range(2) for q in ("pmax", "C_eff", "axial_displacement")]
    units = {"torque": "N*mm", **{f"pmax_case{k}": "MPa" for k in range(2)},
             **{f"C_eff_case{k}": "N" for k in range(2)}, **{f"axial_displacement_case{k}": "mm" for k in range(2)}}
    report.plot_parity({q: far for q in names}, units, "parity.png", "duty cycle ...")
    axes = [ax for ax in figs[0].axes if ax.get_visible()]
    assert len(axes) == 7 and len({round(ax.get_position().y0, 3) for ax in axes}) == 2   # 4 + 3 in two rows
    for ax, q in zip(axes, names):
        assert ax.get_xlabel() == f"simulated {q} [{units[q]}]"
        lo, hi = ax.get_ylim()
        assert lo <= y.min() and hi >= 1.01 * y.max() and hi < 2.0 * y.max()     # the data, not the 1e31 bound


def test_history_numbers_simulations_as_the_report_and_keeps_the_legend_off_the_points(monkeypatch):
    figs = _captured(monkeypatch)

    class Search:
        objective = "torque"
        cycle = [None]
        study = type("S", (), {"name": "s", "load": None})()

        @staticmethod
        def objective_values(vds):
            return vds["torque"].values

    import xarray as xr
    vds = xr.Dataset({"torque": ("design", [5.0, 4.0, 3.0, 6.0]), "feasible": ("design", [False, False, False, False]),
                      "source": ("design", ["initial", "initial", "loop", "loop"])})
    vds.torque.attrs["units"] = "N*mm"
    monkeypatch.setattr(report, "load_case_label", lambda study: "Fa 4.5 kN")
    report.plot_history(Search, vds, [], "history.png")
    fig = figs[0]
    ax = fig.axes[0]
    xs = np.concatenate([line.get_xdata() for line in ax.lines if line.get_marker() == "o"])
    assert sorted(xs) == [0, 1, 2, 3]                    # design indices, as "simulation #i" in the report
    assert not ax.get_legend() and fig.legends            # the legend is the figure's, beside the axes
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "verified best" not in labels                  # nothing feasible: no such line, no such entry


def test_the_cross_validation_table_flags_coverage_outside_the_target():
    """Issue 16 item 1: 95 % intervals should cover 0.92-0.98 of the points in cross-validation.
    The report printed 0.831-0.913 without a word (session 32, an independent check); each output
    now carries met / below / above, and a line names those outside."""
    y = np.linspace(1.0, 2.0, 60)
    cv = {name: CrossValidation(y, y, y - 0.1, y + 0.1, 0.95, 0.99, 0.01, coverage)
          for name, coverage in (("torque", 0.95), ("pmax", 0.92), ("edge_stress_margin", 0.842), ("L10", 0.99))}
    text = report.cv_table(cv)
    rows = {line.split("|")[1].strip(): line for line in text.splitlines() if line.startswith("| ") and "---" not in line}
    assert rows["torque"].endswith("0.92-0.98: met |") and rows["pmax"].endswith("0.92-0.98: met |")
    assert rows["edge_stress_margin"].endswith("below |") and rows["L10"].endswith("above |")
    assert "Coverage outside the target" in text and "edge_stress_margin 0.842, L10 0.990" in text


def test_an_infeasible_local_stage_names_what_it_violates_and_claims_nothing_of_the_bounds():
    """An infeasible end of the local stage (an independent check of session 32: "Active constraints:
    edge_stress" while pmax was violated, and "widening the range may lower the objective" of a point
    that meets no constraint set): the violated margins are named with their values, and the bounds
    are not read as the optimum's place; a feasible end keeps the bound statement."""
    from types import SimpleNamespace

    from studies.refine import LocalResult

    def text(margins):
        L = LocalResult(u=np.array([1.0, 0.5]), value=5610.1, margins=np.array(margins), start_value=5700.0,
                        evaluations=30, message="Maximum number of function evaluations", runs=1,
                        active_constraints=["edge_stress"], active_bounds=[(0, "high")])
        search = SimpleNamespace(local=L, study=SimpleNamespace(bounds={"PCR": [28.0, 170.0], "kappa": [0.9, 0.995]}),
                                 space=SimpleNamespace(names=["PCR", "kappa"]), objective="torque",
                                 limits=SimpleNamespace(names=["simulation", "pmax", "edge_stress"]))
        return report.local_stage_text(search)

    bad = text([-1.0, 0.004, 0.0])
    assert "INFEASIBLE" in bad and "Violated constraints (margin > 0): pmax +0.004." in bad
    assert "widening the range" not in bad and "say nothing about where the optimum lies" in bad
    good = text([-1.0, -0.01, 0.0])
    assert "Violated" not in good and "PCR at its high bound 170" in good and "widening the range" in good

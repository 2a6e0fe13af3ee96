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

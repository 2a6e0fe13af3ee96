"""Load grids (sim.api.cases): full factorial, zipped lists, refused grids, and the thesis grids of conf/load."""
import pytest
from omegaconf import OmegaConf

import sim
from sim.api.cases import operating_points
from sim.api import InputError


def cases(**load):
    base = {"Fa": 4000.0, "Fr": 0.0, "speed": 2000.0, "tilt": 0.0, "oil_temperature": 55.0}
    return [o.values()
            for o in operating_points(OmegaConf.create(base | load))]


def test_single_case():
    assert cases() == [(4000.0, 0.0, 2000.0, 0.0, 55.0)]


def test_lists_combine_as_full_factorial_last_key_fastest():
    got = cases(Fa=[1000, 2000], speed=[1000, 4000])
    assert [(c[0], c[2]) for c in got] == [(1000, 1000), (1000, 4000), (2000, 1000), (2000, 4000)]


def test_zipped_lists_pair_up_and_cross_the_rest():
    """(Fa, Fr) pairs as one factor in Fa's place, crossed with the speeds (Figs. 7.19, 7.20 layout)."""
    got = cases(Fa=[4000, 7000], Fr=[2000, 0], speed=[1000, 2000], zip=[["Fa", "Fr"]])
    assert [(c[0], c[1], c[2]) for c in got] == [(4000, 2000, 1000), (4000, 2000, 2000),
                                                 (7000, 0, 1000), (7000, 0, 2000)]
    assert cases(Fa=[4000, 7000], Fr=500.0, zip=[["Fa", "Fr"]])[1][:2] == (7000, 500.0)  # a number repeats


@pytest.mark.parametrize("load, message", [
    ({"Fa": [1000, 2000], "Fr": [0, 1, 2], "zip": [["Fa", "Fr"]]}, r"load\.zip \['Fa', 'Fr'\]: zipped lists need equal lengths"),
    ({"Fa": [1000, 1000]}, r"load: the grid holds the case .* more than once"),
    ({"zip": [["Fa", "Fx"]]}, r"load\.zip names 'Fx'"),
    ({"Fa": "abc"}, r"load\.Fa = 'abc' is not a number"),
    ({"Fa": []}, r"load\.Fa is an empty list"),
    ({"Fa": [1000, -1]}, r"load\.Fa = -1 is outside the allowed range: a number in \(0, 1e\+07\] N \(per bearing, the equivalent "
                        r"static load P0 is bounded by solver\.max_static_load_ratio x C0\)$"),
])
def test_impossible_grids_are_refused_naming_the_key(load, message):
    with pytest.raises(InputError, match=message):
        cases(**load)


def grid(name):
    return [o.values()[:4] for o in operating_points(sim.load_config([f"load={name}"]).load)]


def test_thesis_grids():
    """The ready grids hold the cases their comments cite (thesis 6.3, 7.2, 7.4)."""
    assert len(grid("test_rig_table_6_3")) == 50                          # Table 6.3 envelope, 5 x 5 x 2
    fig_6_5 = grid("test_rig_fig_6_5")                                    # Fr 0/2/4 kN at Fa 3 and 4.5 kN, Fa sweep
    assert {(c[0], c[1]) for c in fig_6_5} == {(3000, 0), (3000, 2000), (3000, 4000), (4500, 0), (4500, 2000),
                                               (4500, 4000), (1500, 0)}
    assert {c[1] for c in grid("test_rig_fig_6_9")} == {0, 2000, 4000, 5000} and {c[0] for c in grid("test_rig_fig_6_9")} == {4500}
    assert sorted({c[3] for c in grid("test_rig_fig_6_10")}) == [0.0, 0.0417, 0.25, 0.5]
    scenarios = [(c[0], c[1]) for c in grid("sensitivity_scenarios")]
    assert scenarios == [(4000, 0), (4000, 2000), (4000, 4000), (4000, 6000), (7000, 0), (10000, 0)]
    speeds = grid("sensitivity_speeds")                                  # scenario by scenario, speed fastest
    assert [(c[0], c[1]) for c in speeds[::3]] == scenarios and [c[2] for c in speeds[:3]] == [1000, 2000, 4000]
    assert grid("high_axial_load") == [(4500, 0, 2000, 0), (40000, 0, 2000, 0)]
    pinion = grid("pinion_duty")                                          # 15-60 kN x 550-1600 rpm with the design point
    assert min(c[0] for c in pinion) == 15000 and max(c[0] for c in pinion) == 60000
    assert {c[2] for c in pinion} == {550, 1100, 1600} and (35000, 0, 1100, 0) in pinion

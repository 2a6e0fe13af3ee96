"""Edge pressure peaks with a finite roller corner (issue 14 item 6, the thesis 7.2 pmax directions):
prints the table of docs/edge_peak_corner.md.

    python docs/figures/edge_peak_corner.py            # ~6 min on one core

Question: the slice model's pmax cannot hold the pressure peak of a contact that runs onto the
sharp end of Lwe (singular, growing with the slice count: tests/published/test_edge_stress.py).
A real roller ends in a corner radius r_c, which makes the peak finite. Do the thesis's pmax
directions of section 7.2 (thesis_data.yaml sensitivity_directions) come out when pmax includes
that finite peak?

Method (a sub-model of the solved state; nothing in sim/ is changed): for each case of
tests/friction/test_torque.py (tsrb_reference and its Table 7.2 variants at Fa/Fr 4/0 and 4/4 kN)
the quasi-static solution gives the pose of the most loaded roller. Its outer-raceway contact is
then solved again by the 2-D half-space reference solver (sim.physics.halfspace: Boussinesq
influence coefficients of uniform rectangles, Love 1929; conjugate-gradient complementarity
solve, Polonsky & Keer 1999) on a grid of GRID_PER_MM cells per mm along the roller and
GRID_ACROSS cells over 5 Hertz half-widths across it, with the same contact load (the slice
model's). The rigid gap is the exact one of the slice kernel (sim.physics.contact.
slice_contact_meridian) at every grid column; beyond each end of Lwe the generatrix is continued
by its tangent and dropped by a corner circle of radius r_c tangent to it,
r_c - sqrt(r_c^2 - s^2) at a distance s past the end (the roller's edge radius: thesis Table A.2
gives r_k = 0.8 mm for the TRB 32208 roller, thesis 5.5.1 the flat roller face with edge radius r_k;
the TSRB roller of the same size is given none, so 0.5 and 1.0 mm are run beside it). The radius of
relative curvature across the roller is the slice model's R_eq, interpolated.

Grid convergence (printed first): the peak at 80 and 160 cells per mm differs by about 1 % for
r_c = 1.0 mm and 3 % for r_c = 0.5 mm (reference, 4/4 kN); the table uses 80.
"""
import functools

import numpy as np

import sim
from sim.api.simulation import build_model
from tests.friction.test_torque import DIRECTIONS, SCENARIOS, VARIANTS
from tests.helpers import case, halfspace_contact_peak

CORNER_RADII = (0.5, 0.8, 1.0)  # mm, roller corner radii: thesis Table A.2's r_k = 0.8 mm (the edge radius of the
                                # TRB 32208 roller, whose size the reference TSRB keeps) and 0.5 / 1.0 around it
GRID_PER_MM = 80              # cells per mm along the roller (convergence: module docstring)
GRID_ACROSS = 40              # cells across the contact


@functools.lru_cache(maxsize=None)
def solved(overrides, Fa, Fr):
    """(model, quasi-static solution, most loaded roller) of tsrb_reference with ``overrides`` (a
    tuple), solved once for every corner radius and grid."""
    model = build_model(sim.load_config(["bearing=tsrb_reference", *overrides]))
    raw = model.solve(case(Fa, Fr))
    return model, raw, int(np.argmax(raw["Q"].sum(axis=1)))


def outer_contact_peak(overrides, Fa, Fr, r_c, per_mm=GRID_PER_MM):
    """(slice-model pmax [MPa], half-space peak [MPa], its x from mid-roller [mm]) of the most
    loaded roller's outer contact (tests.helpers.halfspace_contact_peak)."""
    model, raw, j = solved(tuple(overrides), Fa, Fr)
    peak, x = halfspace_contact_peak(model, raw, j, 0, r_c, per_mm, GRID_ACROSS)
    return float(raw["pressure"][j, 0].max()), peak, x


def main():
    print("grid convergence, reference 4/4 kN: peak [MPa] at 80 / 160 cells per mm")
    for r_c in CORNER_RADII:
        peaks = [outer_contact_peak([], 4000.0, 4000.0, r_c, n)[1] for n in (GRID_PER_MM, 2 * GRID_PER_MM)]
        print(f"  r_c {r_c} mm: {peaks[0]:.0f} / {peaks[1]:.0f} ({peaks[1] / peaks[0] - 1:+.1%})")
    print("\n| scenario | variant | thesis | slice pmax [MPa] | sign | "
          + " | ".join(f"peak r_c {r} mm [MPa] (x) | sign" for r in CORNER_RADII) + " |")
    print("| --- " * (5 + 2 * len(CORNER_RADII)) + "|")
    for scenario, (Fa, Fr) in SCENARIOS.items():
        ref = {r: outer_contact_peak([], Fa, Fr, r) for r in CORNER_RADII}
        for variant, directions in DIRECTIONS.items():
            if "pmax" not in directions:
                continue
            want = directions["pmax"]
            cells = []
            for r in CORNER_RADII:
                sl, peak, xp = outer_contact_peak(VARIANTS[variant], Fa, Fr, r)
                cells.append(f"{peak:.0f} ({xp:+.2f}) | {_sign(peak / ref[r][1] - 1.0, want)}")
            print(f"| {scenario} | {variant} | {want:+d} | {sl:.0f} (ref {ref[CORNER_RADII[0]][0]:.0f}) | "
                  f"{_sign(sl / ref[CORNER_RADII[0]][0] - 1.0, want)} | " + " | ".join(cells) + " |")


def _sign(change, want):
    """The change [1] and whether it has the thesis's direction (0: |change| < 10 %, as the tests)."""
    ok = abs(change) < 0.1 if want == 0 else change * want > 0.0
    return f"{change:+.1%} {'yes' if ok else 'no'}"


if __name__ == "__main__":
    main()

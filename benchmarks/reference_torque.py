"""TRB 32208 torque from the published reference models against this model (issue 14 items 3, 8).

    python benchmarks/reference_torque.py            # ~30 s (plus numba compile on a fresh cache)
    python benchmarks/reference_torque.py --no-model # reference models only, instant

Conditions of the thesis's rig (6.3, 7.2.5): pure axial load, inner ring 2000 rpm, FVA 3 at
55 degC (viscosity, density, temperature-viscosity coefficient from conf/lubricant/fva3.yaml via
sim.physics.lubricant). Loads Fa = 1.5, 3, 4.5, 10, 20, 40 kN. Prints each model's torque [N mm], the
exponent n of torque ~ Fa^n fitted over 4.5-40 kN, and Aihara's rib term against Fa.

Inputs of the reference models (sim/physics/reference_models.py, sources there; prepared by
studies.validation.reference_torques, which the validation report uses too):
* SKF 2004: d 40, D 80, Y 1.6 (SKF 32208 J2/Q catalogue), series-322 constants, fully flooded
  (K_rs = 0), mu_bl 0.15, mu_EHL 0.002; seals and drag not included.
* Aihara 1987 (transcription, unverified): rollers, radii, cup angle and equivalent radii from
  this project's trb_32208 geometry; rolling speed from rolling kinematics (2.20); E' = E/(1-nu^2)
  of conf/material/steel. The rib term needs e, beta and the rib film parameter Lambda_r, which
  the transcription does not define: printed for e = 1.5 mm (our ASSUMED rib contact height
  0.15 Dwe), cos(beta) = 1 and Lambda_r = 0 (boundary: upper bound) and 1 -- it is linear in Fa
  at a fixed Lambda_r, whatever e and beta are.
* Timken: formula not found; not computed.
"""
import math
import sys

import numpy as np

import sim
from sim.api import torque_exponent
from studies.validation import reference_torques

LOADS = [1500.0, 3000.0, 4500.0, 10000.0, 20000.0, 40000.0]   # N
SPEED = 2000.0        # rpm, inner ring
TEMPERATURE = 55.0    # degC
FIT = slice(2, None)  # 4.5-40 kN


def main(run_model=True):
    ref = reference_torques(LOADS, temperature=TEMPERATURE, speed=SPEED)   # inputs prepared in studies.validation
    x = ref["inputs"]
    print(f"FVA 3 at {TEMPERATURE:g} degC: nu {x['nu']:.2f} mm^2/s, eta0 {x['eta0'] * 1e3:.2f} mPa s, "
          f"beta {x['beta_T']:.4f} 1/K; 32208 cup angle {math.degrees(x['cup_angle']):.2f} deg")
    aih = list(ref["aihara_rolling"])
    rib0, rib1 = (list(ref["aihara_rib"][:, k]) for k in (0, 1))   # Lambda_r = 0 and 1 (studies.validation.RIB_FILM)

    ours, ours_rib = [np.nan] * len(LOADS), [np.nan] * len(LOADS)
    if run_model:
        grid = "[" + ",".join(f"{Fa:g}" for Fa in LOADS) + "]"
        ds = sim.simulate(sim.load_config(["bearing=trb_32208", f"load.Fa={grid}", "load.Fr=0", f"load.speed={SPEED}",
                                           f"load.oil_temperature={TEMPERATURE}"]))
        ours = [float(v) for v in ds.torque.isel(design=0).values]
        ours_rib = [float(v) for v in ds.torque_component.sel(component="rib").isel(design=0).values]

    cols = {
        "SKF rolling": list(ref["skf_rolling"]), "SKF sliding": list(ref["skf_sliding"]),
        "SKF total": list(ref["skf"]), "Aihara rolling": aih,
        "Aihara rib, L_r=0": rib0, "Aihara rib, L_r=1": rib1,
        "Aihara rolling+rib(L_r=1)": [a + b for a, b in zip(aih, rib1)],
        "this model": ours, "this model, rib": ours_rib,
    }
    print("\nTorque [N mm], TRB 32208, pure axial, 2000 rpm, FVA 3 at 55 degC (thesis: ~650 at 4.5 kN, ~1100 at 40 kN)")
    print("| Fa [kN] | " + " | ".join(cols) + " |")
    print("| --- " * (len(cols) + 1) + "|")
    for k, Fa in enumerate(LOADS):
        print(f"| {Fa / 1e3:g} | " + " | ".join(f"{v[k]:.1f}" for v in cols.values()) + " |")
    Fa_fit = LOADS[FIT]
    print("| n (4.5-40 kN) | " + " | ".join(
        f"{torque_exponent(Fa_fit, v[FIT]):.3f}" if np.all(np.isfinite(v[FIT])) else "-" for v in cols.values()) + " |")
    print(f"\nthesis 7.2.5 (its rig-validated model): 650 -> 1100 N mm, n = {math.log(1100 / 650) / math.log(40 / 4.5):.3f}")
    sys.stdout.flush()


if __name__ == "__main__":
    main(run_model="--no-model" not in sys.argv)

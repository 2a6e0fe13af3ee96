"""Command line: simulate one bearing and write ``result.nc`` in Hydra's run directory.

    python -m sim.run bearing=tsrb_reference load.Fa=4500 load.Fr=2000 load.speed=2000 load.tilt=0

Any ``bearing.<param>=`` override works too (e.g. ``bearing.PCR=120``).
"""
import sys
from pathlib import Path

import hydra
from hydra.core.hydra_config import HydraConfig
from omegaconf import DictConfig

from sim.io import write_netcdf_atomic
from sim.simulation import simulate


def summary(ds):
    """Short human-readable summary of a single-design result [pmax MPa, displacement mm]."""
    lines = []
    b = str(ds.bearing_type.values[0])
    for c in range(ds.sizes["case"]):
        case = ds.isel(design=0, case=c)
        head = (f"{b}  Fa={float(case.Fa):.0f} N  Fr={float(case.Fr):.0f} N  "
                f"n={float(case.speed):.0f} rpm  tilt={float(case.tilt):.3f} deg")
        if not bool(case.converged):
            lines.append(f"{head}\n  NOT CONVERGED after {int(case.iterations)} iterations")
            continue
        lines.append(
            f"{head}\n"
            f"  pmax outer/inner      {float(case.pmax.sel(race='outer')):8.0f} / {float(case.pmax.sel(race='inner')):.0f} MPa\n"
            f"  roller axial disp.    {float(case.axial_displacement) * 1e3:8.2f} um (rel. to inner ring, + to large end)\n"
            f"  contact length ratio  {float(case.contact_length_ratio.sel(race='outer')):8.2f} / "
            f"{float(case.contact_length_ratio.sel(race='inner')):.2f} (outer/inner)\n"
            f"  L_eff, C_eff, L10     {float(case.L_eff):8.2f} mm, {float(case.C_eff) / 1e3:.1f} kN, {float(case.L10):.3g} 1e6 rev\n"
            f"  edge stress           {bool(case.edge_stress)}\n"
            f"  converged             True in {int(case.iterations)} iterations, {float(case.wall_time) * 1e3:.1f} ms")
    return "\n".join(lines)


@hydra.main(config_path="../conf", config_name="config", version_base="1.3")
def main(cfg: DictConfig) -> None:
    ds = simulate(cfg)
    out = Path(HydraConfig.get().runtime.output_dir) / cfg.output.file
    write_netcdf_atomic(ds, out)
    print(summary(ds))
    print(f"written: {out}")
    if not bool(ds.converged.all()):
        print("some cases did not converge (written with converged = False)", file=sys.stderr)
        raise SystemExit(1)


if __name__ == "__main__":
    main()

"""Multibody simulation core for tapered spherical (TSRB) and tapered roller bearings (TRB).

Entry points:
- :func:`load_config` composes ``conf/`` like the command line does;
- :func:`simulate` runs a composed config and returns the result Dataset (DATA.md).
"""
from pathlib import Path

CONF_DIR = Path(__file__).resolve().parent.parent / "conf"


def load_config(overrides=None):
    """Compose the project config with Hydra overrides, as ``python -m sim.run`` does.

    Parameters
    ----------
    overrides : list of str, optional
        Hydra overrides, e.g. ``["bearing=trb_32208", "load.Fa=4500"]``.

    Returns
    -------
    omegaconf.DictConfig

    Raises
    ------
    sim.errors.ConfigError
        An override that does not compose (a malformed override, a value of the wrong type for
        a typed key such as ``friction.enabled=abc``, an unknown config file), with Hydra's reason.
    """
    from hydra import compose, initialize_config_dir
    from hydra.core.global_hydra import GlobalHydra
    from hydra.errors import ConfigCompositionException, OverrideParseException

    import sim.api.schema  # noqa: F401  registers the group schemas that conf/config.yaml composes
    from sim.errors import ConfigError

    if GlobalHydra.instance().is_initialized():
        GlobalHydra.instance().clear()
    with initialize_config_dir(config_dir=str(CONF_DIR), version_base="1.3"):
        try:
            return compose(config_name="config", overrides=list(overrides or []))
        except (ConfigCompositionException, OverrideParseException) as exc:
            reason = f": {exc.__cause__}" if exc.__cause__ is not None else ""
            raise ConfigError(f"{exc}{reason}") from exc


def simulate(cfg):
    """Simulate a composed config; see :func:`sim.api.simulation.simulate`."""
    from sim.api.simulation import simulate as _simulate

    return _simulate(cfg)


__all__ = ["load_config", "simulate", "CONF_DIR"]

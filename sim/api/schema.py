"""Structured-config schemas of ``conf/`` (Hydra ConfigStore) and the range check at start.

The schemas themselves, every key's type and range, are :mod:`sim.config_schema` (the bottom
layer, so that the constructors of :mod:`sim.geometry` and :mod:`sim.physics.lubricant` check
their node against the same bounds); this module registers them with Hydra and checks whole
configs. Its names (Number, Choice, BearingConfig, ..., SCHEMAS) are re-exported here.

``conf/config.yaml`` puts each schema below its group (``- schema/bearing@bearing`` before
``- bearing: tsrb_reference``), so composition (``sim.load_config``, ``python -m sim.run``)
merges the group's YAML onto a dataclass: a key that the schema does not declare, a typo in a
file or an override (``bearing.kapa=0.9``), fails there, naming the key (Hydra lets a key added
with ``+`` through; :func:`validate` refuses it and suggests the declared key).

Values are typed ``Any`` at composition so that they reach the physics modules exactly as
written (``bearing.alpha=0`` stays the int 0 that the refusal prints back) and so that a load
value may be a number or a list (a grid, :mod:`sim.api.cases`). :func:`validate` checks type
and range for a whole composed config and raises one :class:`ConfigError` naming every bad
key, its value and the allowed range. It runs before anything else in ``python -m sim.run``
(through :class:`sim.api.sweep.SweepCallback`, for every point of a multirun before the first
job starts), :func:`sim.api.simulation.simulate` and :func:`sim.api.simulation.build_model`.
Combined feasibility (a roller that does not fit, aPk + aP >= Lwe) stays with
:mod:`sim.geometry` and fails the point, not the sweep.
"""
import hashlib

from hydra.core.config_store import ConfigStore
from omegaconf import DictConfig, OmegaConf

from sim.api.cases import operating_points
from sim.config_schema import (MISSING, SCHEMAS, BearingConfig, Choice, DragConfig, Flag,  # noqa: F401  re-exported
                               FrictionConfig, LoadConfig, LubricantConfig, MaterialConfig, Number, OutputConfig,
                               SolverConfig, SurfaceConfig, Text, key, mm, node_problems, not_a_key)
from sim.errors import ConfigError, InputError

for _group, _node in SCHEMAS.items():
    ConfigStore.instance().store(group="schema", name=_group, node=_node)

# A run folder's name (conf/config.yaml, hydra.run.dir) holds the command's overrides: at most this many bytes
# of them. Linux allows 255 bytes per name; a report's re-simulation command with full-precision values ran to 271
# and failed to make its folder (session 32, an independent check).
RUN_FOLDER_OVERRIDES_BYTES = 120
RUN_FOLDER_HASH_CHARS = 12


def run_folder_name(overrides):
    """The overrides part of a run folder's name (``${run_folder_name:${hydra.job.override_dirname}}``):
    the overrides themselves when they fit in RUN_FOLDER_OVERRIDES_BYTES, else their start and a hash of all
    of them (sha1, RUN_FOLDER_HASH_CHARS hex digits), so that two long commands keep apart."""
    text = str(overrides)
    raw = text.encode()
    if len(raw) <= RUN_FOLDER_OVERRIDES_BYTES:
        return text
    digest = hashlib.sha1(raw).hexdigest()[:RUN_FOLDER_HASH_CHARS]
    head = raw[:RUN_FOLDER_OVERRIDES_BYTES - RUN_FOLDER_HASH_CHARS - 1].decode(errors="ignore")
    return f"{head}_{digest}"


OmegaConf.register_new_resolver("run_folder_name", run_folder_name, replace=True)


# ---------------------------------------------------------------------------- validation
def validate(cfg):
    """Check every value of a composed config against its schema (type, range, bearing type).

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed config (the ``hydra`` node, if present, is ignored).

    Raises
    ------
    ConfigError
        Listing every offending key as ``group.key = value is outside the allowed range: ...``,
        and a load grid that cannot be formed (:func:`sim.api.cases.operating_points`).
    """
    bearing_type = OmegaConf.select(cfg, "bearing.type")
    problems = []
    for group, schema in SCHEMAS.items():
        node = cfg.get(group)
        if isinstance(node, DictConfig):  # plain values; "???" where composition left one missing
            node = OmegaConf.to_container(node, resolve=True, throw_on_missing=False)
        problems += node_problems(schema, node, group, bearing_type=bearing_type, strict=True)
    if OmegaConf.select(cfg, "friction.cage_guidance") == "free" and OmegaConf.select(cfg, "friction.kinematics") == "rolling":
        # free rollers are solved from the traction balance (sim.solvers.kinematics.free_roller_speeds),
        # which rolling kinematics replace: the option would have no effect
        problems.append("friction.kinematics = rolling imposes every roller's and the cage's speed ((2.20), (2.22)): "
                        "a rigid cage; set friction.cage_guidance = rigid with it (friction.cage_guidance = free, the "
                        "default, needs friction.kinematics = traction)")
    if not any(p.startswith("load.") for p in problems):
        try:
            operating_points(cfg.load)  # zipped lengths, repeated cases
        except InputError as exc:
            problems.append(str(exc))
    if problems:
        raise ConfigError("\n".join(problems))

"""Design searches over TSRB geometry (issue 5): Optuna on GP surrogates, verified by the full simulation.

Entry point: ``python -m studies.optimize`` (see :mod:`studies.optimize`). Modules:
:mod:`studies.config` (composition, validation), :mod:`studies.space` (design space),
:mod:`studies.evaluate` (full simulations, NetCDF records), :mod:`studies.constraints`
(normalised margins), :mod:`studies.search` (Optuna ask-and-tell, storage, resume),
:mod:`studies.loop` (the verification loop), :mod:`studies.report` (tables, plots, NetCDF).
The sensitivity analysis of thesis 7.2 lives beside them in ``studies.sensitivity*``.
"""

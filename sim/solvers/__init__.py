"""Solver layer: unknowns, residuals, Jacobians and iterations over the physics kernels
(:mod:`quasi_static` load distribution, :mod:`kinematics` roller and cage speeds from the
traction balance). Never imports :mod:`sim.io` or :mod:`sim.api`."""

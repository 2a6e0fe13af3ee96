"""Physics layer: one stateless module per physical topic (contact, elasticity, lubricant, ehl,
kinematics, friction, roller contact frames, ratings; the half-space solver and the catalogue
torque models as references). Imports only :mod:`sim._math`, :mod:`sim.errors` and
:mod:`sim.geometry`."""

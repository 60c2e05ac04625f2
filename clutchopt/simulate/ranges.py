"""The range of every quantity of a start-up (SI, low, high, unit shown): the simulator is tested at the corners of
these ranges (tests/test_hostile.py, tests/test_hostile_sim.py); far outside them float64 products such as J w^2 or
k e^{a w} stop meaning anything. Scenes and case files refuse values outside them field by field; a model built
otherwise (a case's start-up at a design) is refused by :func:`clutchopt.simulate.engine.simulate` as a whole.

A module of its own, importing nothing, so that reading a case file checks these ranges without loading the
integrators (SciPy's and pandas' imports cost most of a second).
"""

INERTIA = (1e-9, 1e9, "kg*m^2")
TORQUE = (1e-9, 1e9, "N*m")
LOAD = (0.0, 1e9, "N*m")
SPEED = (1e-3, 1e5, "rad/s")
TIME = (1e-9, 1e9, "s")
SLIP_SCALE = (-1e6, 1e6, "s/rad")
FORCE = (0.0, 1e9, "N")
HEAT_CAPACITY = (1e-6, 1e12, "J/K")
CONDUCTANCE = (0.0, 1e12, "W/K")
BREAKDOWN_SLIP = (1e-6, 0.99, "")
TOLERANCE = (1e-14, 1e-3, "")

"""The solver tolerance every design command solves at unless ``--tol`` says otherwise, defined once.

`solve`, `sweep`, `pareto`, `compare`, `report` and the Python API (``SolverOptions``, ``Sweep``) all take this
one value, so a point of a sweep (nominal or ``--robust``) is solved exactly as `solve` solves it alone: the same
IPOPT and SQP stopping rule, hence the same design to round-off and, for ``--robust chance=P``, the same Monte Carlo
verdict even for a design whose estimate lies on its target (tests/test_robust_sweep_agrees.py). Kept out of
``clutchopt.optimise`` so that the command line reads it without importing CasADi.
"""

SOLVER_TOL = 1e-10  # IPOPT's tol and constr_viol_tol, 100x it acceptable (SolverOptions.ipopt)
TOLERANCE_RANGE = (1e-14, 1e-2)  # IPOPT's tol: below 1e-14 float64 cannot follow, above 1e-2 is no optimum

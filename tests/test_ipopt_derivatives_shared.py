"""A problem's warm IPOPT solvers take the derivatives of its first one (``Posed.ipopt_derivatives``): the objective's
gradient, the constraints' Jacobian and the Lagrangian's Hessian are CasADi functions of the NLP alone, whatever
IPOPT's options, so a solver built with other options (``warm``, ``warm_near``) is handed them instead of deriving
its own (wedge_motor_start: 41 ms of CasADi's derivation a solver, two solvers a start-up sweep). Shown on the wedge's
static sizing (small and quick); the start-up problems build theirs the same way (``Posed.solver``)."""

import casadi as ca
import numpy as np

from clutchopt.cases import load_case
from clutchopt.optimise.attempts import warm_multipliers
from clutchopt.optimise.problem import Problem, case_formulation
from conftest import CASES

DERIVATIVES = ("nlp_grad_f", "nlp_jac_g", "nlp_hess_l")  # the functions IPOPT evaluates beside f and g


def test_a_warm_solver_evaluates_the_first_solvers_derivatives_and_solves_to_the_same_bits():
    case = load_case(CASES / "wedge_paper.toml")
    posed = Problem(case_formulation(case)).posed
    optimum = Problem(case_formulation(case)).solve(case)
    assert optimum.status == "optimal"
    cold, warm = posed.solver("ipopt"), posed.solver("warm")
    for name in DERIVATIVES:  # the very same functions (CasADi's hash: the object's address)
        assert hash(warm.get_function(name)) == hash(cold.get_function(name))
    own = ca.nlpsol("own", "ipopt", posed.nlp, posed.ipopt_options("warm"))  # one that derives its own
    assert hash(own.get_function("nlp_hess_l")) != hash(cold.get_function("nlp_hess_l"))
    # warm from the optimum at 20 % more resisting torque: IPOPT iterates, and both solvers take the same steps
    moved = case.with_values(resisting_torque=1.2 * case.values["resisting_torque"])
    data = posed.scaled_data(moved, optimum.design, optimum.scale)
    lam_x, lam_g = warm_multipliers(posed, *optimum.multipliers)
    args = {"x0": data.x0, "p": data.p, "lbx": data.lbx, "ubx": data.ubx, "lbg": posed.lbg, "ubg": 0.0,
            "lam_x0": lam_x, "lam_g0": lam_g}
    shared, derived = warm(**args), own(**args)
    assert warm.stats()["success"] and warm.stats()["iter_count"] > 0
    assert warm.stats()["iter_count"] == own.stats()["iter_count"]
    for key in ("x", "lam_g", "lam_x", "f"):
        assert np.array_equal(np.array(shared[key]), np.array(derived[key]))  # to the last bit


"""One symbolic differentiation per posed NLP (issue 26): IPOPT's solvers of a problem after the first are built with
its gradient, constraint Jacobian and Lagrangian Hessian (``Posed.derivatives``), and run as solvers that derived
their own; the solvers, the cold one too, are built on first use."""

import casadi as ca
import numpy as np

import clutchopt.optimise.modifier as modifier
import clutchopt.optimise.problem as problem_module
from clutchopt.cases import load_case
from clutchopt.optimise.problem import case_problem, solve_case
from clutchopt.optimise.sparsity import entries
from tests.conftest import CASES


def test_a_warm_solver_evaluates_the_cold_solvers_derivatives_and_runs_as_its_own_would():
    """lever_motor_start solves cold on its first mesh (one solve; its error 8.2e-8 within the tolerance): its warm
    solver evaluates the cold solver's Hessian, Jacobian and gradient (the same CasADi functions), and from the
    solve's own optimum the warm solver and one that derived its own functions end at the same x, multipliers and
    iterations to the last bit."""
    case = load_case(CASES / "lever_motor_start.toml")
    solution = solve_case(case)
    assert solution.status == "optimal" and solution.solver.solves == 1
    posed = case_problem(case).posed
    cold, warm = posed.solver("ipopt"), posed.solver("warm")
    for name in ("nlp_grad_f", "nlp_jac_g", "nlp_hess_l"):
        assert hash(warm.get_function(name)) == hash(cold.get_function(name))  # (the same function object)
    own = ca.nlpsol("own_warm", "ipopt", posed.nlp, posed.ipopt_options("warm"))
    assert hash(own.get_function("nlp_hess_l")) != hash(cold.get_function("nlp_hess_l"))
    data = posed.scaled_data(case, solution.design, solution.scale, solution.internal, solution.mesh[0])
    lam_x, lam_g = solution.multipliers
    args = dict(x0=data.x0, p=data.p, lbx=data.lbx, ubx=data.ubx, lbg=posed.lbg, ubg=0.0, lam_x0=lam_x, lam_g0=lam_g)
    shared, derived = warm(**args), own(**args)
    assert warm.stats()["success"] and warm.stats()["iter_count"] == own.stats()["iter_count"]
    for key in ("x", "lam_x", "lam_g"):
        assert np.array_equal(np.array(shared[key]), np.array(derived[key]))


def test_each_problem_of_a_solve_derives_its_nlp_once(monkeypatch):
    """cable_motor_start (a fresh process's problems) poses two NLPs: the papers' sizing and the start-up; 7 cables'
    unverified design goes on in modifier adaptation, whose step is refuted before it is solved (its corrected row
    admits no design lighter than 8 cables' 3.952573 kg: ``modifier.no_lighter``), so the modifiers' problem is not
    built. Solved (the refutation turned off), the step poses a third (one step, heavier than 8 cables'). Each is
    differentiated once: the start-up's warm_near solver is built with its cold solver's functions, and the
    modifiers' problem, which solves warm only, builds no cold solver (it derived one it never ran); so is the sizing's
warm solver, for its re-solve scaled by its first optimum. (The start-up's
    warm solver is no longer built: its one warm solve, the relaxation at 7 cables' moved limit, is not solved since 8
    cables are solved first at the case's limit, ``Problem._one_up_first``.)"""
    case = load_case(CASES / "cable_motor_start.toml")

    def built_in_a_fresh_process(patched) -> list:
        patched.setattr(problem_module, "_CACHE", {})
        built, nlpsol = [], ca.nlpsol
        patched.setattr(ca, "nlpsol", lambda name, plugin, nlp, options: built.append(
            (name, "hess_lag" in options)) or nlpsol(name, plugin, nlp, options))
        solution = solve_case(case)
        assert solution.status == "optimal" and solution.design["cable_count"] == 8
        assert abs(solution.objective / 3.952572919154992 - 1) < 1e-12
        return built

    with monkeypatch.context() as patched:
        built = built_in_a_fresh_process(patched)
        assert [name for name, shared in built if not shared] == ["cable_paper_mass", "cable_paper_mass"]
        assert [key for key in problem_module._CACHE if "modifier" in key[2]] == []
    monkeypatch.setattr(modifier, "no_lighter", lambda *args: [])
    built = built_in_a_fresh_process(monkeypatch)
    derived = [name for name, shared in built if not shared]
    assert derived == ["cable_paper_mass", "cable_paper_mass", "cable_paper_mass_warm_near"]  # sizing, start-up,
    # modifiers' (a solver is named by coupling, mode, objective and method)
    assert sorted(name for name, shared in built if shared) == ["cable_paper_mass_warm", "cable_paper_mass_warm_near"]
    # (the sizing's, its re-solve scaled by its first optimum warm from it: problem.rescaled_seed)
    assert len([key for key in problem_module._CACHE if "modifier" in key[2]]) == 1
    modified = case_problem(case).modified_problem.posed
    assert "ipopt" not in modified._built["solver"] and "warm_near" in modified._built["solver"]


def test_a_patterns_entries_are_where_its_dense_matrix_of_ones_is_one():
    """``entries`` reads a sparsity's triplets: on a 3 x 4 pattern with entries at (0, 1), (2, 0) and (2, 3), and on
    the constraint Jacobian of every motor_start case's start-up problem (which rows no design enters: ``fixed_rows``),
    the same booleans as a dense matrix of ones made of it."""
    pattern = ca.Sparsity.triplet(3, 4, [0, 2, 2], [1, 0, 3])
    expected = np.zeros((3, 4), dtype=bool)
    expected[0, 1] = expected[2, 0] = expected[2, 3] = True
    assert np.array_equal(entries(pattern), expected)
    for name in ("wedge", "lever", "ball", "cable"):
        posed = case_problem(load_case(CASES / f"{name}_motor_start.toml")).posed
        jacobian = ca.jacobian(posed.nlp["g"][: posed.n_ineq], posed.nlp["x"]).sparsity()
        assert np.array_equal(posed.row_depends, np.array(ca.DM(jacobian, 1)) != 0)

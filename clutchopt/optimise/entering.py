"""What a posed problem depends on: a quantity that a command varies or scatters must enter the problem, or the
command refuses it by name (a sweep over a quantity that does not enter gives the same design at every point)."""

from __future__ import annotations

import functools
import math

import casadi as ca
import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError, Problems
from clutchopt.model import ElasticLaw, namespace
from clutchopt.start_up.section import DEFAULTS_FROM_DUTY


@functools.lru_cache(maxsize=64)  # built problems are kept (problem_for): each is looked at once
def entering(problem, objective: bool = True) -> frozenset[str]:
    """The case quantities the posed NLP's constraints or (``objective``) its objective depend on."""
    quantities = problem.formulation.quantities
    nlp = problem.posed.nlp
    rows = ca.vertcat(nlp["f"], nlp["g"]) if objective else nlp["g"]
    used = np.diff(ca.jacobian_sparsity(rows, nlp["p"][: len(quantities)]).colind()) > 0
    return frozenset(q.name for q, enters in zip(quantities, used) if enters)


def check_entering(case: Case, problem, names, field: str, objective: bool = True) -> None:
    """Refuse, each by name, the quantities among ``names`` that do not enter the problem posed for ``case``: not in
    its constraints or (``objective``) its objective, nor a design variable the case fixes at its value, nor the
    source of a default that enters (the driven inertia that follows the duty's), nor what only an elastic link's
    simulated start reads (:func:`simulated_only`; a robust start-up design simulates its corners too, review h17:
    cable_motor_start with its damping scattered over 0.05-0.15 is designed with 11 cables, as ``solve`` at 0.05,
    not the nominal 8). ``field``: how an error names one, ``"--vary {}"``; a scatter takes ``objective=False``: a
    robust design keeps its objective at the nominal values, so a quantity only the objective depends on would leave
    it the nominal design."""
    variables = {v.name: v for v in problem.formulation.variables}
    fixed = {name for name, v in variables.items() if v.fixed_unless_freed and name not in case.free}
    entered = entering(problem, objective) | fixed | simulated_only(case, problem)
    entered |= {source for name, (source, _) in case.follows.items() if name in entered}  # through its defaults
    if _profiled(case):  # (its load_torque the profile's largest value: the motor's breakdown check reads it, the
        entered -= {"load_torque"}  # simulated start the profile, so a design would not move with it)
    problems = Problems()
    for name in names:
        if name not in entered:
            with problems.field():
                raise InputError(field.format(name), _why_not(case, problem, name, name in variables, field))
    problems.raise_any()


def simulated_only(case: Case, problem) -> frozenset[str]:
    """The case quantities an elastic link's simulated start reads that its NLP does not: the link's damping ratio
    (the NLP takes the link as quasi-static). The defect correction moves the stress limit by the oscillation that
    start finds, so the design moves with them (cable_motor_start: 9 cables at damping 0.07, 8 at 0.1, 7 at 0.2)."""
    law = problem.formulation.speed_law
    if case.start_up is None or not isinstance(law, ElasticLaw):
        return frozenset()
    x = namespace({v.name: ca.SX.sym(v.name) for v in problem.formulation.variables})
    p = namespace({q.name: ca.SX.sym(q.name) for q in problem.formulation.quantities})
    return frozenset(s.name() for s in ca.symvar(ca.SX(law.damping_ratio(x, p)))) & set(vars(p))


def _profiled(case: Case) -> bool:
    """Whether the case's driven machine has a load profile (``[start_up.driven.load_profile]``)."""
    return case.start_up is not None and case.start_up.load_profile is not None


def _why_not(case: Case, problem, name: str, variable: bool, field: str) -> str:
    declared = {q.name: q for q in case.quantities}
    if name == "load_torque" and _profiled(case):
        return (f"this case's [start_up.driven.load_profile] gives the driven machine's load, and load_torque is its "
                f"largest value ({declared[name].show(case.values[name])}), not a quantity of its own: every simulated "
                f"start would be the same; scale the profile's torques in the case instead")
    own = [follower for follower, source in DEFAULTS_FROM_DUTY.items()
           if source == name and follower in case.values and follower not in case.follows]
    if own:
        quantity = declared[own[0]]
        return (f"this case's start-up gives its own {own[0]} ({quantity.show(case.values[own[0]])}), so {name} does "
                f"not enter the problem; vary {own[0]}" if field.startswith("--vary") else
                f"{own[0]} is given here ({quantity.show(case.values[own[0]])}: by the case, or by what this command "
                f"varies), so {name} does not enter the problem; scatter {own[0]} instead")
    mode = problem.formulation.mode
    if name in entering(problem):  # the objective only
        return (f"only the {problem.objective.name} objective depends on it, not a constraint: a robust design keeps "
                f"its objective at the case's values, so it would be the nominal design; scatter what a constraint "
                f"depends on")
    if variable:
        return (f"a design variable the optimiser chooses in mode {mode} (the case's value only starts the search), "
                "so it does not enter the problem; bound it with [bounds] or fix it in another mode")
    left_out = not math.isfinite(case.values.get(name, math.nan))  # (an optional limit: its row posed where given)
    return (f"does not enter the {case.coupling} problem in mode {mode}"
            + (" with its [start_up]" if case.start_up is not None else "")
            + (f": the case leaves out {declared[name].key}, which no constraint then reads" if left_out else
               ": no constraint and not the objective depends on it") + ", so every design would be the same")

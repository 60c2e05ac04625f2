"""Modifier adaptation: a start-up limit corrected in value and gradient where moving the limit cannot reach a design
the simulated start verifies (docs/start_up.md, "Modifier adaptation").

The defect correction (:func:`~clutchopt.optimise.start_up_check.corrected_case`) moves a limit L to L - (S - C): the
case's limit less what the simulated figure S adds to the NLP's own C at the last design. Its fixed point exists
only where the two figures move the design the same way. cable_motor_start at 0.5 kg m^2 with 8 cables: the NLP's
quasi-static stress C rises with the weight mass, the simulated peak S falls (the weights' pull stiffens the link),
so a moved limit pushes the weight mass down, to its bound, and the NLP has no design there; 8-cable designs with a
heavier weight (from 0.4927 kg) verify, lighter than the 9 cables kept.

Modifier adaptation (Marchetti, Chachuat and Bonvin, "Modifier-adaptation methodology for real-time optimization",
Ind. Eng. Chem. Res. 48 (2009) 6022; Gao and Engell, Comput. Chem. Eng. 29 (2005) 1401) corrects the constraint's
value and its gradient at the last design x_k:

    C(x) + (S - C)(x_k) + grad(S - C)(x_k) . (x - x_k) <= L,

so that at x_k the corrected figure and its gradient are the simulated one's; at a fixed point x_{k+1} = x_k the
corrected NLP's KKT conditions are the simulated problem's (the first-order modifier's property, their Theorem 1).
grad S: forward differences of the simulation over the continuous design variables the start-up depends on (a
simulated start each); grad C: the NLP's figure with its collocation states following the design through the
dynamics' equalities h(x, z) = 0 (implicit function theorem: dC/dx = C_x - C_z h_z^-1 h_x, exact, no solve). The
modifier is written in the NLP as one offset and one slope per design variable for every start-up limit, NLP
parameters (case quantities of a formulation of its own, built once, on first use): the problem every other solve
poses is not touched. A first step that cannot end lighter than the design kept without it is not solved (nor its
problem built): the link's least stress bounds the corrected row, and the objective over the box it leaves
(:func:`no_lighter`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import casadi as ca
import numpy as np

from clutchopt.errors import InputError
from clutchopt.model import Quantity
from clutchopt.optimise.interval import IntervalFunction
from clutchopt.optimise.link_bound import MARGIN, least_stress
from clutchopt.optimise.sparsity import entries
from clutchopt.optimise.start_up_check import CENTRE, LIMIT_OF, limit_gaps, objective_error, simulated_checks
from clutchopt.records import DESIGN_STATUSES
from clutchopt.start_up.equations import with_start_up

MODIFIER_STEPS = 6  # corrected solves at most (the cable's 8 cables at 0.5 kg m^2: 3 from the free loop, 4 fixed)
DIFFERENCE_STEP = 1e-4  # of a variable's magnitude (or its scale): the simulated figures' forward differences (the peak
# stress moves by about 1e-9 of itself with where the integrator steps fall: at 1e-6 its slope was 2 % off; at 1e-4 the
# noise and the curvature are each about 2e-4 of it)
PREFIX = "modifier_"
VARIANT = "modifier adaptation"


def offset_name(limit: str) -> str:
    """The NLP parameter added to the start-up constraint ``limit``'s figure (its unit, SI)."""
    return f"{PREFIX}{limit}"


def slope_name(limit: str, variable: str) -> str:
    """The NLP parameter times ``variable`` (SI) added to the start-up constraint ``limit``'s figure."""
    return f"{PREFIX}{limit}_per_{variable}"


def modifier_names(variables) -> list[str]:
    """The modifiers' NLP parameters: each start-up limit's offset, then its slope per design variable."""
    return [name for limit in LIMIT_OF for name in (offset_name(limit), *(slope_name(limit, v) for v in variables))]


def with_modifiers(formulation):
    """``formulation`` (without its start-up: ``Posed`` adds it) with an offset and slopes for every start-up limit
    (:data:`~clutchopt.optimise.start_up_check.LIMIT_OF`) as case quantities, its own variant (built apart)."""
    variables = [v.name for v in with_start_up(formulation).variables]
    added = tuple(Quantity(name, "", "modifier adaptation of a start-up limit (docs/start_up.md; SI, never shown)",
                           section="modifier", default=None) for name in modifier_names(variables))
    return replace(formulation, quantities=formulation.quantities + added,
                   variant=f"{formulation.variant} {VARIANT}".strip())


def modifiers_in(p) -> bool:
    """Whether the case values ``p`` carry modifiers (a problem built :func:`with_modifiers`)."""
    return any(hasattr(p, offset_name(limit)) for limit in LIMIT_OF)


def modified(constraints: list, x, p) -> list:
    """The start-up ``constraints`` with each start-up limit's figure corrected by its modifier, where ``p`` has
    them (a problem built :func:`with_modifiers`): value + offset + sum of slope x variable. Others as they are."""
    if not modifiers_in(p):
        return constraints
    out = []
    for c in constraints:
        if c.name in LIMIT_OF and c.sense == "<=" and hasattr(p, offset_name(c.name)):
            term = getattr(p, offset_name(c.name)) + sum(getattr(p, slope_name(c.name, name)) * value
                                                         for name, value in vars(x).items())
            c = replace(c, value=c.value + term)
        out.append(c)
    return out


def _figure_derivatives(posed):
    """CasADi function (x, p) -> the NLP's start-up limit figures (every row of each, :data:`LIMIT_OF` order of the
    block's constraints), their Jacobian in x and the dynamics' equalities' Jacobian in x; with the row ranges of
    each named figure and the design columns any of them depends on. Built once per posed problem."""
    def build(_):
        block = posed.start_up
        x, p = posed.nlp["x"], posed.nlp["p"]
        figures, ranges = [], {}
        for c in block.constraints:
            if c.name in LIMIT_OF and c.sense == "<=":
                value = ca.vec(ca.SX(c.value))
                start = sum(f.shape[0] for f in figures)
                ranges[c.name] = (start, start + value.shape[0])
                figures.append(value)
        figure = ca.vertcat(*figures)
        h = ca.vertcat(*block.equalities)
        jf, jh = ca.jacobian(figure, x), ca.jacobian(h, x)
        n = len(posed.names)
        depends = entries(jf.sparsity())[:, :n].any(axis=0) | entries(jh.sparsity())[:, :n].any(axis=0)
        function = ca.Function("start_up_limit_figures", [x, p], [figure, jf, jh])
        return function, ranges, depends, h.shape[0] == x.shape[0] - n

    return posed.built("modifier", "figures", build)


def figure_gradients(posed, case, solution) -> dict[str, tuple[float, np.ndarray]] | None:
    """The NLP's own figure of each start-up limit at ``solution`` (its largest row) and its gradient in the design
    variables (SI), the collocation states following the design through the dynamics' equalities h(x, z) = 0:
    dC/dx = C_x - C_z h_z^-1 h_x. None where the states are not determined by the equalities (not as many as
    states) or h_z is singular."""
    function, ranges, _, square = _figure_derivatives(posed)
    if not square:
        return None
    data = posed.scaled_data(case, solution.design, solution.scale, solution.internal, solution.mesh[0])
    figure, jf, jh = (np.array(v) for v in function(data.x0, data.p))
    n = len(data.scale)
    try:
        follows = -np.linalg.solve(jh[:, n:], jh[:, :n])  # dz/dx_hat
    except np.linalg.LinAlgError:
        return None
    total = (jf[:, :n] + jf[:, n:] @ follows) / data.scale  # per SI unit of each design variable
    out = {}
    for name, (start, end) in ranges.items():
        row = start + int(np.argmax(figure[start:end, 0]))
        out[name] = (float(figure[row, 0]), total[row])
    return out


def simulated_figures(problem, case, design: dict[str, float]) -> dict[str, float]:
    """The start-up limits' figures of the simulated start at ``design``, by constraint name."""
    posed = problem.posed
    _, _, checks = simulated_checks(posed.start_up, *posed.start_up_seen(case, design), problem.formulation,
                                    posed.seen_by(case, design))
    return {check.name: check.value for check in checks if check.name in LIMIT_OF}


def modifiers(problem, case, solution, names: set[str], counts: dict | None = None) -> dict[str, float] | None:
    """The modifier of each start-up limit in ``names`` at ``solution``'s design x_k (offset and slopes: the NLP's
    figure C(x) + offset + slope . x is S(x_k) + grad S(x_k) . (x - x_k) to first order), every other one zero.
    ``counts`` (where given): the simulations run are added to its ``simulations``. None where a gradient cannot be
    had."""
    posed = problem.posed
    own = figure_gradients(posed, case, solution)
    if own is None or any(name not in own for name in names):
        return None
    _, _, depends, _ = _figure_derivatives(posed)
    simulated = {check.name: check.value for check in solution.constraints[posed.n_checked:]}
    design = solution.design
    slopes = {name: np.zeros(len(posed.names)) for name in names}
    for i, (variable, v) in enumerate(zip(posed.names, posed.formulation.variables)):
        lower, upper = solution.bounds.get(variable, (v.lower, v.upper))
        if v.integer or not depends[i] or not lower < upper:
            continue
        step = DIFFERENCE_STEP * max(abs(design[variable]), solution.scale[i])
        if design[variable] + step > upper:
            step = -step
        try:
            moved = simulated_figures(problem, case, {**design, variable: design[variable] + step})
        except InputError:
            return None
        if counts is not None:
            counts["simulations"] = counts.get("simulations", 0) + 1
        for name in names:
            slopes[name][i] = (moved[name] - simulated[name]) / step - own[name][1][i]
    values = dict.fromkeys(modifier_names(posed.names), 0.0)
    x = np.array([design[name] for name in posed.names])
    for name in names:
        slope = slopes[name]
        if not all(math.isfinite(s) for s in (simulated[name], *slope)):
            return None
        values[offset_name(name)] = simulated[name] - own[name][0] - float(slope @ x)
        values.update({slope_name(name, variable): float(s) for variable, s in zip(posed.names, slope)})
    return values


def violated(solution) -> set[str]:
    """The start-up limits the simulated start misses."""
    return {check.name for check, _, _ in limit_gaps(solution) if not check.feasible}


def centred(solution, names: set[str]) -> bool:
    """Every modified limit met by the simulated start so close to it that the objective is within CENTRE of the
    tolerance of the simulator's optimum (:func:`~clutchopt.optimise.start_up_check.objective_error`)."""
    tolerance = solution.start_up["tolerance"]
    return all(check.feasible and objective_error(check, gap) <= CENTRE * tolerance
               for check, _, gap in limit_gaps(solution) if check.name in names)


def first_order(problem, case, solution, solves: list, bound: float = math.inf, excluded: list | None = None):
    """``solution`` (a start-up solve its defect correction left ``unverified``), or the lightest design of its
    integers that modifier adaptation reaches and its simulated start verifies: each step solves the NLP at the
    case's limits with the modifiers of the limits missed so far at the last design (warm from it), at most
    MODIFIER_STEPS times, until the design is verified and centred (:func:`centred`), or a step's design is no
    lighter than ``bound`` (an integer choice's own loop: the design kept without it, ``Problem._own_loop``): each
    step's design is the lightest the corrected NLP, the simulated figure to first order at the last design,
    predicts to meet the limits, so the choice has no lighter verified design near there (the cable at 0.55 kg
    m^2: 8 cables' steps 4.348, 4.547 kg, ..., verified at 4.596 kg against 9 cables' 4.418 kg; at 0.6 kg m^2 they
    never verify). ``solves``: each step's solver record is appended. A first step that cannot end lighter than
    ``bound`` (:func:`no_lighter`) is not solved: the rows that show it are appended to ``excluded`` (where given)."""
    names = violated(solution)
    if solution.status != "unverified" or not names or solution.internal is None:
        return solution
    posed = problem.posed
    fixed = {posed.names[i]: (solution.design[posed.names[i]],) * 2 for i in posed.integer}
    last, best = solution, None
    for _ in range(MODIFIER_STEPS):
        values = modifiers(problem, case, last, names)
        if values is None:
            break
        if last is solution and (rows := no_lighter(problem, case, solution, values, fixed, bound)):
            if excluded is not None:
                excluded.extend(rows)
            break
        nlp_case = replace(case, values={**case.values, **values}, bounds={**case.bounds, **fixed})
        step = problem.modified_problem._solve(case, warm=last, nlp_case=nlp_case, cold=False,  # (built on first
                                               heavier=bound)  # use; no lighter: ``not_found``, not simulated)
        solves.append(step.solver)
        if step.status not in DESIGN_STATUSES or step.objective >= bound:
            break
        step.sensitivities = {k: v for k, v in step.sensitivities.items() if not k.startswith(PREFIX)}
        names |= violated(step)
        if step.status == "optimal" and centred(step, names):  # the simulator's optimum: kept
            best = step
            break
        if step.status == "optimal" and (best is None or step.objective < best.objective):
            best = step  # verified, not yet centred: kept where no later step is
        last = step
    if best is None:
        return solution
    best.integer_search, best.diagnosis = solution.integer_search, None
    return best


def no_lighter(problem, case, solution, values: dict[str, float], fixed: dict, bound: float) -> list[str]:
    """``["link_stress"]`` where no design of the NLP corrected by ``values`` (from ``solution``, integers ``fixed``,
    at the case's limits) weighs less than ``bound`` (:func:`least_objective` over it by MARGIN), else ``[]``.
    cable_motor_start: 7 cables' first step needs weights of 0.691 kg, at least 4.84 kg against 8 cables' 3.953 kg;
    solved, it ended at 0.789 kg, 5.826 kg (docs/start_up.md, "A modifier step refuted unsolved")."""
    if not math.isfinite(bound):
        return []
    return ["link_stress"] if least_objective(problem, case, solution, values, fixed) > bound * (1.0 + MARGIN) else []


def least_objective(problem, case, solution, values: dict[str, float], fixed: dict) -> float:
    """A lower bound on the objective of every design of the NLP corrected by ``values`` (the modifiers at
    ``solution``, integers ``fixed``, the case's limits): its corrected row C(x) + offset + slope . x <= L holds only
    where slope . x <= L - offset - S_least, S_least the link's least stress at ``solution``'s nodes whatever the free
    variables (:func:`~clutchopt.optimise.link_bound.least_stress`: below C at every design the NLP admits); that
    linear row narrows the box (each variable with a slope, the others at their least), and the objective is bounded
    over what is left by interval arithmetic (inf: the box empty). -inf where no least stress is had (not an
    elastic link, a robust design's corners)."""
    posed = problem.posed
    data = posed.scaled_data(replace(case, bounds={**case.bounds, **fixed}), solution.design, solution.scale,
                             solution.internal, solution.mesh[0])
    lbx, ubx = data.lbx, data.ubx
    least = least_stress(posed, data, data.x0, lbx, ubx)
    if least is None:
        return -math.inf
    n = len(posed.names)
    slope = np.array([values[slope_name("link_stress", name)] for name in posed.names]) * data.scale  # per x_hat
    room = data.params.max_link_stress * (1.0 + MARGIN) - values[offset_name("link_stress")] - least
    with np.errstate(invalid="ignore"):
        least_terms = np.where(slope == 0.0, 0.0, np.minimum(slope * lbx[:n], slope * ubx[:n]))
    if least_terms.sum() > room:  # (no slope: the limit broken whatever the design)
        return math.inf
    for i in np.flatnonzero(slope):
        reach = (room - np.delete(least_terms, i).sum()) / slope[i]  # slope_i x_i <= room - the others' least
        if slope[i] > 0:
            ubx[i] = min(ubx[i], reach)
        else:
            lbx[i] = max(lbx[i], reach)
    if np.any(lbx > ubx):
        return math.inf
    lower, _ = _objective_bounds(posed).bounds([(lbx[:, None], ubx[:, None]), (data.p[:, None], data.p[:, None])])[0]
    return float(lower[0, 0]) * data.f_scale


def _objective_bounds(posed) -> IntervalFunction:
    """The NLP's (scaled) objective bounded over a box of its variables (interval arithmetic); built once a problem."""
    return posed.built("objective_bounds", None, lambda number: IntervalFunction(
        ca.Function(f"objective_bounds_{number}", [posed.nlp["x"], posed.nlp["p"]], [posed.nlp["f"]]), compiled=False))

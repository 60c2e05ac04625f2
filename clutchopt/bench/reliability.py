"""Failure probabilities side by side: clutchopt's estimators against OpenTURNS on the same limit states.

The limit states: each constraint of ``cases/wedge_centrifuge.toml`` that is active at its worst-case design and at
its nominal design (the torque, the finger's bending), g(x) = the constraint's relative margin at the design with
the scattered quantities at x (``clutchopt.optimise.robust_models.constraints_at``, float64, vectorised); failure
is g < -FEASIBILITY_TOL, as the tool counts it. The inputs: the case's ``[scatter]``, each kind as the same
OpenTURNS distribution (normal, uniform over a range, lognormal, truncated normal), joined by a normal copula of
the case's ``[scatter.correlation]`` (the tool's Gaussian copula, :func:`clutchopt.scatter.draw`).

An estimator is one entry of :data:`TOOL` or :data:`OPENTURNS`: a name and a function from the limit states of one
design to (probability, interval low, interval high) per constraint (interval None where the method gives none:
FORM, SORM). Times: the median of ``config.repeats`` runs (``clutchopt.bench.timing.median_run``) for all the
design's limit states at once (the tool's Monte Carlo evaluates them in one vectorised pass, OpenTURNS one event
at a time). OpenTURNS is an optional benchmark dependency (``pip install clutchopt[bench]``); without it the
section says so and has the tool's rows only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Callable

import numpy as np

from clutchopt.bench.timing import median_run
from clutchopt.cases import Case, load_case
from clutchopt.model import Formulation
from clutchopt.optimise.reliability import IS_SAMPLES
from clutchopt.optimise.robust_reliability import reliability_at
from clutchopt.optimise.robust_models import CONFIDENCE, SEED, constraint_table, constraints_at, failure_probabilities
from clutchopt.optimise.verify import FEASIBILITY_TOL

CASE = Path(__file__).resolve().parents[2] / "cases" / "wedge_centrifuge.toml"
SAMPLES = 10_000  # of either Monte Carlo: the tool's default (robust_models.SAMPLES)
IMPORTANCE_SAMPLES = 2_000  # around the design point
BLOCK = 1_000  # points per call of the limit state by OpenTURNS' samplers (vectorised)
FORM_START = 0.5  # standard normal units: where OpenTURNS' FORM starts its search of the design point


@dataclass(frozen=True)
class LimitStates:
    """The limit states of one design: its constraints' relative margins over the case's scatter."""

    formulation: Formulation
    design: dict
    params: SimpleNamespace
    case: Case
    names: tuple[str, ...]  # the constraints compared

    def margins(self, points: np.ndarray) -> np.ndarray:
        """Relative margins, one row per constraint of ``names``, one column per point (rows of ``points``, in the
        order of ``case.scatter``); a margin that is not a number counts as failed (-1)."""
        values = {s.name: points[:, i] for i, s in enumerate(self.case.scatter)}
        constraints = constraints_at(self.formulation, self.design, self.params, values)
        margins = constraint_table(constraints, len(points))[3]
        rows = [margins[[c.name for c in constraints].index(name)] for name in self.names]
        return np.nan_to_num(np.array(rows, dtype=float), nan=-1.0)


@dataclass(frozen=True)
class Estimator:
    name: str
    # constraint -> (probability, interval low, interval high), or (None, None, None, why not)
    run: Callable[[LimitStates], dict[str, tuple]]
    samples: int | None = None  # evaluations of the limit state it draws, where fixed


def _tool_monte_carlo(states: LimitStates) -> dict:
    found = failure_probabilities(states.formulation, states.design, states.params, states.case.scatter, SAMPLES,
                                  SEED, states.case.correlation)
    return {name: tuple(found[name]) for name in states.names}


def _tool_design_point(which: int) -> Callable[[LimitStates], dict]:
    """clutchopt's estimate number ``which`` of each constraint at its design point (0 FORM, 1 SORM, 2 importance
    sampling, ``clutchopt.optimise.robust_reliability.reliability_at``); a constraint without a design point gives
    its one estimate (exact, or FORM's bound) with what it is."""
    def run(states: LimitStates) -> dict:
        found = reliability_at(states.formulation, states.design, states.params, states.case.scatter,
                               states.case.correlation, states.names).constraints
        out = {}
        for name in states.names:
            estimates = found[name].estimates
            if len(estimates) == 3:
                e = estimates[which]
                out[name] = (e.probability, *((e.low, e.high) if which == 2 else (None, None)))
            else:
                e = estimates[0]
                out[name] = (None, None, None, f"clutchopt: {e.estimator}: {e.probability:.3g} [{e.low:.3g}, "
                                               f"{e.high:.3g}]")
        return out
    return run


TOOL: tuple[Estimator, ...] = (  # clutchopt's estimators, one line each
    Estimator("clutchopt monte carlo", _tool_monte_carlo, SAMPLES),
    Estimator("clutchopt form", _tool_design_point(0)),
    Estimator("clutchopt sorm (breitung)", _tool_design_point(1)),
    Estimator("clutchopt importance sampling", _tool_design_point(2), IS_SAMPLES),
)


# --- OpenTURNS ------------------------------------------------------------------------------------------------------
def openturns_available() -> bool:
    from importlib.util import find_spec

    return find_spec("openturns") is not None


def _distribution(case: Case):
    """The case's scatter as one OpenTURNS distribution: its marginals, joined by a normal copula."""
    import openturns as ot

    marginals = []
    for s in case.scatter:
        if s.kind == "normal":
            marginals.append(ot.Normal(s.mean, s.sd))
        elif s.kind == "lognormal":
            marginals.append(ot.LogNormal(*s.log_parameters()))
        elif s.kind == "truncated":
            marginals.append(ot.TruncatedNormal(s.mean, s.sd, s.low, s.high))
        else:
            marginals.append(ot.Uniform(s.low, s.high))
    n = len(marginals)
    if case.correlation is None:
        return ot.JointDistribution(marginals)
    matrix = ot.CorrelationMatrix(n)
    for i in range(n):
        for j in range(i):
            matrix[i, j] = case.correlation[i][j]
    return ot.JointDistribution(marginals, ot.NormalCopula(matrix))


def _events(states: LimitStates):
    """Per constraint, the OpenTURNS event {g < -FEASIBILITY_TOL} over the case's distribution."""
    import openturns as ot

    distribution = _distribution(states.case)
    vector = ot.RandomVector(distribution)
    events = {}
    for row, name in enumerate(states.names):
        def margin(points, row=row):
            return states.margins(np.asarray(points))[row].reshape(-1, 1)

        function = ot.PythonFunction(len(states.case.scatter), 1, func_sample=margin)
        events[name] = ot.ThresholdEvent(ot.CompositeRandomVector(function, vector), ot.Less(), -FEASIBILITY_TOL)
    return distribution, events


def _simulated(algorithm, samples: int) -> tuple[float, float, float]:
    import openturns as ot

    ot.RandomGenerator.SetSeed(SEED)
    algorithm.setBlockSize(BLOCK)
    algorithm.setMaximumOuterSampling(max(1, samples // BLOCK))
    algorithm.setMaximumCoefficientOfVariation(-1.0)  # the whole budget
    algorithm.setMaximumStandardDeviation(-1.0)
    algorithm.run()
    result = algorithm.getResult()
    interval = result.getProbabilityDistribution().computeBilateralConfidenceInterval(CONFIDENCE)
    p = result.getProbabilityEstimate()
    return p, max(0.0, interval.getLowerBound()[0]), min(1.0, interval.getUpperBound()[0])


def _form(distribution, event):
    import openturns as ot

    algorithm = ot.FORM(_solver(distribution), event)
    algorithm.run()
    return algorithm.getResult()


def _solver(distribution):
    """Abdo-Rackwitz (OpenTURNS' usual solver of FORM) from FORM_START in each standard normal variable: at the
    origin itself (the median) a limit state that is active at the nominal design starts on its surface and the
    solver leaves it the wrong way."""
    import openturns as ot

    solver = ot.AbdoRackwitz()
    solver.setStartingPoint([FORM_START] * distribution.getDimension())
    return solver


def _each_event(states: LimitStates, estimate) -> dict:
    """``estimate(distribution, event)`` for each limit state; one that OpenTURNS cannot estimate (a design point
    search that does not converge, e.g. where the failure domain lies beyond a uniform quantity's end) as None with
    OpenTURNS' reason."""
    distribution, events = _events(states)
    found = {}
    for name, event in events.items():
        try:
            found[name] = estimate(distribution, event)
        except RuntimeError as exc:
            found[name] = (None, None, None, f"openturns: {str(exc).split(':', 1)[-1].strip()[:90]}")
    return found


def _ot_monte_carlo(states: LimitStates) -> dict:
    import openturns as ot

    return _each_event(states, lambda distribution, event: _simulated(
        ot.ProbabilitySimulationAlgorithm(event, ot.MonteCarloExperiment()), SAMPLES))


def _ot_form(states: LimitStates) -> dict:
    return _each_event(states, lambda distribution, event: (_form(distribution, event).getEventProbability(), None,
                                                            None))


def _ot_sorm(states: LimitStates) -> dict:
    import openturns as ot

    def sorm(distribution, event):
        algorithm = ot.SORM(_solver(distribution), event)
        algorithm.run()
        return algorithm.getResult().getEventProbabilityBreitung(), None, None

    return _each_event(states, sorm)


def _ot_importance_sampling(states: LimitStates) -> dict:
    """Importance sampling around FORM's design point, in the standard space (FORM's time counted)."""
    import openturns as ot

    return _each_event(states, lambda distribution, event: _simulated(
        ot.PostAnalyticalImportanceSampling(_form(distribution, event)), IMPORTANCE_SAMPLES))


OPENTURNS: tuple[Estimator, ...] = (
    Estimator("openturns monte carlo", _ot_monte_carlo, SAMPLES),
    Estimator("openturns form", _ot_form),
    Estimator("openturns sorm (breitung)", _ot_sorm),
    Estimator("openturns importance sampling", _ot_importance_sampling, IMPORTANCE_SAMPLES),
)


# --- The section ----------------------------------------------------------------------------------------------------
def limit_states(case: Case) -> dict[str, LimitStates]:
    """The worst-case and the nominal design of ``case``, each with its active constraints as limit states."""
    from clutchopt.optimise.robust import WORST_CASE, solve_robust

    robust = solve_robust(case, WORST_CASE)
    params = case.params()
    return {label: LimitStates(robust.formulation, solution.design, params, case,
                               tuple(c.name for c in solution.constraints if c.active))
            for label, solution in (("worst case", robust.solution), ("nominal", robust.nominal))}


def reliability_rows(config) -> list[dict]:
    """One row per design, constraint and estimator: the probability, its interval where the estimator gives one,
    and the median time of the estimator over all of the design's limit states."""
    case = load_case(CASE)
    available = openturns_available()
    estimators = TOOL + (OPENTURNS if available else ())
    rows = []
    for design, states in limit_states(case).items():
        for estimator in estimators:
            found, seconds = median_run(lambda: estimator.run(states), config.repeats)
            for name in states.names:
                p, low, high, *why = found[name]
                rows.append({"case": CASE.name, "design": design, "constraint": name, "estimator": estimator.name,
                             "probability": _number(p), "interval_low": _number(low), "interval_high": _number(high),
                             "samples": estimator.samples, "time_s": seconds,
                             "note": why[0] if why else ""})
    if not available:
        rows.append({"case": CASE.name, "design": "", "constraint": "", "estimator": "openturns",
                     "probability": None, "interval_low": None, "interval_high": None, "samples": None,
                     "time_s": None, "note": "openturns not installed (pip install 'clutchopt[bench]')"})
    return rows


def _number(value) -> float | None:
    return None if value is None or (isinstance(value, float) and math.isnan(value)) else float(value)

"""One phase of a start-up integrated step by step with SciPy's solvers (DOP853, Radau; LSODA runs in spans of
``odeint``, :mod:`clutchopt.simulate.spans`), driven here rather than through ``solve_ivp`` so that the work is
bounded by the input and nothing is kept that is not needed:

- a budget of solver steps shared by the phases of one run (:class:`Budget`): a run that would take more stops
  with a reason instead of running on;
- events located on each step's dense output as ``solve_ivp`` locates them (Brent's method to 4 eps): a terminal
  one ends the phase where it occurs; a sampled one (a state's maximum) only adds a sample where it occurs;
- samples: the end of every step and the middle of its dense output (a solver's interpolant is used inside its
  own step only, so no interpolant is kept after the step).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.integrate import DOP853, Radau
from scipy.optimize import brentq

EPS = np.finfo(float).eps
SOLVERS = {"DOP853": DOP853, "Radau": Radau}
IMPLICIT = ("Radau",)  # these take the Jacobian


@dataclass
class Budget:
    """Solver steps a run may still take."""

    steps: int
    taken: int = 0

    @property
    def spent(self) -> bool:
        return self.taken >= self.steps


@dataclass
class Phase:
    """What one phase's integration gave: samples (the start and the end included) and how it ended: ``event``
    (the terminal event ``event`` ended it), ``end`` (the bound), ``failed`` (``message``), ``budget`` (no steps
    left)."""

    t: np.ndarray
    y: np.ndarray
    status: str
    event: int | None = None
    message: str = ""


def integrate(fun, jac, t0: float, y0: np.ndarray, bound: float, events: list, method: str, rtol: float,
              atol: np.ndarray, budget: Budget) -> Phase:
    """Integrate y' = fun(t, y) from (t0, y0) towards ``bound`` until a terminal event, the bound, a failure or the
    end of ``budget``. Each event is a function g(t, y) with attributes ``terminal`` and ``direction`` (as
    ``solve_ivp``'s); a non-terminal one adds a sample where g changes sign strictly. A solver's warnings are raised
    as errors; NumPy's floating-point warnings are not shown (a state gone infinite or NaN, e.g. a start of a driven
    inertia far in a lognormal's tail, printed SciPy's "invalid value encountered in dot" once a step until the step
    size fell below its least: the phase ends ``failed`` saying so)."""
    options = {"jac": jac} if method in IMPLICIT else {}
    solver = SOLVERS[method](fun, t0, y0, bound, rtol=rtol, atol=atol, **options)
    with warnings.catch_warnings(), np.errstate(over="ignore", invalid="ignore"):  # once per phase, not per step
        warnings.simplefilter("error", UserWarning)  # (it cost 5 % of a start-up's simulation)
        return _stepped(solver, t0, y0, events, budget)


def _stepped(solver, t0: float, y0: np.ndarray, events: list, budget: Budget) -> Phase:
    """:func:`integrate`'s steps (a UserWarning of a step: the phase failed)."""
    times, states = [t0], [np.array(y0, dtype=float)]
    values = [event(t0, y0) for event in events]
    while solver.status == "running":
        if budget.spent:
            return Phase(np.array(times), np.array(states).T, "budget")
        try:
            solver.step()
        except UserWarning as warning:
            return Phase(np.array(times), np.array(states).T, "failed", message=str(warning))
        budget.taken += 1
        if solver.status == "failed":
            return Phase(np.array(times), np.array(states).T, "failed", message="the step size fell below its least")
        t_old, t, y = solver.t_old, solver.t, solver.y
        dense = solver.dense_output()
        new = [event(t, y) for event in events]
        hits = sorted((_root(event, dense, t_old, t), index)
                      for index, (event, g, g_new) in enumerate(zip(events, values, new))
                      if crosses(event, g, g_new))
        stop = next(((root, index) for root, index in hits if events[index].terminal), None)
        inside = [root for root, index in hits if not events[index].terminal and (stop is None or root < stop[0])]
        end = stop[0] if stop else t
        for sample in sorted(inside + ([0.5 * (t_old + end)] if end > t_old else [])):
            times.append(sample)
            states.append(dense(sample))
        times.append(end)
        states.append(dense(end) if stop else np.array(y))
        if stop:
            return Phase(np.array(times), np.array(states).T, "event", stop[1])
        values = new
    return Phase(np.array(times), np.array(states).T, "end")


def crosses(event, g, g_new):
    """Whether the event crosses zero from ``g`` to ``g_new`` (numbers, or arrays: each sample interval of a span,
    clutchopt.simulate.spans): a terminal event as ``solve_ivp`` finds it (a zero at the step's start counts); a
    sampled one, or one marked ``strict``, only where its sign changes strictly (a function that stays at zero is no
    maximum; a difference that starts at zero and moves by rounding has not crossed it)."""
    direction, strict = event.direction, not event.terminal or getattr(event, "strict", False)
    if direction <= 0:  # (each direction's test alone: on a span's samples 11 -> 3 us)
        falls = (g > 0) & (g_new < 0) if strict else (g >= 0) & (g_new <= 0)
        if direction < 0:
            return falls
    rises = (g < 0) & (g_new > 0) if strict else (g <= 0) & (g_new >= 0)
    return rises if direction > 0 else falls | rises


def _root(event, dense, t_old: float, t: float) -> float:
    """The zero of the event on the step's interpolant; where the interpolant's ends do not bracket one (an
    implicit method's interpolant need not pass exactly through the step's start), the end nearer zero."""
    g_old, g = event(t_old, dense(t_old)), event(t, dense(t))
    if g_old * g > 0 or g_old == g:
        return t_old if abs(g_old) < abs(g) else t
    return brentq(lambda s: event(s, dense(s)), t_old, t, xtol=4 * EPS, rtol=4 * EPS)

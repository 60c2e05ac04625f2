"""Starts already known to fail at a point: a retry before a verdict is not solved twice (issue 26).

Before a start-up point is reported without a design it is solved again from other starts
(``clutchopt.optimise.verdict``): a feasible neighbour's design among them; a sweep then follows the design from its
last feasible point by continuation (``clutchopt.optimise.sweep.continued``), whose steps from that design alone (a
stored design, an optimum of the loop's doubled problem; a step warm from an optimum of the problem is no such retry)
can fall on a point already retried from that same design (ball_motor_start over driven_inertia: the first step
towards 430.3 kg m^2 from 382.9, its optimum on the doubled problem, lands on 398.7, tried from 382.9's design a
moment before). Such a retry, an undiagnosed solve from a given design, is a function of the case and that design
alone, so its failure is kept here and returned again (charged no solver call). The point is recognised to 12
significant digits of each value: a continuation's step computed as a + (b - a) / 3 differs from the grid's value in
the last bits, and IPOPT, on a problem without a feasible point, can end elsewhere for such a difference (lever,
15.284 kg m^2: 34 or 65 iterations), never at a design where the same start failed. Only failures are kept: a
design is returned to be used and changed.

A sweep's continuation (``clutchopt.optimise.sweep.continued``) follows the last feasible point's design towards a
point without one in equal steps. Where one such path was lost at a step (no design there from the step before),
a later continuation from the same design whose first step lands on or beyond that step, on the same ray from the
feasible point, is not started (:meth:`lost_beyond`): it would jump from that design at once further than the path
already failed to follow it (lever_motor_start from 14.78 kg m^2: lost at 14.95, then asked to start at 15.12 and
15.45, 53 and 82 IPOPT iterations; ball_motor_start from 382.9: lost at 393.4, then asked at 393.4 from the design
itself (487 iterations) and at 403.9-425.0). Nor is a verdict's retry from that design (the neighbouring point's, in
``clutchopt.optimise.verdict``) at a point on or beyond that step (lever 15.79-16.8 kg m^2, ball 414.5-525 kg m^2:
30-80 iterations each). A continuation, or a retry from a neighbour's design, changes a point's verdict only where it
finds a design ``solve`` of that point alone would not try (it has no neighbour: its verdict is ``solve``'s either
way); a retry left out is not among the starts the verdict names.
"""

from __future__ import annotations

from contextlib import contextmanager
from dataclasses import replace

from clutchopt.cases import Case
from clutchopt.optimise.solution import Solution, SolverInfo
from clutchopt.start_up.mesh import settled

KEPT = 256  # failures kept per problem (a sweep's run of points without a design, a few starts each)


def case_numbers(case: Case) -> dict[str, float]:
    """The case's values that are numbers (not flags), as floats: where a sweep's point lies (read here to 12 digits,
    and by ``start_up_sweep``'s secant, the finite ones)."""
    return {name: float(value) for name, value in case.values.items()
            if isinstance(value, (int, float)) and not isinstance(value, bool)}


def _make_room(table: dict, key) -> None:
    """The oldest entry of ``table`` dropped where it holds KEPT and ``key`` is not among them (a problem is kept
    for the process)."""
    if len(table) >= KEPT and key not in table:
        table.pop(next(iter(table)))


def _digits(value) -> float:
    return float(f"{float(value):.12g}")


class FailedStarts:
    """Retries (an undiagnosed solve of a case from a start design) that ended without a design, by case and start."""

    def __init__(self):
        self._failed: dict[tuple, Solution] = {}
        self._lost: dict[tuple, list[tuple[dict, dict]]] = {}  # a continuation's start -> (from, lost at) values
        self._along = False  # inside a sweep's run (:meth:`along_a_run`)

    @contextmanager
    def along_a_run(self):
        """A sweep's run of points: the paths its continuations lose are kept for its later points
        (:meth:`lost_beyond`) and forgotten at its end; they bear only on starts ``solve`` of a point alone does not
        try. No start ``solve`` tries is left out for what an earlier point showed, in a run or out of one: a point's
        verdict does not depend on what the process solved before (review h12: ball_motor_start in paper mode at
        605.7 kW was 554.69 kg in a new process, not_found after a solve at 900 kW whose sampled start had failed for
        the same constraints; h13: so was a sweep's point there after a point at 900 kW, and a resumed sweep's first
        point took the start its uninterrupted run left out). (A sweep's point beyond one without a design may be
        decided by its own solve from that one's least relaxation, not by ``solve``'s starts, and says so:
        ``clutchopt.optimise.start_up_region``.)"""
        self._lost.clear()
        self._along = True
        try:
            yield
        finally:
            self._lost.clear()
            self._along = False

    @staticmethod
    def key(case: Case, start: dict[str, float]) -> tuple:
        return (case.coupling, tuple(sorted((k, _digits(v)) for k, v in case.values.items())),
                repr(sorted(case.bounds.items())), case.free, repr(sorted(case.options.items())), case.start_up,
                tuple(sorted((k, _digits(v)) for k, v in start.items())))

    def known(self, key: tuple) -> Solution | None:
        """The failure kept for ``key``, charged no solver call (it is not solved again), or None."""
        failed = self._failed.get(key)
        if failed is None:
            return None
        return replace(failed, solver=SolverInfo(failed.solver.name, failed.solver.status, 0, 0.0, 0))

    def keep(self, key: tuple, solution: Solution) -> None:
        _make_room(self._failed, key)
        settled(solution.mesh)  # (kept for the process: its simulation's columns let go)
        self._failed[key] = solution

    def lose(self, case: Case, start: dict[str, float], origin: dict[str, float], at: dict[str, float]) -> None:
        """A continuation of the sweep ``case`` from ``start`` (the design at the varied values ``origin``) lost its
        path at the step ``at`` (the varied values); kept along a sweep's run only."""
        if not self._along:
            return
        key = self._start_key(case, start)
        _make_room(self._lost, key)
        self._lost.setdefault(key, []).append((_values(case), dict(origin), dict(at)))

    def lost_beyond(self, case: Case, start: dict[str, float], origin: dict[str, float] | None = None,
                    first: dict[str, float] | None = None) -> bool:
        """Whether a path from ``start`` was lost on the way to ``first`` (the varied values; default: ``case``'s own)
        from ``origin`` (default: the point ``start`` was lost from): ``first`` on the ray from there through the step
        where the path was lost, on or beyond it, and every other value of ``case`` the sweep's."""
        if not self._lost:  # (a static problem's: none kept, no key built)
            return False
        for base, lost_from, lost_at in self._lost.get(self._start_key(case, start), ()):
            here = _values(case)
            ahead = {name: here[name] for name in lost_from} if first is None else first
            others = {name for name in base if name not in lost_from} if first is None else set()
            if (origin is None or lost_from == origin) and all(here.get(name) == base[name] for name in others) \
                    and _on_or_beyond(lost_from, lost_at, ahead):
                return True
        return False

    def _start_key(self, case: Case, start: dict[str, float]) -> tuple:
        at = self.key(case, start)
        return at[:1] + at[2:]  # (the case but its values: a sweep's points share it)


def _values(case: Case) -> dict[str, float]:
    return {name: _digits(value) for name, value in case_numbers(case).items()}


def _on_or_beyond(origin: dict[str, float], lost: dict[str, float], first: dict[str, float]) -> bool:
    """``first`` = ``origin`` + t (``lost`` - ``origin``) in every value with t >= 1 (to 1e-9 of each step)."""
    t = on_ray(origin, lost, first)
    return t is not None and t >= 1.0 - 1e-9


ON_RAY = 1e-9  # relative: a value on the ray to this fraction of its step


def on_ray(origin: dict[str, float], towards: dict[str, float], point: dict[str, float]) -> float | None:
    """t where ``point`` = ``origin`` + t (``towards`` - ``origin``) in every value (to ON_RAY of each step), taken
    from the first value that moves; None where they are not so placed (other names, no value moving, or one off
    the ray). A sweep's continuation lost on its way (:func:`_on_or_beyond`) and the secant of a start-up sweep's
    moved limits (``start_up_sweep``) read it."""
    if origin.keys() != towards.keys() or origin.keys() != point.keys():
        return None
    steps = [(towards[name] - origin[name], point[name] - origin[name]) for name in origin]
    moved = [(step, ahead) for step, ahead in steps if step != 0.0]
    if not moved or any(step == 0.0 and ahead != 0.0 for step, ahead in steps):
        return None
    t = moved[0][1] / moved[0][0]
    return t if all(abs(ahead - t * step) <= ON_RAY * abs(ahead) for step, ahead in moved) else None

"""A formulation's problem solved for cases: the driver over a posed problem (``clutchopt.optimise.posed``).

``Problem.solve`` tries its strategies in turn. A re-solve, ``solve(case, warm=previous)``, starts from a previous
optimum, keeps its scales and hands its multipliers to CasADi's SQP method, then to warm IPOPT
(``clutchopt.optimise.attempts``); should both fail, the cold solve from the case's own start follows. An optimum far
off its scales is solved again scaled by it, warm from its own KKT point carried into them (:func:`rescaled_seed`: the
cable's cold solves 42 -> 31 IPOPT iterations, the same optimum); free integers are searched
(``clutchopt.optimise.integers``); the kept design is checked in float64, and a failed solve diagnosed
(``clutchopt.optimise.diagnosis``); an optimal one gets its sensitivities (``clutchopt.optimise.sensitivity``). With
a start-up, the collocation mesh is refined around the solves until the simulated start-up agrees. Sweeps chain SQP
re-solves in one CasADi call and check them together (``clutchopt.optimise.batch``).
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import replace
from functools import cached_property
from typing import Callable

import numpy as np

from clutchopt.cases import Case, check_across
from clutchopt.errors import NOT_SIMULATED, InputError, shown_value
from clutchopt.model import Formulation
from clutchopt.optimise.attempts import attempt, tallied, warm_multipliers
from clutchopt.optimise.diagnosis import diagnose, whatever_the_design
from clutchopt.optimise.failed_starts import FailedStarts
from clutchopt.optimise.integers import (FROM_THE_RELAXATION, RuledOut, descend, fixed_box, fixing, from_the_start,
                                         meets_every_row, nearest_integers, relaxation_seed, within)
from clutchopt.optimise.link_bound import MARGIN as LINK_MARGIN, least_stress, refuted
from clutchopt.optimise.modifier import VARIANT, first_order, modifiers_in, with_modifiers
from clutchopt.optimise.own_shift import (CARRIED, OWN_LOOP, ForeignShifts, carried_by, climbing,
                                          excluded_own_entry, lighter_above, own_entry, stepped, unverified_here)
from clutchopt.optimise.polish import polishable, polished
from clutchopt.optimise.posed import Posed, ScaledData, off_scale
from clutchopt.optimise.sensitivity import limit_elasticity, sensitivities, with_followers
from clutchopt.optimise.solution import Diagnosis, Solution, SolverInfo, SolverOptions, WarmStart
from clutchopt.optimise.start_up_check import BACK_OFF_STEPS, CENTRE, corrected_case, start_up_report, worn_start
from clutchopt.optimise.start_up_shift import limit_shift, shifted
from clutchopt.optimise.start_up_sweep import sized_choices
from clutchopt.optimise.verdict import GIVEN, OWN, infeasible_at, shown
from clutchopt.optimise.proofs import start_up_proofs
from clutchopt.optimise.sampled_start import from_a_sampled_design, from_the_held_design
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import evaluate_outputs
from clutchopt.records import UNRANKED
from clutchopt.start_up.drive import Structure
from clutchopt.start_up.equations import with_start_up
from clutchopt.start_up.mesh import MAX_INTERVALS, MESH_STEPS
from clutchopt.start_up.transcription import mesh_of_the_start


UNRANKED_ERROR = 1e-3  # a first mesh's collocation error (start time, relative) over which it ranks no neighbours
AT_THE_CASE = "simulated at the case's limits"  # a count whose NLP design at the case's own limits the loop simulated,
# its start missing a limit (the integer search's entry): ``lighter_settled`` takes it as settled there, as ``solve``
# alone's path goes no further with it; no proof that the count has no design (its correction or modifier might)
FIRST_UP = "solved first at the case's limits"  # a count solved at the case's limits before the search at moved
# limits (one up: :meth:`Problem._one_up_first`; a sweep's failed warm count: :meth:`Problem._own_first`), whose own
# loop never ran
PROVEN = "proof"  # the solver of a start-up the drive's proofs cover (:meth:`Problem.proven`: no start-up solve)


class Problem:
    """One formulation with one objective, posed as a CasADi NLP once (``posed``), solved for many cases."""

    def __init__(self, formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions(),
                 start_up: Structure | None = None):
        self.posed = posed = Posed(formulation, objective, options, start_up)
        self.formulation, self.objective, self.options, self.start_up = (  # what callers read of the posed problem
            posed.formulation, posed.objective, posed.options, posed.start_up)
        self.failed_starts = FailedStarts()  # a start-up's retries that ended without a design

    def solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | WarmStart | None = None,
              mesh: np.ndarray | None = None, refine: bool = True, neighbour: dict[str, float] | None = None,
              coarser: float = math.inf, first: Solution | None = None, alone: Solution | None = None,
              infeasible: dict[tuple, str] | None = None) -> Solution:
        """Solve for one case (:meth:`refined`); a solve that ends without a design is retried from the starts that can
        reach one before its verdict is given (:func:`clutchopt.optimise.verdict.shown`): ``neighbour``, the feasible
        design of a neighbouring point (a sweep's), among them. ``first``: that first solve, where a caller has made it
        already (a sweep's quick solve of a point its interval search did not prove). A start-up's ``not_found`` solved
        from its own start (no start, warm solution or neighbour given: a sweep's point too, before the starts the
        sweep adds) is retried last from the sampled design its NLP's rows miss least
        (:mod:`clutchopt.optimise.sampled_start`). A start-up from a ``start`` or a ``warm`` solution given (a sweep's
        point retried from the next feasible point's design, a start-up's pareto front, the robust loop) that ends
        without a verified design is set beside ``solve`` of the case alone (``alone``, where the caller has it: a
        sweep's point without a design), whose verified design is kept (:func:`verified_alone`; ball_motor_start in
        paper mode at 1.5 GPa, 650 kW from the design at 507.9 kW: ``not_found`` at 656.12 kg, now 687.92 kg as
        alone; 610 kW warm from 530 kW's optimum: ``not_found``, alone 565.36 kg: tests/test_start_up_held.py); not the
        design a loop hands its doubled problem (``mesh`` or ``coarser`` given). A start-up optimum a row of
        the collocation holds (:func:`held_by_the_mesh`; the loop's remedy, the papers' sizing, missed a limit) is
        walked from (:func:`~clutchopt.optimise.sampled_start.from_the_held_design`): the lighter design kept.
        ``infeasible``: integer choices known to have no design here, with why (:meth:`_refined`; a loop's doubled
        problem: those the papers' sizing at the point found infeasible)."""
        try:
            solution = first or self.refined(case, start, warm, mesh, refine, coarser=coarser, infeasible=infeasible)
        except InputError:  # a start-up whose first simulation fails from this design: from the papers' sizing
            if self.start_up is None or (start is None and warm is None):
                raise
            if alone is not None:  # (the caller has ``solve``'s verdict alone, and counts it: not solved again; the
                return replace(alone, solver=alone.solver.summed([]))  # start given, not simulated, is not named)
            solution, start, warm = self.refined(case, None, None, mesh, refine, coarser=coarser,
                                                 infeasible=infeasible), None, None
        if self.start_up is not None and refine and self._held(solution):  # the loop's remedy missed: walked
            solution = from_the_held_design(self, case, solution)
        if solution.status == "optimal" or not refine or solution.diagnosed is not None and solution.diagnosed.proven:
            return solution  # (a proof, the drive's: no start was solved from, none is named; review 19c)
        if self.start_up is not None and neighbour is None and mesh is None and coarser == math.inf and (
                warm is not None or start is not None):  # a start given that missed: beside ``solve`` alone (a
            return verified_alone(solution, alone or self.solve(case), counted=alone is None)  # caller's: its count)
        if solution.status in DESIGN_STATUSES:
            return solution
        verdict = shown(self, case, solution, start is not None or warm is not None, neighbour)
        own = self.start_up is not None and start is None and warm is None and neighbour is None
        return from_a_sampled_design(self, case, verdict) if own else verdict  # (alone: the sampled start last)

    def refined(self, case: Case, start: dict[str, float] | None = None, warm: Solution | WarmStart | None = None,
                mesh: np.ndarray | None = None, refine: bool = True, diagnosed: bool = True,
                coarser: float = math.inf, shift: dict[str, float] | None = None, cold: bool = True,
                infeasible: dict[tuple, str] | None = None, sizing: dict[str, float] | None = None) -> Solution:
        """:meth:`_refined`; a start-up the drive makes impossible for every coupling
        (:func:`~clutchopt.optimise.proofs.start_up_proofs`) is not solved (:meth:`proven`: a sweep's continuation
        onto such a point, its retries, ``solve``), and a start-up's retry (from ``start`` alone, undiagnosed) that
        already ended without a design at this point from this start is not solved again
        (:mod:`clutchopt.optimise.failed_starts`)."""
        if self.start_up is not None and refine and (proofs := start_up_proofs(case)):
            return self.proven(case, proofs)
        retry = (self.start_up is not None and start is not None and warm is None and mesh is None and refine
                 and not diagnosed and coarser == math.inf and shift is None and cold)
        key = self.failed_starts.key(case, start) if retry else None
        if key is not None and (known := self.failed_starts.known(key)) is not None:
            return known
        with tallied() as made:
            try:
                solution = self._refined(case, start, warm, mesh, refine, diagnosed, coarser, shift, cold,
                                         infeasible=infeasible, sizing=sizing)
            except InputError as exc:
                if self.start_up is None or not made.calls or exc.field != NOT_SIMULATED:
                    raise  # (its first simulation failed from this start: nothing solved; callers say so)
                solution = self._not_simulated(case, start, exc, made)
        if key is not None and solution.status not in DESIGN_STATUSES:
            self.failed_starts.keep(key, solution)
        return solution

    def _not_simulated(self, case: Case, start: dict[str, float] | None, error: InputError, made) -> Solution:
        """The verdict of a start-up solve whose simulation failed after the solver ran (``error``: outside the
        simulator's ranges; the design a run reached, checked by its simulated start, or a start the loop drew later):
        ``not_found``, no design checked, at ``start`` (or the case's own), its runs counted (``made``: a
        :class:`~clutchopt.optimise.attempts.Tally`), so that a retry is named among the starts tried and counted,
        not taken for one whose first simulation failed (nothing solved: the InputError raised, which callers catch)."""
        lower, upper, x0 = self.posed.bounds_and_start(case, start)
        solver = SolverInfo("ipopt", "not_simulated", made.iterations, made.seconds, made.calls)
        text = f"no design checked: the solver ran, then a simulated start failed ({error.problem})"
        found = infeasible_at(self.posed, case, dict(zip(self.posed.names, map(float, x0))), text, solver,
                              bounds=(lower, upper))
        return replace(found, status="not_found")

    def _refined(self, case: Case, start: dict[str, float] | None = None, warm: Solution | WarmStart | None = None,
                 mesh: np.ndarray | None = None, refine: bool = True, diagnosed: bool = True,
                 coarser: float = math.inf, shift: dict[str, float] | None = None, cold: bool = True,
                 fixed: dict[str, tuple[float, float]] | None = None,
                 infeasible: dict[tuple, str] | None = None, sizing: dict[str, float] | None = None,
                 lighter_than: float = math.inf, first: Solution | None = None) -> Solution:
        """One solve for one case. ``warm``: a previous solution of this problem, whose design and scales start this one.

        With a start-up, the simulated start is what the limits are checked against, and the collocation's own
        error is the NLP's start time against the simulated one. While that error exceeds the case's tolerance,
        the mesh is adapted to the simulated start (MESH_STEPS times, or until an adaptation no longer halves the
        error), then the intervals doubled (up to MAX_INTERVALS, while the rate at which the last doubling cut the
        error, from ``coarser`` at half the intervals, can reach the tolerance by then). Should the simulated
        start still miss a limit, the missed limits are moved in by what the simulation adds to the NLP's figure
        (defect correction) and the problem re-solves warm; so is a binding limit the simulated start meets so far
        off that the objective is off by a quarter of the tolerance (the design then does not depend on the mesh the
        loop ended on; not for an elastic link, whose NLP is another model than its simulation). Limits are always
        reported as the case gives them. A start-up problem without a start point starts from the optimum the
        papers' sizing gives (the same mode without the start-up), a design the start-up changes but does not
        overturn. Integer variables keep their values while limits are moved in (an elastic link's excepted).
        ``refine=False``: one solve on ``mesh`` (or the warm solution's, or the first one), as it comes (for
        measuring what accuracy costs). ``shift``: a neighbouring design's ``limit_shift`` (a sweep's point before):
        the first solve sees the limits moved as its last one did, so that the correction it needed is not solved
        again; the simulated start decides as for any solve. ``cold=False``: a ``warm`` start that fails ends the
        solve (``not_found``, undiagnosed) instead of falling back to the case's own start (a sweep's point: ``solve``
        then starts cold from the papers' sizing, and diagnoses). An integer choice an earlier solve of the loop found
        infeasible by far more than that solve's collocation error is not solved again (:class:`RuledOut`). An elastic
        link's integer choice found infeasible only at limits another choice's simulated start moved, lighter than the
        kept design, is solved through its own loop (:meth:`_own_loops`); ``fixed``: integer bounds of such a loop. A
        sweep's point whose warm integers fail at the limits carried from the point before solves their own loop
        first (:meth:`_own_first`).
        A loop that ends ``unverified`` goes on in modifier adaptation
        (:func:`~clutchopt.optimise.modifier.first_order`: the limits' figures corrected in value and gradient,
        integers kept), its steps ending at a design no lighter than ``lighter_than`` (an own loop's: the kept
        design's objective). ``first``: the loop's first solve, made already (an own loop's, :meth:`_one_up_first`).
        ``infeasible``: integer choices known to have no design here, with why (:class:`RuledOut`; a start-up
        sweep's point: those the papers' sizing at the point finds infeasible, ``start_up_sweep.sized_out``);
        ``sizing``: the papers' sizing's design at the point, where a caller starting warm knows it (a start-up
        sweep's point, ``sized_out``): the integer search of each warm solve of the loop is completed by its
        integers, as a first solve's is from the sizing (:meth:`_sized`)."""
        case.require(self.objective.name, quantities=self.formulation.quantities)
        if self.start_up is None:
            return self._solve(case, start, warm, mesh=mesh, diagnosed=diagnosed)
        if not refine:
            return self._worn(case, self._solve(case, start, warm, mesh=mesh, diagnosed=diagnosed))
        sized_design = sizing  # the papers' sizing's design, for a design a row of the collocation holds
        if start is None and warm is None:
            sized = self._sizing(case)
            start = sized.design if sized.status == "optimal" else None
            sized_design = start if sizing is None else sizing
            if infeasible is None and not self.start_up.s.elastic:  # the choices the sizing's own search found
                infeasible = sized_choices(self, sized)  # infeasible (a sweep's point: given; an elastic link: none)
        structure = self.start_up.s
        nlp_case = shifted(case, shift)
        if fixed:
            nlp_case = replace(nlp_case, bounds={**nlp_case.bounds, **fixed})
        foreign = ForeignShifts(self.integer_names,
                                carried_by(warm) if limit_shift(case, nlp_case) else ()) if structure.elastic else None
        ruled = None if structure.elastic else RuledOut(infeasible)  # an elastic link's NLP differs from its
        # simulation by the model, not the mesh: no collocation error bounds what the next solve changes
        first_mesh = start is not None and warm is None and mesh is None and ruled is not None
        before: list[SolverInfo] = []  # a failed warm count's own first solve, not verified (:meth:`_own_first`)
        solution = first or self._solve(case, start, warm, nlp_case=nlp_case, mesh=mesh, diagnosed=diagnosed,
                                        ruled=ruled, cold=cold, sizing=sizing,
                                        unranked_above=UNRANKED_ERROR if first_mesh else math.inf,
                                        kept_first=coarser < math.inf,  # (a loop's doubled problem: from its design)
                                        failed_warm=None if fixed or first is not None
                                        else self._own_first(case, warm, foreign, before))
        if foreign is not None and foreign.looped:  # (the failed warm count verified at the case's limits)
            return self._worn(case, self._own_loops(case, solution, foreign))
        adapted, last_error, solves = 0, math.inf, [solution.solver, *before]
        sized_again = False  # the papers' sizing solved again, where a row of the collocation held a design
        for _ in range(MESH_STEPS + BACK_OFF_STEPS):
            if foreign is not None:
                foreign.seen(solution)
            if solution.status not in ("optimal", "unverified"):
                break
            if not sized_again and self._held(solution):  # no mesh makes it the physics' design: the sizing
                sized_again = True
                lighter = self._from_the_sizing(case, solution, nlp_case, sized_design, solves, ruled)
                if lighter is not None:
                    solution = lighter
                    break
            error = abs(solution.start_up["discretisation_error"]["start_time"])
            if ruled is not None:
                ruled.settle(error, solution.design, solution.objective)
            if error > structure.spec.tolerance and not structure.elastic:  # an elastic link: its quasi-static
                # NLP differs from the simulated dynamics by the model, not by the mesh
                if shapes_nothing(solution, self.posed.n_checked, structure.spec.tolerance, self._own_names):
                    break
                if adapted == MESH_STEPS or error > 0.5 * last_error:  # adapting no longer pays: more intervals
                    if not doubling_pays(error, coarser, structure.intervals, structure.spec.tolerance):
                        break
                    finer = replace(structure, intervals=2 * structure.intervals)
                    halved = np.repeat(solution.mesh[1], 2) / 2.0  # each interval of each phase split in two
                    solution = problem_for(self.posed.base, self.objective.name, self.options, finer).solve(
                        case, solution.design, mesh=halved, coarser=error, infeasible=ruled.known)  # its own
                    # limit_shift; the choices the papers' sizing rules out are the same on any mesh
                    solves.append(solution.solver)
                    nlp_case = None
                    break
                adapted, last_error = adapted + 1, error
                solution = self._solve(case, warm=solution, nlp_case=nlp_case, mesh=solution.mesh[1], ruled=ruled,
                                       redecide=unsettled(solution, error), sizing=sizing)
            elif (moved := corrected_case(solution, nlp_case, centre=not structure.elastic)) is not None:
                # integers kept, unless the difference is the model's (an elastic link's dynamics), not a small one
                integers = {v.name: (solution.design[v.name],) * 2 for v in self.formulation.variables
                            if v.integer and not structure.elastic}
                moved = replace(moved, bounds={**nlp_case.bounds, **integers})
                if foreign is not None:
                    foreign.corrected(solution)
                    if not fixed and (up := self._one_up_first(case, solution, moved, foreign, solves)) is not None:
                        return self._worn(case, self._own_loops(case, up, foreign))
                corrected = self._solve(case, warm=solution, nlp_case=moved, ruled=ruled)
                if corrected.status not in DESIGN_STATUSES:  # no design meets the moved limits
                    solves.append(corrected.solver)
                    if foreign is not None:
                        foreign.seen(corrected)
                    solution = uncorrected(solution, corrected)
                    break
                nlp_case, solution = moved, corrected
            else:
                break
            solves.append(solution.solver)
        if nlp_case is not None and solution.status == "unverified":  # the limits' correction reached no verified
            # design: the limits' figures corrected in value and gradient (modifier adaptation), integers kept
            solution = first_order(self, case, solution, solves, lighter_than)
            nlp_case = case if solution.status == "optimal" else nlp_case
        if nlp_case is not None and self._held(solution):  # (the doubled problem's loop decided its own)
            lighter = None if sized_again else self._from_the_sizing(case, solution, nlp_case, sized_design, solves,
                                                                     ruled)
            solution = lighter or held_note(solution)
        solution.solver = solution.solver.summed(solves)
        if nlp_case is not None:  # not the doubled problem's
            solution.limit_shift = limit_shift(case, nlp_case)
        if foreign is not None:
            foreign.seen(solution)  # (the last solve's, where the loop ran its course)
            solution.shift_measured_by = frozenset(foreign.measured)
            if not fixed:
                solution = self._own_loops(case, solution, foreign)
        return self._worn(case, solution)

    def _own_loops(self, case: Case, solution: Solution, foreign: ForeignShifts) -> Solution:
        """``solution``, or the design of an integer choice its elastic link's loop found infeasible only at limits
        another choice's simulated start moved (:class:`~clutchopt.optimise.own_shift.ForeignShifts`), lighter: each
        such choice, lightest first, is solved through its own accuracy loop (its integers fixed, from the case's
        limits, warm from ``solution``), and the first that ends optimal is kept. cable_motor_start at 0.3 kg m^2:
        7 cables' start moves the stress limit to 0.905 of the case's, where 8 cables are infeasible and 9 kept
        (4.418 kg); 8 cables' own loop solves once at the case's limit, which their simulated start meets (3.953 kg).
        Then a count one below the kept design's that no search of the loop solved (a loop started at a sweep's
        moved limits may round past it) is solved through its own loop too, and kept where it ends optimal and
        lighter, until the count below is tried (:meth:`~clutchopt.optimise.own_shift.ForeignShifts.untried_below`).
        Where the loop keeps an ``unverified`` design, the counts above it are solved through their own loops, one
        up at a time while each comes nearer to its limits, and the first that ends optimal kept (:meth:`_climbed`
        from :meth:`~clutchopt.optimise.own_shift.ForeignShifts.above_unverified`; cable_motor_start at a motor
        inertia of 0.027 kg m^2: 8 cables unverified, 12 kept). A lighter choice the loop kept ``unverified`` goes on
        in modifier adaptation first (:meth:`_first_order`; the cable at 0.5 kg m^2: 8 cables' start carries 0.44 %
        more than the stress allowed, their defect correction has no design at the moved limit, their modifier
        adaptation verifies them at 4.257 kg against 9 cables' 4.418 kg: docs/start_up.md)."""
        kept, runs = solution, [solution.solver]
        for combo in foreign.lighter(solution):
            kept, own = self._own_loop(case, solution, kept, foreign, combo, runs)
            if kept is own:
                break
        for unverified in foreign.unverified_below(kept):  # a lighter choice kept unverified: modifier adaptation
            kept, better = self._first_order(case, kept, foreign, unverified, runs)
            if better:
                break
        bounds = self._integer_bounds(case)
        upper = {name: hi for name, (_, hi) in bounds.items()}
        for combo in foreign.above_unverified(kept, upper):  # counts up while their simulated starts come nearer
            kept = self._climbed(case, solution, kept, foreign, combo, upper, runs)
        lower = {name: lo for name, (lo, _) in bounds.items()}
        while below := foreign.untried_below(kept, lower):  # a count below the kept one its search never solved
            kept, _ = self._own_loop(case, solution, kept, foreign, below[0], runs)
        for combo, first in foreign.first.items():  # a count solved first whose own loop never ran (its solve
            kept.integer_search = kept.integer_search + [own_entry(foreign.names, combo, first, FIRST_UP)]  # counted)
        own = foreign.choice(kept.design) if kept.status in DESIGN_STATUSES else None  # (its design is the record)
        kept.integer_search = kept.integer_search + [  # a count whose start at the case's limits missed one, said
            own_entry(foreign.names, combo, seen, AT_THE_CASE) for combo, seen in foreign.unverified_at_the_case.items()
            if combo not in foreign.first and combo != own]  # (a count solved first: its own entry says so)
        foreign.first.clear()
        kept.unverified_at_the_case = frozenset(foreign.unverified_at_the_case)
        if len(runs) > 1:
            kept.solver = kept.solver.summed(runs)
        return kept

    def _own_loop(self, case: Case, solution: Solution, kept: Solution, foreign: ForeignShifts, combo: tuple,
                  runs: list) -> tuple[Solution, Solution]:
        """The integer choice ``combo`` solved through its own accuracy loop (its integers fixed, from the case's
        limits, warm from ``solution``, or from its first solve made already: :meth:`_one_up_first`), recorded in
        ``kept``'s integer search and ``runs``: its design where it ends optimal and lighter than ``kept`` (or ``kept``
        has none verified), else ``kept``; and its own solution."""
        fixed = {name: (value, value) for name, value in zip(foreign.names, combo)}
        own = self._refined(case, warm=solution, diagnosed=False, cold=False, fixed=fixed,
                            lighter_than=kept.objective if kept.status == "optimal" else math.inf,
                            first=foreign.first.pop(combo, None))
        foreign.own_loop(combo)
        runs.append(own.solver)
        return _recorded(kept, foreign.names, combo, own), own

    def _integer_bounds(self, case: Case) -> dict[str, tuple[float, float]]:
        """Each integer variable's bounds: the case's, else the formulation's."""
        return {v.name: case.bounds.get(v.name, (v.lower, v.upper)) for v in self.formulation.variables if v.integer}

    def _one_up_first(self, case: Case, solution: Solution, moved: Case, foreign: ForeignShifts,
                      solves: list) -> Solution | None:
        """An elastic link's defect correction (``moved``: the limits ``solution``'s simulated start moved) where the
        link's least stress refutes both ``solution``'s count and the count one up at the moved limits
        (:func:`~clutchopt.optimise.link_bound.refuted`): the search there would exclude the two (the first at its own
        shift, the second at a shift its own start did not measure), keep a count further up, simulate it, and then
        solve the count one up through its own loop (:meth:`_own_loops`), whose first solve is at the case's limits.
        That solve is made first, warm from ``solution``; where its simulated start verifies it (the own loop then
        ends there, whatever design is kept beside it), it is returned as the own loop's, recorded as the search's
        own loops record it, every solve counted (``solves``), and the search at the moved limits is not solved. Else
        None: the correction goes on as ever, and the count's own loop later goes on from that solve (counted in
        ``solves``). cable_motor_start: 7 cables' start moves the stress limit to 314.2 MPa, where 7 cables' least
        stress is 341 MPa and 8's 314.24; 9 cables were solved and simulated there before 8's own loop kept 8
        (3.953 kg): 5 solves and 4 simulated starts, now 3 and 3, the design the same to 4e-13. It assumes the count
        one up, verified at the case's limit, is no heavier than what the search at the tighter moved limit keeps
        further up (the objective rising with the count above the refuted ones): review h17 found no counterexample
        in 288 variants (mass, cost, envelope mass; both modes; six quantities), the rule firing at 56."""
        names = foreign.names
        combo = foreign.choice(solution.design)
        if len(names) != 1 or combo[0] + 1.0 > self._integer_bounds(case)[names[0]][1]:
            return None
        up = (combo[0] + 1.0,)
        if not self._link_refutes(case, moved, solution, (combo, up)):
            return None
        own = self._first_at_the_case(case, solution, up, foreign, solves)
        if own is None:
            return None
        foreign.own.add(combo)  # (found at its own shift, as the search there finds it)
        kept = _recorded(solution, names, up, own)
        kept.solver = kept.solver.summed(solves)
        return kept

    def _own_first(self, case: Case, warm: Solution | WarmStart | None, foreign: ForeignShifts | None,
                   solves: list[SolverInfo]) -> Callable | None:
        """A sweep point's first solve's ``failed_warm`` (:meth:`_solve`) where its elastic link's loop starts at the
        limits the point before's loop moved (carried, :func:`carried_by`): where the point before's count fails at
        them, its own loop's first solve (:meth:`_first_at_the_case`, warm from the point before) is made before the
        relaxation there; where its simulated start verifies it, that is the point's first solve's design, recorded
        after the failed run, every solve counted, and the own loops go on from it (:meth:`_own_loops`: the counts
        below); else the search at the carried limits goes on, that solve in ``solves`` (the own loop, where it comes,
        goes on from it). It assumes, as :meth:`_one_up_first` does, that the count verified at the case's limits is
        no heavier than what the search at the tighter carried limits keeps further up. cable_motor_start over
        driven_inertia 0.6x-1.4x at points 10, 12 and 16: 8 cables fail at the limit 7 cables' start moved, the
        relaxation and 9 cables (4.4178 kg) were solved there before 8's own loop kept 8 (3.9526 kg): 5, 5, 4 solver
        calls, now 3, 3, 2. None where no limit was carried, or for more than one integer variable."""
        if foreign is None or CARRIED not in foreign.measured or len(foreign.names) != 1:
            return None

        def failed_warm(combo: tuple, search: list[dict], runs: list[dict], data: ScaledData) -> Solution | None:
            own = self._first_at_the_case(case, warm, combo, foreign, solves)
            if own is None:
                return None
            own.integer_search = search + [own_entry(foreign.names, combo, own)]
            own.bounds = self.posed.named_bounds(data.lower, data.upper)
            own.solver = own.solver.summed([spent_on(runs, own.solver.name, ""), *solves])  # (with the failed run)
            return own

        return failed_warm

    def _first_at_the_case(self, case: Case, warm: Solution | WarmStart, combo: tuple, foreign: ForeignShifts,
                           solves: list[SolverInfo]) -> Solution | None:
        """The integer choice ``combo``'s own loop's first solve (its integers fixed, at the case's limits, warm from
        ``warm``: as ``_refined`` with ``fixed`` makes it), made before its own loop, counted in ``solves``: its
        design where its simulated start verifies it (the own loop ends there: not held, no limit missed), recorded
        as looped; else None, its design kept for the own loop to go on from (``ForeignShifts.first``; none: its
        own loop solves it, as ever). A choice solved first already is not solved again (None)."""
        if combo in foreign.first:
            return None
        own_case = replace(case, bounds={**case.bounds, **{n: (v, v) for n, v in zip(foreign.names, combo)}})
        own = self._solve(case, warm=warm, nlp_case=own_case, diagnosed=False, cold=False)
        solves.append(own.solver)
        foreign.simulated_at_the_case(own)
        if own.status != "optimal" or self._held(own) or corrected_case(own, own_case, centre=False) is not None:
            if own.status in DESIGN_STATUSES:  # (its own loop goes on from it, counted here; from none, as ever)
                foreign.first[combo] = replace(own, solver=replace(own.solver, iterations=0, time_s=0.0, solves=0))
            return None
        own.limit_shift, own.shift_measured_by = {}, frozenset()  # (its own loop's: at the case's limits)
        foreign.own_loop(combo)
        return self._worn(case, own)

    def _link_refutes(self, case: Case, nlp_case: Case, solution: Solution, choices) -> bool:
        """Whether the link's least stress refutes each of the integer ``choices`` (tuples of the integer variables)
        at ``nlp_case``'s limits, at the nodes of ``solution``'s point of ``case``
        (:func:`~clutchopt.optimise.link_bound.refuted`: no design of the NLP has them)."""
        posed = self.posed
        data = posed.scaled_data(nlp_case, solution.design, solution.scale, solution.internal, solution.mesh[0],
                                 posed.params(case))
        integer = posed.free_integers(data)
        for choice in choices:
            lbx, ubx, x0 = fixed_box(data, integer, np.array(choice), data.x0)
            if not refuted(posed, data, x0, lbx, ubx):
                return False
        return True

    def lighter_settled(self, case: Case, solution: Solution) -> bool:
        """Whether each count below ``solution``'s (an elastic link's one integer variable, down to its lower bound)
        is settled at ``case`` already: its design of the NLP at the case's limits simulated in ``solution``'s solve,
        unverified (AT_THE_CASE: evidence ``solve``'s path goes no further with, not a proof), or solved through its
        own accuracy loop there (``own_shift.unverified_here``), or refuted by the link's least stress at the case's
        limits (:meth:`_link_refutes`: no design of the NLP has it). False for any other problem, or a solution not
        ``optimal``."""
        names = self.integer_names
        if self.start_up is None or not self.start_up.s.elastic or len(names) != 1 or solution.status != "optimal":
            return False
        lower = self._integer_bounds(case)[names[0]][0]
        below = [(float(count),) for count in range(math.ceil(lower), round(solution.design[names[0]]))]
        return self._link_refutes(case, case, solution, [combo for combo in below
                                                          if not unverified_here(names, solution, combo)])

    def _climbed(self, case: Case, solution: Solution, kept: Solution, foreign: ForeignShifts, combo: tuple,
                 upper: dict[str, float], runs: list) -> Solution:
        """``kept`` (``unverified``), or the design of the first count up from it that its own accuracy loop
        verifies: from ``combo`` (one count up in one integer) each count is solved through its own loop
        (:meth:`_own_loop`) and the next one up tried while the last one's simulated start comes nearer to meeting
        its limits (its worst margin grows: :func:`~clutchopt.optimise.own_shift.climbing`), until one ends optimal,
        or the trend says no count within the ``upper`` bound will (why is added to ``kept``'s diagnosis); from a
        verified count on, while each count up comes out lighter (:func:`~clutchopt.optimise.own_shift.lighter_above`).
        An elastic link's stress falls as cables are added, but its loop may find a count infeasible at the limit its
        own start moved: cable_motor_start at a motor inertia of 0.027 kg m^2, 2.21 s allowed: 8 cables kept, their
        simulated stress 81 % over; 9 cables' own loop unverified, 10 cables' verified at 7.307 kg (their weights
        made heavy by modifier adaptation), 11 at 6.276 kg, 12 at 5.81260 kg, the sweep's design, 13 at 6.277 kg,
        heavier: 12 kept (tests/test_hostile_agree2.py)."""
        last, i = kept, stepped(foreign.names, kept.design, combo)
        while True:
            kept, own = self._own_loop(case, solution, kept, foreign, combo, runs)
            if kept.status == "optimal":  # a count verified: on while each count up comes out lighter
                ahead = lighter_above(foreign.names, i, own, kept, combo, upper)
                if ahead is None:
                    return kept
            else:
                ahead, reason = climbing(foreign.names, i, last, own, combo, upper)
                if ahead is None:
                    kept.diagnosis = f"{kept.diagnosis}; {reason}" if kept.diagnosis else reason
                    return kept
            last, combo = own, ahead

    def _first_order(self, case: Case, kept: Solution, foreign: ForeignShifts, unverified: Solution,
                     runs: list) -> tuple[Solution, bool]:
        """Modifier adaptation from ``unverified`` (a design of another integer choice the loop kept, its simulated
        start missing a limit: :meth:`~clutchopt.optimise.own_shift.ForeignShifts.unverified_below`), its integers
        fixed, each step warm from the last and stopped at a design no lighter than ``kept``
        (:func:`~clutchopt.optimise.modifier.first_order`), recorded in ``kept``'s integer search and ``runs`` as an
        own loop of the choice: its design where it ends optimal and lighter, else ``kept``; and whether it was."""
        combo = foreign.choice(unverified.design)
        steps: list = []
        excluded: list = []
        own = first_order(self, case, unverified, steps, kept.objective, excluded)
        foreign.own_loop(combo)
        if excluded:  # its first step refuted unsolved (``modifier.no_lighter``)
            kept.integer_search = kept.integer_search + [excluded_own_entry(foreign.names, combo, VARIANT, excluded)]
        if not steps:
            return kept, False
        spent = (own.solver if own is not unverified else steps[-1]).summed(steps)  # (the loop's design untouched)
        if own is not unverified:
            own.solver = spent
        runs.append(spent)
        better = _recorded(kept, foreign.names, combo, own, VARIANT)  # (``kept`` optimal: ``unverified_below``)
        return better, better is own

    def _given(self, case: Case, data: ScaledData, runs: list[dict]) -> Solution | None:
        """The verdict on a static case that breaks a requirement no design variable enters
        (:func:`~clutchopt.optimise.diagnosis.whatever_the_design`: the wedge's release condition in paper mode, its
        flank angle given, at f above tan(alpha - margin)) before a cold solve from ``data``: ``infeasible``, proven,
        at its start design, every constraint re-evaluated in float64, the calls before it (``runs``: a warm attempt)
        counted; else None. An IPOPT solve there (13 iterations on the wedge) ended at a point of its own, which the
        verdict showed, and then diagnosed it."""
        posed = self.posed
        given = whatever_the_design(posed, data.p, data.x0) if posed.fixed_rows or posed.sides.pairs else None
        if given is None:
            return None
        solution = infeasible_at(posed, case, dict(zip(posed.names, map(float, data.start))), given.text,
                                 spent_on(runs, PROVEN, "proven"), bounds=(data.lower, data.upper))
        solution.diagnosed = given
        return solution

    def proven(self, case: Case, proofs: list[str]) -> Solution:
        """The verdict on a start-up the drive makes impossible (``proofs``, in words): ``infeasible``, without a
        start-up solve (each would end without a design, then be retried and diagnosed: lever_motor_start with 6 s
        allowed took 3 solves, 305 IPOPT iterations and 2.5 s to end `not_found`). The design shown is the papers'
        sizing at the case (one static solve: where a start-up solve would begin), its constraints re-evaluated in
        float64; its diagnosis a proof, so that :meth:`solve` gives it as it is (no retry: ``verdict.shown``)."""
        sized = self._sizing(case)
        lower, upper, x0 = self.posed.bounds_and_start(case, sized.design)
        text = "proven infeasible: " + "; ".join(proofs)
        solution = infeasible_at(self.posed, case, dict(zip(self.posed.names, map(float, x0))), text,
                                 SolverInfo(PROVEN, "proven", sized.solver.iterations, sized.solver.time_s,
                                            sized.solver.solves), bounds=(lower, upper))
        solution.diagnosed = Diagnosis("infeasible", text, 0.0, proven=True)
        return solution

    @property
    def static_problem(self) -> "Problem":
        """The papers' sizing's problem: the same formulation without the start-up, the same objective and options
        (built once: :func:`problem_for`), its IPOPT optimum not polished (``SolverOptions.polish``): the start-up
        solves start from the sizing as they did before the polish, each with its own tolerance contract."""
        return problem_for(self.posed.base, self.objective.name, replace(self.options, polish=False))

    @property
    def modified_problem(self) -> "Problem":
        """This problem posed with modifier adaptation's parameters
        (:func:`~clutchopt.optimise.modifier.with_modifiers`): built once a process, on first use (0.06 s for the
        cable, its warm IPOPT 0.04 s more)."""
        return problem_for(with_modifiers(self.posed.base), self.objective.name, self.options, self.start_up.s)

    def _held(self, solution: Solution) -> bool:
        """:func:`held_by_the_mesh` for this problem's start-up."""
        return held_by_the_mesh(solution, self.posed.n_checked, self.start_up.s.spec.tolerance, self._own_names)

    def _from_the_sizing(self, case: Case, held: Solution, nlp_case: Case, sizing: dict[str, float] | None,
                         solves: list, ruled: RuledOut | None = None) -> Solution | None:
        """The papers' sizing's optimum solved as a start-up design, where a row of the collocation holds ``held``
        (:func:`held_by_the_mesh`) and the sizing ends ``optimal`` and lighter; else None. No start-up limit holds
        ``held``, so the static constraints alone bind where the physics has its optimum: the sizing's, a relaxation
        of this problem where its rows are the start-up's own (the same formulation without the start-up limits:
        the ball's and the cable's; the wedge's and the lever's sizing keep the constant-acceleration torque row the
        start-up drops, tests/test_start_up_relaxation.py), is the optimum wherever its simulated start meets every
        limit. It is solved in two steps on the mesh its own simulated start draws
        (:func:`~clutchopt.start_up.transcription.mesh_of_the_start`; ``held``'s mesh has no collocated start of it,
        the lighter side of its fold): its design fixed (the collocation's states follow it), then freed, warm from
        that point (IPOPT's barrier from 1e-9: a KKT point where the collocation follows the design, so it stays).
        Every solve's SolverInfo is added to ``solves``; ``ruled``: the loop's integer choices not to solve again
        (the freed solve's search skips them as the loop's solves do) (docs/start_up.md, "A design a row of the
        collocation holds")."""
        sizing = self.sized_design(case) if sizing is None else sizing
        if sizing is None:
            return None
        posed = self.posed
        fixed = replace(nlp_case, bounds={**nlp_case.bounds, **{name: (value, value) for name, value in
                                                               sizing.items() if name in posed.names}})
        seen, design = posed.start_up_seen(fixed, dict(zip(posed.names, posed.bounds_and_start(fixed, sizing)[2])))
        mesh = mesh_of_the_start(posed.start_up, seen, self.formulation, design)
        states = self._solve(case, sizing, nlp_case=fixed, mesh=mesh, diagnosed=False)
        solves.append(states.solver)
        if states.status != "optimal" or states.objective >= held.objective:
            return None
        freed = self._solve(case, warm=states, nlp_case=nlp_case, mesh=mesh, diagnosed=False, cold=False, ruled=ruled,
                            sizing=sizing)
        solves.append(freed.solver)
        return freed if freed.status == "optimal" and freed.objective < held.objective else None

    def _sizing(self, case: Case) -> Solution:
        """The papers' sizing at ``case``: :attr:`static_problem` solved (where a start-up solve begins)."""
        return self.static_problem.solve(case)

    def sized_design(self, case: Case) -> dict[str, float] | None:
        """The papers' sizing's design at ``case`` where it is optimal, else None."""
        sized = self._sizing(case)
        return sized.design if sized.status == "optimal" else None

    @cached_property
    def integer_names(self) -> list[str]:
        """The formulation's integer variables' names."""
        return [v.name for v in self.formulation.variables if v.integer]

    def _warm_method(self, warm: Solution | WarmStart, mesh: np.ndarray | None) -> str:
        """``warm_near`` (IPOPT's barrier from 1e-9) for a start-up re-solved on the mesh its warm optimum was solved
        on (a limit correction, a sweep's next point): the optimum moves by what the limits or the case moved;
        ``warm`` (from 1e-6) otherwise, an adapted mesh moving it by up to the collocation's error (the ball's
        first adaptation: its previous rows found infeasible in 68 iterations from 1e-6, 129 from 1e-9)."""
        same_mesh = self.start_up is not None and warm.mesh is not None and np.array_equal(mesh, warm.mesh[0])
        return "warm_near" if same_mesh else "warm"

    def _worn(self, case: Case, solution: Solution) -> Solution:
        """The solution a solve returns, its start on worn linings simulated (:func:`worn_start`; the lever)."""
        if solution.start_up is not None:
            worn_start(solution.start_up, *self.posed.start_up_seen(case, solution.design), self.formulation.mode)
        return solution

    def _solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | WarmStart | None = None,
               nlp_case: Case | None = None, mesh: np.ndarray | None = None,
               diagnosed: bool = True, ruled: RuledOut | None = None, cold: bool = True,
               redecide: bool = False, sizing: dict[str, float] | None = None,
               heavier: float = math.inf, unranked_above: float = math.inf, kept_first: bool = False,
               failed_warm: Callable[[tuple, list[dict], list[dict], ScaledData], Solution | None] | None = None
               ) -> Solution:
        """One solve (with its integer search); the NLP sees ``nlp_case`` (moved limits), the checks ``case``;
        a start-up's mesh is ``mesh``, else the warm solution's, else the first one; ``ruled``: integer choices
        not to solve again, and where those found infeasible are recorded; ``cold=False``: no cold start after a
        failed warm one; ``redecide``: the warm solution's integers are not tried first, the relaxation is solved
        (warm) and its integers searched as a first solve's (:func:`unsettled`); ``sizing``: the papers' sizing at
        the point, whose integers a warm start-up solve's search is completed by (:meth:`_sized`); ``heavier``: a
        start-up design this heavy or heavier is of no use to the caller, its start not simulated (:meth:`_finish`);
        ``unranked_above``: the neighbours of the relaxation's rounded integers are not solved where those integers'
        design's simulated start shows the mesh too coarse to rank them (:meth:`_unranked`); ``kept_first``: a cold
        start's integers (``start``'s) are solved first and descended from, the relaxation only where they fail
        (:meth:`_kept_first`); ``failed_warm(combo, search, runs, data)``: where the warm integers ``combo`` fail, the
        caller's design instead of the relaxation's search (None: the search goes on with the same ``search`` and
        ``runs``: :meth:`_refined`, an elastic link's kept count's own loop first)."""
        posed = self.posed
        warm_ok = warm is not None and warm.status in ("optimal", "unverified") and warm.scale is not None
        if mesh is None and warm_ok and warm.mesh is not None and len(warm.mesh[0]) == posed.mesh_size:
            mesh = warm.mesh[0]
        solved, checked = nlp_case or case, posed.params(case)
        duals = warm_multipliers(posed, *warm.multipliers) if warm_ok else None
        if duals is not None and len(duals[1]) != len(posed.lbg):
            duals = None  # a warm start from another problem (e.g. uncapped) gives its point only
        runs: list[dict] = []
        search: list[dict] = []
        relaxed = None
        if warm_ok:
            data = posed.scaled_data(solved, warm.design, warm.scale, warm.internal, mesh, checked)
            warm_ok = self.start_up is not None or not posed.conflicting(solved)  # (limits with no room between: the
            # cold path's verdict, without a solve; warm, SQP solved the kept row, posed where the rows cross)
        if warm_ok:
            integer = posed.free_integers(data)
            if not integer and (refuted_here := self._link_refuted(case, data)) is not None:
                return refuted_here
            seed = {"x": data.x0, "lam_x": duals[0], "lam_g": duals[1]} if duals is not None else None
            combo = np.array([warm.design[posed.names[i]] for i in integer])
            sqp = ("sqp",) if self.options.warm_sqp and self.start_up is None else ()  # small dense NLPs only
            methods = sqp + (self._warm_method(warm, mesh),) if seed is not None else ("ipopt",)
            if integer and seed is not None and within(data, integer, combo):
                attempt_at = fixing(posed, data, runs, search, ruled)
                kept = None if redecide else descend(posed, data.box, integer, combo, seed, search, attempt_at,
                                                     first=methods)
                if kept is not None:
                    kept = self._sized(solved, data, integer, kept, search, attempt_at, sizing)
                    return self._finish(case, kept, runs, data, search, heavier=heavier)
                if not redecide and failed_warm is not None and (
                        decided := failed_warm(tuple(map(float, combo)), search, runs, data)) is not None:
                    return decided
                seed, methods = relaxation_seed(seed, integer), ("warm",)  # the previous integers fail here (or
                # are decided again: ``redecide``)
            run = attempt(posed, data, data.lbx, data.ubx, data.x0, seed, methods, runs)
            relaxed = run if run["ok"] else None
        if relaxed is None and warm_ok and not cold:
            return self._finish(case, run, runs, data, search, ("not_found", "no design from the warm start"))
        if relaxed is None:  # cold: from the case's own start
            data = posed.scaled_data(solved, start, mesh=mesh, checked=checked)
            if self.start_up is None and (given := self._given(case, data, runs)) is not None:
                return given  # (a requirement no design variable enters, broken: no solve)
            if kept_first and (kept := self._kept_first(data, runs, search, ruled)) is not None:
                return self._finish(case, kept, runs, data, search, heavier=heavier)
            relaxed = attempt(posed, data, data.lbx, data.ubx, data.x0, None, ("ipopt",), runs)
        n = len(data.scale)
        x_opt = relaxed["x"][:n] * data.scale
        if relaxed["ok"] and off_scale(relaxed["x"][:n]):  # the start was far off: solve again, scaled by the
            # first optimum, warm from it (cold where that fails)
            before = data
            data = posed.scaled_data(solved, dict(zip(posed.names, x_opt)), None, relaxed["x"][n:],
                                     posed.mesh_of(data.p), checked)
            relaxed = attempt(posed, data, data.lbx, data.ubx, data.x0, rescaled_seed(relaxed, before, data),
                              ("warm",), runs)
            if not relaxed["ok"]:
                relaxed = attempt(posed, data, data.lbx, data.ubx, data.x0, None, ("ipopt",), runs)
        integer = posed.free_integers(data)
        if not relaxed["ok"] and not diagnosed:  # a retry before a verdict: its own diagnosis is not needed
            return self._finish(case, relaxed, runs, data, search, ("not_found", "no design from this start"))
        diagnosis = None
        if not relaxed["ok"] and self.start_up is not None:
            relaxed, diagnosis = self._from_the_elastic_point(relaxed, data, runs)
        if not integer or not relaxed["ok"]:
            return self._finish(case, relaxed, runs, data, search, diagnosed=diagnosis, heavier=heavier)
        attempt_at = fixing(posed, data, runs, search, ruled)
        first: list[tuple] = []  # the first kept run, its Solution, the runs then, why its neighbours are not solved

        def unranked(seed: dict) -> str | None:  # the first kept run's neighbours (the relaxation's own, and those
            # of a design the descent went on to, solved as ever)
            if seed is relaxed or seed["x"] is relaxed["x"]:  # (or nearest_integers' copy of it)
                return None
            if not first:
                first.append((seed, *self._unranked(case, seed, runs, data, search, unranked_above, heavier)))
            return first[0][3] if seed is first[0][0] else None

        # (a start that meets every row, whose integers :func:`from_the_start` solves, may beat the kept design:
        # the search then runs in full)
        ranks = unranked_above < math.inf and not meets_every_row(posed, data.x0, data.p)
        near = fixing(posed, data, runs, search, ruled, unranked) if ranks else attempt_at
        by_sqp = posed.start_up is None and posed.options.polish and posed.options.warm_sqp  # (not a start-up's
        # NLPs, nor its papers' sizing, which is not polished either: IPOPT from cold, their starts as they were; nor
        # where SQP is switched off, SolverOptions.warm_sqp)
        kept = nearest_integers(posed, data.box, integer, relaxed, search, near,
                                FROM_THE_RELAXATION if by_sqp else ("ipopt",))
        if self.start_up is not None and start is not None and not warm_ok:  # a first solve, from the sizing
            kept = from_the_start(posed, data, integer, kept, search, attempt_at)
        else:
            kept = self._sized(solved, data, integer, kept, search, attempt_at, sizing)
        if first and first[0][1] is not None and kept is first[0][0] and first[0][2] == len(runs):
            return first[0][1]  # (its simulation reused)
        if kept is None:  # the relaxation is feasible, no integer near it is
            tried = "; ".join(", ".join(f"{k}={v}" for k, v in e.items() if k in posed.names) for e in search)
            return self._finish(case, runs[-1], runs, data, search,
                                ("infeasible", f"infeasible in integers: the continuous relaxation is feasible "
                                 f"but none of the integer neighbours is ({tried})"))
        return self._finish(case, kept, runs, data, search, heavier=heavier)

    def _kept_first(self, data: ScaledData, runs: list[dict], search: list[dict],
                    ruled: RuledOut | None) -> dict | None:
        """A cold solve's search from its start's integers (``data``'s): they are fixed and solved from the start, and
        :func:`~clutchopt.optimise.integers.descend` goes on from there, as a warm solve's search goes on from its
        warm integers; the kept run, or None where they fail (or lie outside the bounds): the relaxation is solved
        then, as ever. A loop's doubled problem starts so (:meth:`_refined`): its start is the loop's design on the
        same intervals halved, whose integers the loop decided, and its relaxation rounded to them again
        (ball_motor_start over driven_inertia at 351.3 and 382.9 kg m^2: 23 and 25 rows, 15 IPOPT iterations and
        about 19 ms at 32 intervals each; every design of the ball's sweeps and of `solve` alone the same rows, the
        objectives within 1e-13)."""
        posed = self.posed
        integer = posed.free_integers(data)
        combo = np.round(data.start[integer])
        if not integer or not within(data, integer, combo):
            return None
        attempt_at = fixing(posed, data, runs, search, ruled)
        return descend(posed, data.box, integer, combo, {"x": data.x0}, search, attempt_at)

    def _link_refuted(self, case: Case, data: ScaledData) -> Solution | None:
        """The verdict on a warm start-up solve whose integers are all fixed (an elastic link's own loop, its defect
        correction's solve at the moved limit) where their least link stress at the warm point's nodes is over the
        stress limit the NLP solves with (:func:`~clutchopt.optimise.link_bound.least_stress`, as the integer search
        excludes a choice, ``integers.fixing``): ``infeasible`` without a solve, the warm design shown, proven where
        the NLP solves with the case's own limit (at one the defect correction moved in, of that NLP alone); else
        None. Its callers: the defect correction, the own loop, ``solved_along``'s and the freed solve's warm starts,
        a walk's last solve, none of which makes it the case's verdict. cable_motor_start over driven_inertia
        0.6x-1.4x: 7 cables' own loop at the limit their simulated start moved in (314-321 MPa; their least stress 341
        MPa) took a failed warm run and a failed cold one, 10-20 and 33-45 IPOPT iterations, at 13 of the 20 points;
        its verdict the same (the loop keeps their design ``unverified``)."""
        posed = self.posed
        if self.start_up is None or not self.start_up.s.elastic or modifiers_in(data.params):  # (modifier
            return None  # adaptation's limits: its own bound, ``modifier.no_lighter``)
        least = least_stress(posed, data, np.clip(data.x0, data.lbx, data.ubx), data.lbx, data.ubx)
        limit = getattr(data.params, "max_link_stress", math.inf)
        if least is None or not least > limit * (1.0 + LINK_MARGIN):
            return None
        own = case.values.get("max_link_stress", math.inf)
        proven = limit == own  # (a proof of the case itself only at its own limit; at a limit the defect correction
        # moved in, of that NLP alone: a correction, an own loop, not the case's verdict)
        text = (f"{'proven infeasible' if proven else 'infeasible at the moved limit'}: link_stress: the least stress "
                f"of every design at these integers, {least / 1e6:.6g} MPa at the locked drive's nodes, is over the "
                f"limit the NLP solves with, {limit / 1e6:.6g} MPa"
                + ("" if proven else f" (the case's {own / 1e6:.6g} MPa)"))
        solution = infeasible_at(posed, case, dict(zip(posed.names, map(float, data.start))), text,
                                 SolverInfo(PROVEN, "proven", 0, 0.0, 0), bounds=(data.lower, data.upper))
        solution.diagnosed = Diagnosis("infeasible", text, 0.0, proven=proven, violated=("link_stress",))
        return solution

    def _unranked(self, case: Case, run: dict, runs: list[dict], data: ScaledData, search: list[dict],
                  above: float, heavier: float) -> tuple[Solution | None, int, str | None]:
        """A first mesh's kept design ``run`` (the relaxation's rounded integers) finished (its Solution; the number
        of ``runs`` then) and why its neighbours are not solved on this mesh: its simulated start shows the mesh too
        coarse to rank them (the start time's collocation error over ``above``) and the accuracy loop adapts the mesh
        from it (the error over the case's tolerance too, which may be up to 1e-2; a design its limits shape: not
        :func:`shapes_nothing`, not held by the mesh), where the integers are decided again (:func:`unsettled`). Else
        None: they are solved (the simulation, about 3 ms, spent; a simulation that fails leaves no Solution).
        ball_motor_start: 24 rows at error 1.1e-2; 25 rows, within 7.6e-4 of them, not solved there (12 IPOPT
        iterations); the adapted mesh decides again and keeps 25 rows, the design the same to the last bit.
        ``heavier``: as for :meth:`_finish`."""
        try:
            solution = self._finish(case, run, runs, data, search, heavier=heavier)
        except InputError:  # (its start not simulated: the neighbours solved, as ever; a design kept is simulated
            return None, len(runs), None  # where it is finished)
        if solution.status not in ("optimal", "unverified"):
            return solution, len(runs), None
        error = abs(solution.start_up["discretisation_error"]["start_time"])
        if (not error > max(above, self.start_up.s.spec.tolerance) or self._held(solution)  # (an error not a number:
                # no adaptation, none left)
                or shapes_nothing(solution, self.posed.n_checked, self.start_up.s.spec.tolerance, self._own_names)):
            return solution, len(runs), None
        return solution, len(runs), f"the mesh's collocation error {error:.2g} is too coarse to rank it"

    @cached_property
    def _own_names(self) -> frozenset[str]:
        """The coupling's own quantities and design variables (a variable a case fixes by its bounds has a
        sensitivity of its name): what the start-up's drive, load and limits are not (:func:`shapes_nothing`)."""
        return frozenset(q.name for q in self.posed.base.quantities) | {v.name for v in self.formulation.variables}

    def _sized(self, solved: Case, data: ScaledData, integer: list[int], kept: dict | None, search: list[dict],
               attempt_at, sizing: dict[str, float] | None) -> dict | None:
        """A warm start-up solve's search (of the NLP at ``solved`` on ``data``; ``kept``: its kept run) completed by
        the papers' sizing's integers, as a first solve's is by its start
        (:func:`~clutchopt.optimise.integers.from_the_start`), where it ended without a design or on other integers
        than the sizing's: the sizing's point of this NLP (its design on ``data``'s scales, its states simulated on
        ``data``'s mesh) is built only where the sizing may win. A search from a neighbouring optimum that keeps the
        sizing's integers, heavier, is left as it is: its design is the mesh's (ball_motor_start at 288.2 kg m^2, the
        loop's first solve: 23 rows at 957.55 kg, the same from the sizing, one solve more; the loop's next solve
        then decided the rows again, ended without a design and the sweep solved the point cold). ``sizing``: None
        (not known: a sweep's point before its sizing is solved, ``start_up_sweep.sized_out``): ``kept`` as it is."""
        posed = self.posed
        if self.start_up is None or sizing is None or kept is not None and all(
                round(kept["design"][posed.names[i]]) == round(sizing[posed.names[i]]) for i in integer):
            return kept
        mesh = posed.mesh_of(data.p)

        def point() -> np.ndarray | None:  # (None: the sizing cannot be simulated here, outside the simulator's
            # ranges: the warm search's design is kept)
            try:
                return posed.scaled_data(solved, sizing, data.scale, None, mesh, data.checked).x0
            except InputError:
                return None

        design = posed.bounds_and_start(solved, sizing)[2]
        return from_the_start(posed, data, integer, kept, search, attempt_at, (design, point))

    def _from_the_elastic_point(self, failed: dict, data: ScaledData,
                                runs: list[dict]) -> tuple[dict, Diagnosis | None]:
        """A start-up's failed cold run and its diagnosis; where the elastic problem finds a point of the NLP (its
        slacks zero: ``solver_failed``), the run from that point (design and states) instead. IPOPT's restoration
        can end ``Infeasible_Problem_Detected`` on a first, coarse mesh whose relaxation is feasible:
        ball_motor_start at 403.9-410 kg m^2 (docs/start_up.md, "A feasible point on the first mesh"); solved from
        the elastic point (15 iterations), the accuracy loop then decides on the meshes that resolve the start; the
        elastic solve's seconds counted in that run's (its diagnosis is not shown)."""
        diagnosed = diagnose(self.posed, failed["p"], failed["lbx"], failed["ubx"], failed["x"], data.scale)
        if diagnosed.status != "solver_failed" or diagnosed.point is None:
            return failed, diagnosed
        rescued = attempt(self.posed, data, data.lbx, data.ubx, diagnosed.point, None, ("ipopt",), runs)
        if not rescued["ok"]:
            return failed, diagnosed
        rescued["time"] += diagnosed.seconds  # (``_finish`` sums the runs' times)
        return rescued, None

    def _finish(self, case, run, runs, data: ScaledData, search, verdict=None,
                diagnosed: Diagnosis | None = None, heavier: float = math.inf) -> Solution:
        """The Solution of a solve's kept run: its float64 checks (and a start-up's simulated ones) with their
        multipliers, its status (``verdict``, or by the checks, or the diagnosis of a failed run: ``diagnosed``,
        where it is made already), sensitivities. A start-up design whose float64 objective is ``heavier`` or more
        ends ``not_found`` (:func:`no_lighter`) without its start simulated: the caller has a lighter design
        (modifier adaptation's step, :func:`~clutchopt.optimise.modifier.first_order`, stops there whatever the
        simulation says)."""
        posed = self.posed
        f = posed.formulation
        if verdict is None and diagnosed is None and polishable(posed, run):  # IPOPT's end onto its exact vertex
            ended, run = run, polished(posed, data, run)
            runs = [run if r is ended else r for r in runs]
        params, scale, f_scale = data.checked or data.params, data.scale, data.f_scale
        design, objective, checks = run["design"], run["value"], list(run["checks"])
        start_up = mesh = None
        collocated = {}
        unsimulated = verdict is None and diagnosed is None and run["ok"] and objective >= heavier
        if unsimulated:
            verdict = no_lighter(objective, heavier)
        if posed.start_up is not None and not unsimulated:  # re-checked by the independent simulator
            start_up, simulated, mesh, collocated = start_up_report(
                posed.start_up, *posed.start_up_seen(case, design), f, posed.seen_by(case, design),
                posed.mapped(posed.start_up_figures, 1)(run["x"], run["p"]),  # (on NumPy arrays: 15 us, not 90)
                posed.mesh_of(run["p"]))
            checks += simulated
        for check, lam in zip(checks, posed.named_multipliers(run["lam_g"])):
            check.multiplier = lam
            check.elasticity = limit_elasticity(check, lam, f_scale, objective)
        feasible = all(c.feasible for c in checks)
        diagnosis, diagnosis_s = None, 0.0
        if verdict is not None:
            status, diagnosis = verdict
        elif run["ok"] and feasible:
            status = "optimal"
        elif run["ok"]:
            status = "unverified"
            worst = min(checks, key=lambda c: c.margin if math.isfinite(c.margin) else -math.inf)
            check = "the simulated start-up" if worst in checks[posed.n_checked:] else "the float64 check"
            diagnosis = (f"{'IPOPT' if run['solver'] == 'ipopt' else 'SQP'} reported success but {check} finds "
                         f"{worst.name} violated by {-worst.margin:.3g} (relative)")
        else:
            diagnosed = diagnosed or diagnose(posed, run["p"], run["lbx"], run["ubx"], run["x"], scale)
            status, diagnosis, diagnosis_s = diagnosed.status, diagnosed.text, diagnosed.seconds
        info = spent_on(runs, run["solver"], run["status"], diagnosis_s)
        bounds = posed.named_bounds(data.lower, data.upper)
        elasticities = with_followers(sensitivities(posed, run, objective), case.follows) if status == "optimal" else {}
        return Solution(f.coupling, f.mode, posed.objective.name, posed.objective.unit, status, objective, design,
                        evaluate_outputs(f, design, params), checks, info, diagnosis, search, bounds,
                        elasticities, scale, (run["lam_x"], run["lam_g"]), {v.name: v.unit for v in f.variables},
                        start_up, run["x"][len(scale):] if posed.start_up is not None else None, mesh, diagnosed,
                        collocated=collocated)


def rescaled_seed(run: dict, before: ScaledData, after: ScaledData) -> dict:
    """``run``'s primal-dual point in the scaling of ``after`` (from ``before``'s): a scaled variable's bound
    multiplier goes with its scale's ratio, every multiplier with the objective scale's inverse ratio."""
    n, ratio = len(before.scale), before.f_scale / after.f_scale
    lam_x = run["lam_x"] * ratio
    lam_x[:n] *= after.scale / before.scale
    return {"x": after.x0, "lam_x": lam_x, "lam_g": run["lam_g"] * ratio}


def spent_on(runs: list[dict], name: str, status: str, seconds: float = 0.0) -> SolverInfo:
    """The solver calls of ``runs`` as one SolverInfo (``name``, ``status``), ``seconds`` more (a diagnosis's)."""
    return SolverInfo(name, status, sum(r["iterations"] for r in runs), sum((r["time"] for r in runs), 0.0) + seconds,
                      len(runs))


def verified_alone(given: Solution, alone: Solution, counted: bool = True) -> Solution:
    """A start-up solved from a start or a warm solution given that ended without a verified design (``given``:
    ``unverified``, ``not_found``), beside ``solve`` of the case alone (``alone``): ``alone``'s where it is ``optimal``
    or ``given`` has no design (its solver's name and status, its ``starts`` the start given, then those ``alone``
    names, else OWN), else ``given``'s, saying what ``solve`` alone ended with (``Solution.beside_alone``, once); the
    solver calls of both summed (``counted``; else ``given``'s alone: a caller that handed ``alone`` in counts it)."""
    infos = [given.solver, alone.solver] if counted else [given.solver]
    if alone.status == "optimal" or given.status not in DESIGN_STATUSES:
        return replace(alone, solver=alone.solver.summed(infos), starts=given_first(alone))
    return replace(given, solver=given.solver.summed(infos)).beside_alone(alone)


def given_first(alone: Solution) -> tuple[str, ...]:
    """The starts of ``solve``'s verdict alone kept for a solve from a start given: the start given, then those
    ``alone`` names (else OWN, its own)."""
    return (GIVEN,) + (alone.starts or (OWN,))


def no_lighter(objective: float, heavier: float) -> tuple[str, str]:
    """The verdict of a start-up solve whose design (``objective``, float64) is no lighter than the caller's
    ``heavier``: ``not_found``, its start not simulated (one simulation a modifier step that ends there:
    cable_motor_start's 7 cables, 20-30 ms of a 0.2-0.4 s solve)."""
    return "not_found", f"the design ({objective:.10g}) is no lighter than {heavier:.10g}: its start not simulated"


def uncorrected(solution: Solution, corrected: Solution) -> Solution:
    """A start-up solve's last design where its defect correction's solve (``corrected``) ends without one, kept with
    its status and said so in its diagnosis. ``unverified`` (its simulated start misses a limit): it stays what its
    simulated start makes it (the violation named, and that the correction found no design), not a verdict of the
    solve: cable_motor_start at 0.5 kg m^2 with 8 cables fixed (their simulated start 0.44 % over the allowed stress,
    where no 8-cable design of the quasi-static NLP is 4.4 % under it: docs/start_up.md, "The defect correction's
    fixed point"; modifier adaptation then goes on from that design and verifies them, 4.2568 kg: ``first_order``).
    Only an ``infeasible`` corrected solve says that no design of the NLP meets the moved limits; one
    that ended ``solver_failed`` or ``not_found`` found none from its start, which proves nothing. ``optimal`` (the
    correction only centred a binding limit the simulated start meets): verified, its status kept, but the objective
    may be off the simulator's optimum by more than the CENTRE of the tolerance the correction holds it to: a note."""
    moved = "the start-up limits moved by what the simulated start adds to its figures"
    ended = (f"no design of the NLP meets {moved}" if corrected.status == "infeasible"
             else f"the NLP at {moved} ended without a design")
    if solution.status == "unverified":
        solution.diagnosis = f"{solution.diagnosis}; {ended} ({corrected.status})"
    elif solution.status == "optimal":
        note = (f"verified by its simulated start, but not centred on the start-up limits it binds: {ended} "
                f"({corrected.status}), so the objective may be off the simulator's optimum by more than "
                f"{CENTRE:g} of the tolerance")
        solution.diagnosis = f"{solution.diagnosis}; {note}" if solution.diagnosis else note
    return solution


def doubling_pays(error: float, coarser: float, intervals: int, tolerance: float) -> bool:
    """Whether doubling the intervals may bring the collocation's error within ``tolerance`` by MAX_INTERVALS: at
    the rate the last doubling cut it (from ``coarser``; none yet: it may). A start whose load jumps in time
    converges at first order (half the error a doubling), far too slowly to try every doubling."""
    doublings = int(math.log2(MAX_INTERVALS // intervals))
    if doublings < 1:
        return False
    rate = error / coarser  # 0 before the first doubling (coarser is infinite)
    return rate < 1.0 and error * rate ** doublings <= tolerance


def unsettled(solution: Solution, error: float) -> bool:
    """Whether a start-up solve's integer choice was made on a mesh too coarse to make it: another choice its search
    found feasible came within ``error`` (its collocation error, relative) of the kept objective, so the next mesh
    may well reverse the order, or find the kept choice infeasible (its start-up limits bind). The next solve then
    decides the integers again from its relaxation (``Problem._solve``, ``redecide``) instead of trying the kept
    ones first. ball_motor_start's first mesh (error 1.1e-2): 24 rows kept, 25 worse by 7.6e-4; on the adapted
    mesh 24 rows are infeasible, which IPOPT took 55 iterations to find from their first-mesh optimum, 32 from the
    optimum of 25 rows the relaxation rounds to (its downhill neighbour); the design is the same to the last bit.
    So does a choice its search left unsolved, the mesh too coarse to rank it (an UNRANKED entry,
    :meth:`Problem._unranked`)."""
    kept = solution.objective
    others = [e["objective"] for e in solution.integer_search if e["feasible"] and math.isfinite(e["objective"])]
    return any(0 < (other - kept) / abs(kept) < error for other in others) or any(
        e.get("status", "").startswith(UNRANKED) for e in solution.integer_search)


SHAPING_MARGIN = 10.0  # times the collocation's largest error: a start-up limit this far off cannot become active


def shapes_nothing(solution: Solution, first: int, tolerance: float, static: set[str]) -> bool:
    """Whether no start-up limit shapes the design, so that no mesh changes it: each start-up check (from index
    ``first`` on) met by the simulated start with a margin over SHAPING_MARGIN times the collocation's largest error
    (start time, friction work, lock-up speed against the simulated ones), and the NLP's multiplier of each one
    negligible (elasticity of the objective within ``tolerance``): only the static constraints bind, the start-up
    states follow the design. (ball_motor_start at 0.6-0.9 times its driven inertia: the sizing's 950.755 kg starts
    in time whatever the mesh; the accuracy loop solved it 4 more times, every design the same to 1e-12.) And the
    objective elastic within ``tolerance`` to every quantity not in ``static`` (the coupling's own quantities and
    design variables, one a case fixes having a sensitivity of its name: so the drive, the load and the start-up's
    limits): where it is not, a row of the collocation binds, not a named check, and
    the design is the mesh's (ball_motor_start in paper mode at a width ratio of 1.36: only the width ratio bound
    of the named constraints, elasticity 0.16 to the driven inertia, error 2.3e-4: 765.47 kg, where the start-time
    bound optimum is 728.24 kg; tests/test_hostile_agree.py)."""
    errors = [abs(e) for e in solution.start_up["discretisation_error"].values()]
    checks = solution.constraints[first:]
    if not checks or not all(math.isfinite(e) for e in errors):
        return False
    return all(math.isfinite(c.margin) and c.margin > SHAPING_MARGIN * max(errors) for c in checks) \
        and no_multiplier(checks, tolerance) and not drive_elastic(solution, tolerance, static)


def no_multiplier(checks: list, tolerance: float) -> bool:
    """Whether the NLP's multiplier of each of the start-up ``checks`` is negligible (the objective's elasticity to
    its limit within ``tolerance``)."""
    return all(abs(c.elasticity or 0.0) <= tolerance for c in checks)


def drive_elastic(solution: Solution, tolerance: float, static: set[str]) -> bool:
    """Whether the objective is elastic beyond ``tolerance`` to a quantity not in ``static`` (the coupling's own
    quantities and design variables): to the drive, the load or a start-up limit."""
    return any(abs(e) > tolerance for name, e in solution.sensitivities.items() if name not in static)


def _recorded(kept: Solution, names: list[str], combo: tuple, own: Solution, how: str = OWN_LOOP) -> Solution:
    """``own`` (integer choice ``combo`` solved through its own loop, ``how``) recorded in ``kept``'s integer search:
    ``own`` where it ends optimal and lighter than ``kept`` (or ``kept`` has none verified), carrying that search and
    ``kept``'s bounds; else ``kept``."""
    kept.integer_search = kept.integer_search + [own_entry(names, combo, own, how)]
    if own.status == "optimal" and (kept.status != "optimal" or own.objective < kept.objective):
        own.integer_search, own.bounds = kept.integer_search, kept.bounds
        return own
    return kept


def held_note(solution: Solution) -> Solution:
    """A design a row of the collocation holds (:func:`held_by_the_mesh`), kept: said so in its diagnosis."""
    note = ("a row of the collocation holds this design, not a limit (no start-up limit's multiplier, the objective "
            "elastic to the drive): it is the mesh's, and may be heavier than the optimum")
    solution.diagnosis = f"{solution.diagnosis}; {note}" if solution.diagnosis else note
    return solution


def held_by_the_mesh(solution: Solution, first: int, tolerance: float, static: set[str]) -> bool:
    """Whether a row of the collocation holds an ``optimal`` start-up design, not a limit: no start-up check (from
    index ``first`` on) has a multiplier (each elasticity within ``tolerance``), yet the objective is elastic to the
    drive (:func:`drive_elastic`). Only the equalities of the collocation can carry that elasticity: their
    multipliers lam solve J_z^T lam = 0 in the states z (the objective is the design's), so J_z is singular, a fold
    of the discretised start where the design's lighter neighbours have no collocated start on this mesh, though
    their simulated starts are sound. ball_motor_start (paper) at a start-time limit of 24 s: the motor's knee
    (57 to 102 rad/s in 0.9 s) inside the graded part's two longest intervals; each mesh of the loop folds at another
    design (487.5 to 512.9 kg, elastic 0.58 to the breakdown torque), the sizing's 475.95 kg starts in 7.43 s."""
    checks = solution.constraints[first:]
    return (solution.status == "optimal" and bool(checks) and solution.sensitivities
            and no_multiplier(checks, tolerance) and drive_elastic(solution, tolerance, static))


_CACHE: dict[tuple, Problem] = {}


def problem_for(formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions(),
                start_up: Structure | None = None) -> Problem:
    """Build a problem once per (formulation, objective, options, start-up structure) in this process and reuse it."""
    key = (formulation.coupling, formulation.mode, formulation.variant, objective, options, start_up)
    if key not in _CACHE:
        _CACHE[key] = Problem(formulation, objective, options, start_up)
    return _CACHE[key]


def start_up_key(key: tuple) -> bool:
    """Whether a key of :func:`problem_for`'s is a start-up problem's (its structure, the last entry, given)."""
    return key[-1] is not None


@contextmanager
def problems_set_aside(chosen: Callable[[tuple], bool] = lambda key: True):
    """The problems :func:`problem_for` built in this process whose keys ``chosen`` picks (default: all) set aside, so
    that what runs inside builds its own as a new process does, and yields the list of those built inside (filled on
    exit); on exit those dropped and the ones set aside given back (a benchmark's first solves and start-up sweeps)."""
    saved = {key: _CACHE.pop(key) for key in [key for key in _CACHE if chosen(key)]}
    built: list[Problem] = []
    try:
        yield built
    finally:
        for key in [key for key in _CACHE if chosen(key)]:
            built.append(_CACHE.pop(key))
        _CACHE.update(saved)


def case_formulation(case: Case, mode: str | None = None) -> Formulation:
    """The formulation a case is solved with, as shown: the coupling's in ``mode`` (default: the case's option,
    then the coupling's), with the start-up's quantities and spring preload if the case has a [start_up] section."""
    from clutchopt.formulations import get_coupling

    formulation = get_coupling(case.coupling).formulation(case.mode_of(mode))
    return with_start_up(formulation) if case.start_up is not None else formulation


def case_problem(case: Case, mode: str | None = None, objective: str | None = None,
                 options: SolverOptions = SolverOptions()) -> Problem:
    """The built problem that solves ``case`` in ``mode`` (default: the case's option, then the coupling's)."""
    from clutchopt.formulations import get_coupling

    formulation = get_coupling(case.coupling).formulation(case.mode_of(mode))
    structure = Structure.of(case) if case.start_up is not None else None
    return problem_for(formulation, case.objective_of(objective), options, structure)


def solve_case(case: Case, mode: str | None = None, objective: str | None = None,
               options: SolverOptions = SolverOptions()) -> Solution:
    """Solve a case in a mode (default: the case's option, then the coupling's default), checked across its fields
    first as a case file and a sweep's point are."""  # (review 27: a case moved by with_values above its motor's
    # synchronous speed had solved optimal, a cable without any hub stiffness had raised ZeroDivisionError)
    if not isinstance(options, SolverOptions):
        raise InputError("options", f"must be SolverOptions, got {shown_value(options)}")
    check_across(case)
    return case_problem(case, mode, objective, options).solve(case)

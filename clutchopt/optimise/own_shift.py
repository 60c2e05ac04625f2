"""Integer choices a start-up's accuracy loop found infeasible only at limits moved for another choice.

The defect correction (:func:`~clutchopt.optimise.start_up_check.corrected_case`) moves a start-up limit by what the
simulated start of the kept design adds to the NLP's figure. An elastic link's loop then decides its integers again
at the moved limit, but what the simulation adds is the kept choice's: the cable's dynamic stress over its
quasi-static one differs from one cable count to the next. cable_motor_start at 0.3 kg m^2: the first solve keeps
7 cables, whose simulated stress moves the stress limit in to 0.905 of the case's; at that limit 8 cables are
infeasible and 9 are kept (4.418 kg), where 8 cables fixed solve to 3.953 kg, their own simulated start meeting the
case's limit. :class:`ForeignShifts` records the choices found infeasible at limits another choice's start moved
(or a sweep's point before carried), and ``Problem._refined`` solves those lighter than the kept design through
their own accuracy loop (integers fixed, from the case's limits) before it keeps the heavier one (docs/start_up.md,
"Integer attempts").
"""

from __future__ import annotations

import math

from clutchopt.optimise.integers import EXCLUDED, SOLVED
from clutchopt.records import DESIGN_STATUSES

CARRIED = None  # the "choice" that measured a shift carried from elsewhere, where it is not known
OWN_LOOP = "own accuracy loop"  # how an integer search's entry of a choice solved through its own loop begins


def carried_by(warm) -> frozenset:
    """The choices that measured the limits a loop starts moved (a sweep's: the point before's ``limit_shift``,
    with its solution ``warm``): those its loop recorded, and always :data:`CARRIED`, for they measured it at another
    point: no choice's verdict at a carried limit is its own. cable_motor_start (paper) swept over its motor inertia
    0.0695, 0.0779, 0.0820 kg m^2: at 0.0779 8 cables' start carries 0.029 % more than the stress allowed and moves
    the limit; the third point starts there, 8 cables infeasible, and with 8 taken as having measured that shift
    itself no own loop ran: the sweep kept 9 cables (4.418 kg) where 8's own start at 0.0820 meets the case's limit
    (3.953 kg, solve's). (The sweep at 0.25 kg m^2 from 0.2, 7 cables' limit, now solves 7 through its own loop
    once: infeasible there as at 0.25 alone.)"""
    return frozenset(getattr(warm, "shift_measured_by", None) or ()) | {CARRIED}


class ForeignShifts:
    """The integer choices (tuples of the integer variables ``names``, in order) an elastic link's accuracy loop
    found infeasible at limits moved by other choices' simulated starts, with the objective at each run's end."""

    def __init__(self, names: list[str], carried: frozenset | tuple = ()):
        self.names = names
        self.measured: set = set(carried)  # the choices whose simulated starts moved the limits (``carried``: those
        # that moved the limits the loop starts with, a sweep's point before's)
        self.found: dict[tuple, float] = {}  # choice -> least objective at the end of its infeasible runs (-inf:
        # excluded without a run)
        self.own: set[tuple] = set()  # choices found infeasible at the case's limits or at their own shift
        self.looped: set[tuple] = set()  # the choices solved through their own loop (``Problem._own_loop``)
        self.unverified: dict[tuple, object] = {}  # choice -> the loop's lightest design of it whose simulated
        # start missed a limit (:meth:`unverified_below`)
        self.first: dict[tuple, object] = {}  # choice -> its own loop's first solve, made before the loop
        # (``Problem._one_up_first``; its solver calls counted by the caller)
        self.unverified_at_the_case: dict[tuple, object] = {}  # choices whose design of the NLP at the case's own
        # limits (no limit moved yet) the loop simulated, its start missing a limit: that solution (the first)

    def choice(self, design: dict[str, float]) -> tuple:
        return tuple(float(design[name]) for name in self.names)

    def corrected(self, solution) -> None:
        """The limits are moved by ``solution``'s simulated start (its choice measured the shift)."""
        self.measured.add(self.choice(solution.design))

    def seen(self, solution) -> None:
        """A solve of the loop (at the limits moved so far): its infeasible choices, recorded as found at another
        choice's shift or at their own (none moved, or moved by their own start alone); its design, where its
        simulated start misses a limit (at the case's own limits, where no choice has moved them yet:
        :attr:`unverified_at_the_case`)."""
        if not self.measured:
            self.simulated_at_the_case(solution)
        if getattr(solution, "status", None) == "unverified":
            combo = self.choice(solution.design)
            if combo not in self.unverified or solution.objective < self.unverified[combo].objective:
                self.unverified[combo] = solution
        for entry in solution.integer_search:
            if not all(name in entry for name in self.names):
                continue
            combo = tuple(float(entry[name]) for name in self.names)
            if entry["status"] == SOLVED:
                continue
            if self.measured <= {combo}:  # (excluded without a solve, too: a verdict at these limits)
                self.own.add(combo)
            elif math.isfinite(entry["objective"]):
                self.found[combo] = min(self.found.get(combo, math.inf), entry["objective"])
            elif entry["status"].startswith(EXCLUDED):  # excluded without a solve at another's shift: no run's
                self.found[combo] = -math.inf  # end bounds its objective (the link bound at 7 cables' moved limit)

    def simulated_at_the_case(self, solution) -> None:
        """``solution``: a design of the NLP at the case's own limits, its start simulated; recorded in
        :attr:`unverified_at_the_case` where the start misses a limit."""
        if getattr(solution, "status", None) == "unverified":
            self.unverified_at_the_case.setdefault(self.choice(solution.design), solution)

    def own_loop(self, combo: tuple) -> None:
        """``combo`` solved through its own accuracy loop (``Problem._own_loop``)."""
        self.looped.add(combo)

    def lighter(self, kept) -> list[tuple]:
        """The choices to solve through their own loop before ``kept`` (the loop's solution) is kept: found
        infeasible only at another choice's shift, their runs ending below the kept objective (any, where the loop
        kept no design), lightest first."""
        has_design = kept.status in DESIGN_STATUSES
        bound = kept.objective if has_design else math.inf
        own = self.choice(kept.design) if has_design else None
        return sorted((combo for combo, value in self.found.items()
                       if value < bound and combo not in self.own and combo != own), key=self.found.get)

    def unverified_below(self, kept) -> list:
        """The designs of other choices the loop kept ``unverified`` at some step (the lightest of each), lighter
        than ``kept`` (optimal), their choices not solved through their own loop, lightest first: a choice the defect
        correction then found infeasible at its own shift has no verdict, for a moved limit cannot reach every
        verified design of it; modifier adaptation goes on from that design
        (:func:`~clutchopt.optimise.modifier.first_order`). cable_motor_start at 0.5 kg m^2: 8 cables' start carries
        0.44 % over the allowed stress, their correction has no design and 9 cables are kept (4.418 kg); from 8
        cables' design the modifier verifies them with a heavier weight, 4.257 kg."""
        if kept.status != "optimal":
            return []
        own = self.choice(kept.design)
        return sorted((solution for combo, solution in self.unverified.items()
                       if solution.objective < kept.objective and combo != own and combo not in self.looped),
                      key=lambda solution: solution.objective)

    def above_unverified(self, kept, upper: dict[str, float]) -> list[tuple]:
        """The choices one count above ``kept``'s in one integer (within its ``upper`` bound) where the loop kept an
        ``unverified`` design (its corrections did not bring its simulated start within the limits, or the NLP had
        no design at the moved limits: ``Problem._refined``'s ``uncorrected``). Written for the cable at 0.5 kg m^2,
        whose 8 cables' start carries 0.44 % more than the stress allowed; since the correction moves the NLP's
        limit from its own figure (docs/start_up.md, "The defect correction's fixed point") that loop finds 8
        cables infeasible at the moved limit and keeps 9 itself (4.418 kg)."""
        if kept.status != "unverified":
            return []
        return self.one_off(kept, +1.0, lambda name, value: value <= upper[name])

    def untried_below(self, kept, lower: dict[str, float]) -> list[tuple]:
        """The choices one count below ``kept``'s in one integer (within its ``lower`` bound) that no search of the
        loop settled: a loop started at limits moved for another choice (a sweep's point before's) may round past
        them. allowable_cable_stress 350, 300, 250 MPa swept: at 250 MPa from 300's limit, moved by 10 cables'
        start, the search went 10 -> 13 -> 14 and 13's own loop ended optimal (6.277 kg); 12 cables, never tried,
        are `solve`'s of 250 MPa alone (5.813 kg). So is one the searches found infeasible only at limits another
        choice's start moved, whatever the objective its runs ended at (:attr:`found`; :meth:`lighter` takes those
        below the kept objective only, but an infeasible run's end bounds nothing): cable_motor_start (threads) at
        344.09 MPa: 7 cables' start moves the limit to 0.896 of the case's, where 8 cables' run ends infeasible at
        5.598 kg and 9 are kept (4.083 kg); 8 cables' own loop: 3.655 kg, verified. And so is one a search solved
        (a design of the NLP) but did not keep: its start was never simulated, so nothing but its own loop is its
        verdict. cable_motor_start at a breakdown torque of 466.69 N m swept over torque 133.58 then 110.72 N m: the
        second point's first search solves 16 down to 12 cables and keeps 12, whose start moves the limit; 19 are
        kept there, 18's and 17's own loops end lighter, and 16 (solved, not kept) was skipped: the sweep kept 17
        cables (8.141 kg) where 16's own loop gives solve's 7.677 kg. Only a choice found infeasible at the case's
        limits or its own shift (:attr:`own`) or already looped is not solved again."""
        if kept.status != "optimal":
            return []
        below = self.one_off(kept, -1.0, lambda name, value: value >= lower[name])
        return [combo for combo in below if combo not in self.own and combo not in self.looped]

    def one_off(self, kept, step: float, within) -> list[tuple]:
        """The choices ``step`` counts off ``kept``'s in one integer, where ``within(name, value)``."""
        own = self.choice(kept.design)
        return [own[:i] + (value + step,) + own[i + 1:] for i, (name, value) in enumerate(zip(self.names, own))
                if within(name, value + step)]


def worst_margin(solution) -> float:
    """The least margin (relative) of ``solution``'s checks, its simulated start's among them (-inf: none)."""
    return min((c.margin for c in solution.constraints if math.isfinite(c.margin)), default=-math.inf)


def stepped(names: list[str], design: dict[str, float], combo: tuple) -> int:
    """The index of the integer in which ``combo`` differs from ``design``'s choice (one count off it)."""
    return next(k for k, (name, value) in enumerate(zip(names, combo)) if float(design[name]) != value)


def climbing(names: list[str], i: int, last, own, combo: tuple, upper: dict[str, float]) -> tuple[tuple | None, str]:
    """The next choice up from ``combo`` (``own``'s: one count above ``last``'s in the integer ``names[i]``, within
    its ``upper`` bound) where ``own``'s loop ended ``unverified`` nearer to meeting its limits than ``last``'s (its
    worst margin, :func:`worst_margin`, larger) and, at the rate the margin grew, a count within the bound meets
    them; else None, and why no count further up is tried (in words). Adding a cable lowers each cable's stress, so
    the margin of an unverified count grows count by count; where it does not, no count above is nearer
    (``Problem._climbed``)."""
    name, count = names[i], combo[i]
    before, now = worst_margin(last), worst_margin(own)
    if own.status != "unverified":
        return None, f"no count of {name} above {count:g} tried: its own accuracy loop ended {own.status}"
    if not now > before:
        return None, (f"no count of {name} above {count:g} tried: its simulated start misses its limits by "
                      f"{-now:.3g} (relative), no nearer than {count - 1:g}'s {-before:.3g}")
    needed = math.ceil(-now / (now - before))
    if count + needed > upper[name]:
        return None, (f"no count of {name} above {count:g} tried: at the rate its simulated start came nearer to its "
                      f"limits ({now - before:.3g} a count) {count + needed:g} would be needed, above the bound "
                      f"{upper[name]:g}")
    return combo[:i] + (count + 1.0,) + combo[i + 1:], ""


def lighter_above(names: list[str], i: int, own, kept, combo: tuple, upper: dict[str, float]) -> tuple | None:
    """Once a count of the climb is verified (``kept``, optimal): the next choice up from ``combo`` in ``names[i]``
    (within ``upper``) where ``combo``'s own loop (``own``) came out lighter than every verified count so far: kept
    (``own is kept``), or ``unverified`` below ``kept``'s objective (its NLP's design, which the simulated start only
    moves up); None where it did not, for a count heavier at the limits it meets has a heavier one above. The first
    verified count need not be the lightest: cable_motor_start at 0.027 kg m^2 (modifier adaptation in the own loops)
    verifies 10 cables at 7.307 kg with heavy weights, then 11 at 6.276 kg, 12 at 5.813 kg and 13 at 6.277 kg: 12
    kept."""
    if not (own is kept or own.status == "unverified" and own.objective < kept.objective):
        return None
    if combo[i] + 1.0 > upper[names[i]]:
        return None
    return combo[:i] + (combo[i] + 1.0,) + combo[i + 1:]


def own_entry(names: list[str], combo: tuple, own, how: str = OWN_LOOP) -> dict:
    """The integer search's record of ``combo`` solved through its own accuracy loop (``own``, its solution; ``how``:
    or modifier adaptation)."""
    return {**{n: int(v) for n, v in zip(names, combo)}, "status": f"{how}: {own.status}",
            "feasible": own.status == "optimal", "objective": own.objective}


def unverified_here(names: list[str], solution, combo: tuple) -> bool:
    """Whether ``solution``'s solve (an elastic link's start-up at its point) had ``combo``'s design of the NLP at the
    case's own limits simulated, its start missing a limit, or solved ``combo`` through its own accuracy loop (its
    first solve at the case's limits: :func:`own_entry`, OWN_LOOP)."""
    return combo in solution.unverified_at_the_case or any(
        entry["status"].startswith(f"{OWN_LOOP}:") and tuple(float(entry.get(n, math.nan)) for n in names) == combo
        for entry in solution.integer_search)


def excluded_own_entry(names: list[str], combo: tuple, how: str, rows: list[str]) -> dict:
    """The integer search's record of ``combo``'s own loop (``how``) refuted without a solve by ``rows``."""
    return {**{n: int(v) for n, v in zip(names, combo)}, "status": f"{how}: {EXCLUDED}{', '.join(rows)}",
            "feasible": False, "objective": math.nan}

"""A design space shown empty by interval branch and bound: no design within the bounds meets the constraints.

The posed problem's own constraint rows (``g <= 0``, normalised) are bounded over boxes of the design variables by
interval evaluation (:mod:`clutchopt.optimise.interval`). A box is empty of feasible designs when one row's lower
bound exceeds the tolerance over all of it. A box whose uncertain rows (those not met throughout it) all fall, or all
rise, with one variable holds a feasible design only if its face at that variable's upper (lower) bound does: the
box shrinks to the face (the monotonicity test of interval global optimisation). Every box is first contracted to
the part where each row's mean-value form allows it to be met (:mod:`clutchopt.optimise.interval_contract`; a box
contracted to nothing is empty). Other boxes are bisected across their widest variable, relative to the design box.
From a search's second evaluation on, where the rows hold no declared monotone nodes, each row's limit is also
carried back through its expressions to the variables (:mod:`clutchopt.optimise.interval_backward`: the lever in
design mode, whose torque is a product of variables over ranges of orders of magnitude, was proven at none of its 47
points without a design over 1x-10x its inertia, at 37 now), and the boxes are bisected by their relative widths
instead (:func:`_bisected`). Each box's integer variables are rounded inwards to whole numbers, and a box without one
is dropped. When no box is left the design space is empty: a proof, for the integers
(ball_motor_start at 565 kW: its continuous relaxation has designs, no whole number of ball rows does). A box whose
centre meets every row is a feasible design (of the relaxation), and the search stops there: the case is not
infeasible.

Work is bounded: at most ``MAX_BOXES`` boxes are evaluated, after which the search gives up without a verdict; beyond
the first ``SURE_BOXES`` it also gives up as soon as the boxes left grow by more than ``GROWTH`` in an iteration. A
search that will prove closes in: the boxes left grow by at most 1.25 an iteration and then fall (ball_motor_start
at 580-800 kW: 300 to 1,200 boxes left at each of about 30 iterations, 15,000-34,000 boxes in all), while one whose
bounds are too loose to prove doubles them every iteration (wedge_motor_start in geometry mode in a 100 mm
housing: 32, 110, 204, 392, 752, ...) and stops where it did with a budget of 2,500 boxes.

Declared monotone nodes (Hertz's n_a, n_b of the ball's contact, :mod:`clutchopt.monotone`) are bounded at their
argument's ends (:mod:`clutchopt.optimise.interval_nodes`): replayed through their Newton step on the elliptic
integrals, their bounds are unbounded on boxes 1 % wide, and no conflict through the contact stress was provable.
"""

from __future__ import annotations

import time
from typing import Callable, NamedTuple

import numpy as np

from clutchopt.optimise.interval_backward import Tape
from clutchopt.optimise.interval_backward import contracted as backward_contracted
from clutchopt.optimise.interval_contract import contracted
from clutchopt.optimise.interval_nodes import enclosed_rows, split_bounds
from clutchopt.start_up.drive import graded_part

MAX_BOXES = 40_000  # about 1.5 s of CPU; ball_motor_start's static conflict at 580-800 kW takes 15,000-34,000
SURE_BOXES = 2_500  # evaluated in any case; beyond, only while the search closes in (GROWTH)
FEW_BOXES = 64  # about what one search costs whatever its boxes: a search tried before a solve or a region's search
# may take this many (optimise/verdict.py, optimise/region_proof.py)
GROWTH = 1.5  # the most the boxes left may grow from one iteration to the next beyond SURE_BOXES
BATCH = 128  # boxes an iteration evaluates at least (bisecting as often as it takes)
INTEGER_BATCH = 32  # the same where the design has integer variables (the ball's: see _batch)
TOLERANCE = 1e-6  # a row must be broken by more than this (relative) over a whole box for the box to be empty


class Emptiness(NamedTuple):
    """The outcome of a search: ``proven`` empty, or a ``feasible`` design of the relaxation found, or neither."""

    proven: bool
    boxes: int  # evaluated
    decisive: dict[str, int]  # constraint name -> boxes it emptied
    feasible: np.ndarray | None = None  # a design meeting every row (SI), if one was met
    reached: bool = False  # a design met at one end of a parameter interval (no proof for the interval can exist)
    witness: np.ndarray | None = None  # where reached: that design (SI; a box centre, its integers whole unless met
    # over a part of the interval)
    paused: "Paused | None" = None  # where its budget ended it (a search asked to pause): where it stood


class Paused(NamedTuple):
    """Where a budget ended a search, at the start of the iteration that would have passed it: its boxes (design and
    parameter bounds, in its order), the boxes it had evaluated, the boxes left after its last iteration (the growth
    rule's), the iterations begun and the boxes each row emptied or cut. A search resumed from it
    (:func:`empty_design_space`'s ``resume``) makes the steps the search without that budget makes from there: the
    same outcome, its boxes evaluated once."""

    lo: np.ndarray
    hi: np.ndarray
    plo: np.ndarray
    phi: np.ndarray
    evaluated: int
    left: float
    rounds_begun: int
    decisive: dict[str, int]
    budget: int  # (the budget that ended it: its outcome is that of a search within it)


def interval_functions(posed):
    """The formulation's own constraint rows (a start-up's left out: its states are not searched) and their
    Jacobian in the design variables, as interval functions of (design, p) with the declared monotone nodes
    enclosed at their arguments' ends (:mod:`clutchopt.optimise.interval_nodes`), built once per problem."""
    return posed.built("interval", True, lambda _: enclosed_rows(posed))


def row_tape(posed, functions=None) -> Tape | None:
    """The rows of ``functions`` (default :func:`interval_functions`; the nodes replayed, where those disagree) as a
    :class:`Tape` to carry their limits back, built once per problem and variant; None where they hold declared
    monotone nodes (their values enter as further inputs, whose enclosures carry nothing back)."""
    rows = (functions or interval_functions(posed))[0]
    return None if rows.nodes.nodes else posed.built("interval_tape", id(rows), lambda _: Tape(rows.interval.function,
                                                                                              rows.interval.program))


def search(posed, p: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Emptiness | None:
    """Interval branch and bound over the box [lower, upper] of a posed problem's design whose variable scales in
    ``p`` are 1 (x in SI); None where it cannot start (an unbounded variable)."""
    return searches(posed, [(p, lower, upper)])[0]


def searches(posed, problems: list[tuple[np.ndarray, ...]], budgets: list[int] | None = None,
             lead: bool = False, pause: bool = False, resumed: Paused | None = None) -> list[Emptiness | None]:
    """:func:`search` of each ``(p, lower, upper)`` (the points of a sweep), all at once: the boxes of every search
    in one array (a box's bounds are its own: the interval rules work box by box), each with its own parameters and
    its own tally, so each search's outcome, box count and decisive constraints are what it alone would give; an
    evaluation and an iteration's bookkeeping cost per call as much as per box, so searches together cost less than
    one by one.

    A problem ``(p, lower, upper, p_upper)`` searches the parameters over the interval [p, p_upper] (a run of a
    sweep's points: :mod:`clutchopt.optimise.region_proof`): every bound holds for every parameter vector in it, so
    an empty design space is empty for each of them. A box's parameter interval is split like a design variable
    where it spreads the box's uncertain rows more than any design variable does (the rows' bounds at the box's
    centre: their width comes from the parameters alone), so a run is proven where the rows' bounds over its whole
    interval are too loose (the lever over 2131-2351 rpm, whose torque takes the speed squared: at one design its
    torque row bounded by [-0.005, 0.258], its values 0.073 to 0.174) or different rows break at different
    parameters; the halves cover the interval, so the proof is still one for every point. A box whose centre meets
    every row for all of the search's parameters is a design of every such point (the search stops there); for the
    parameters of a part of the interval, a design of some of its points: the search stops as ``reached`` (no
    proof for the interval exists). ``budgets``: each search's most boxes (default MAX_BOXES). ``lead``: the first
    search leads; where it ends at its first evaluation, the others still searching (with the same interval
    functions) end there, given up (:func:`searched_along`). ``pause``: where its budget ends the first search, its
    outcome says where it stood (``Emptiness.paused``); ``resumed``: the one search goes on from there."""
    outcomes: list[Emptiness | None] = [None] * len(problems)
    assert resumed is None or len(problems) == 1, "a search resumed alone"
    started = [i for i, (_, lower, upper, *_) in enumerate(problems)
               if np.all(np.isfinite(lower)) and np.all(np.isfinite(upper))]
    if not started:
        return outcomes
    budgets = budgets or [MAX_BOXES] * len(problems)
    declared = interval_functions(posed)
    agree = declared[0].nodes.agree_all([problems[i] for i in started])
    for functions, group in ((declared, [i for i, a in zip(started, agree) if a]),
                             (None, [i for i, a in zip(started, agree) if not a])):
        if group:  # where the declared nodes do not stand for the NLP's rows, the rows replayed
            functions = functions or posed.built("interval", False, lambda _: enclosed_rows(posed, declared=False))
            first = group.index(0) if 0 in group else None
            for i, outcome in zip(group, _searched(posed, functions, [problems[i] for i in group],
                                                   np.array([budgets[i] for i in group]), first if lead else None,
                                                   first if pause else None, resumed)):
                outcomes[i] = outcome
    _proofs(posed)["evaluated"] += sum(outcome.boxes for outcome in outcomes if outcome is not None) - (
        resumed.evaluated if resumed is not None and outcomes[0] is not None else 0)  # (a resumed search's boxes
    # before its pause counted where they were evaluated)
    return outcomes


def _searched(posed, functions, problems: list, budgets: np.ndarray, lead: int | None = None,
              pause: int | None = None, resumed: Paused | None = None) -> list[Emptiness]:
    """The searches of :func:`searches` with the same interval functions, every box a column with its search's
    (``lead``: the leading search's number; ``pause``: the number of the search whose budget pauses it; ``resumed``:
    the one search's state, see :func:`searches`)."""
    names, count = posed.row_names, len(problems)
    p_lo = np.stack([problem[0] for problem in problems], axis=1)
    p_hi = np.stack([problem[3] if len(problem) > 3 else problem[0] for problem in problems], axis=1)
    lo = np.stack([problem[1] for problem in problems], axis=1)
    hi = np.stack([problem[2] for problem in problems], axis=1)
    ranged = ~np.all(_same(p_lo, p_hi), axis=0)  # a parameter interval (a quantity
    # the case leaves out reads NaN at both ends): its ends are tried too (_reached)
    intervals = bool(ranged.any())  # (none: no parameter is split, no end tried)
    width0 = np.where(hi > lo, hi - lo, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):  # (a variable not positive throughout: NaN, by difference)
        ratio0 = np.where((lo > 0) & (hi > lo), np.log(hi / lo), np.nan)
    spans0 = (width0, ratio0)
    p_width0 = np.where(p_hi > p_lo, p_hi - p_lo, 0.0)  # (a NaN: 0, never split)
    owner = np.arange(count)  # each box's search (a column of params), the boxes of one search together
    plo, phi = p_lo.copy(), p_hi.copy()  # each box's parameters (a search's interval, split where it spreads the rows)
    n = lo.shape[0]
    decisive: list[dict[str, int]] = [{} for _ in problems]
    whole_names = [f"a whole {posed.names[i]}" for i in posed.integer]
    evaluated, left = np.zeros(count, dtype=int), np.full(count, np.inf)
    outcomes: list[Emptiness | None] = [None] * count

    def end(searches_ended, outcome) -> None:
        for j in np.asarray(searches_ended, dtype=int).tolist():
            outcomes[j] = outcome(j)

    def tally(keys: list[str], boxes: np.ndarray, owner: np.ndarray) -> None:
        """The boxes each key (of a row of ``boxes``: which boxes it emptied or cut; the rows the first keys') counts,
        by search (a start-up's names: its formulation's rows, then the start-up's, which are not searched); one
        count over (key, search) pairs, not one a key (a tally had cost a tenth of an iteration's fixed cost)."""
        rows, columns = np.nonzero(boxes)
        per_search = np.bincount(rows * count + owner[columns], minlength=boxes.shape[0] * count).reshape(-1, count)
        for k, j in zip(*np.nonzero(per_search)):  # (a search's keys in the order of the rows)
            decisive[j][keys[k]] = decisive[j].get(keys[k], 0) + int(per_search[k, j])

    def searching(owner: np.ndarray) -> np.ndarray:
        """Which searches have a box among ``owner`` (one flag a search)."""
        return np.bincount(owner, minlength=count) > 0

    def flagged(searches_flagged) -> np.ndarray:
        mask = np.zeros(count, dtype=bool)
        mask[list(searches_flagged)] = True
        return mask

    def within_budgets(owner: np.ndarray, grown: np.ndarray | None = None) -> np.ndarray:
        """Which boxes belong to searches their evaluation keeps within budget (of ``grown`` boxes each, if given:
        after their splits); the others' searches end there, not proven."""
        counts = np.bincount(owner, minlength=count) if grown is None else grown
        over = (counts > 0) & (evaluated + counts > budgets)
        end(np.flatnonzero(over), lambda j: Emptiness(False, int(evaluated[j]), decisive[j]))
        return ~over[owner]

    carries = not functions[0].nodes.nodes  # (rows without declared nodes: carried back, row_tape, built at first use)
    rounds_begun = 0  # (the leader's first box evaluated in the first)
    if resumed is not None:  # (one search)
        lo, hi, plo, phi = resumed.lo, resumed.hi, resumed.plo, resumed.phi
        owner, evaluated[0], left[0], rounds_begun = np.zeros(lo.shape[1], dtype=int), *resumed[4:7]
        decisive[0] = dict(resumed.decisive)
    while lo.shape[1]:
        paused, mine = None, None if pause is None or outcomes[pause] is not None else owner == pause
        if mine is not None and evaluated[pause] + np.count_nonzero(mine) > budgets[pause]:  # (its budget may end it
            # in this iteration: where it stands kept)
            paused = _state(mine, lo, hi, plo, phi, evaluated[pause], left[pause], rounds_begun, decisive[pause],
                            budgets[pause])
        rounds_begun += 1
        before = searching(owner)
        lo, hi, none = _rounded(lo, hi, posed.integer)
        tally(whole_names, none, owner)
        kept = ~none.any(axis=0)
        if not kept.all():
            lo, hi, owner, plo, phi = _taken(kept, lo, hi, owner, plo, phi)
            end(np.flatnonzero(before & ~searching(owner)),
                lambda j: Emptiness(True, int(evaluated[j]), decisive[j]))
        keep = within_budgets(owner)
        if paused is not None and outcomes[pause] is not None and not outcomes[pause].proven:  # (its budget)
            outcomes[pause] = outcomes[pause]._replace(paused=paused)
        lo, hi, owner, plo, phi = _taken(keep, lo, hi, owner, plo, phi)
        if rounds_begun == 2 and lead is not None and outcomes[lead] is not None:  # (the leader ended by its first
            # box)
            end(np.flatnonzero(searching(owner)), lambda j: Emptiness(False, int(evaluated[j]), decisive[j]))
            break
        if not lo.shape[1]:
            break
        evaluated += np.bincount(owner, minlength=count)
        ends = _end_boxes(lo, hi, owner, ranged, posed.integer) if intervals else np.zeros(0, dtype=int)
        (g_lo, g_hi), (d_lo, d_hi), centre, (c_lo, c_hi), at_ends = _bounds(
            functions, lo, hi, (plo, phi), (ends, p_lo[:, owner[ends]], p_hi[:, owner[ends]]))
        first_met = _first_boxes(np.flatnonzero(np.all(c_hi <= 0.0, axis=0)), owner)  # each search's first box met
        whole_p = (np.all(_same(plo, p_lo[:, owner]) & _same(phi, p_hi[:, owner]), axis=0) if first_met
                   else None)
        end(sorted(first_met), lambda j: (  # a design for every parameter of the search, or (a part of its interval)
            Emptiness(False, int(evaluated[j]), decisive[j], centre[:, first_met[j]]) if whole_p[first_met[j]]
            else Emptiness(False, int(evaluated[j]), decisive[j], reached=True, witness=centre[:, first_met[j]])))
        # (for some: no proof for all)
        reached = _reached(at_ends, ends, owner, first_met) if len(ends) else {}
        end(list(reached), lambda j: Emptiness(False, int(evaluated[j]), decisive[j], reached=True,
                                               witness=centre[:, reached[j]]))
        keep = ~flagged([*first_met, *reached])[owner]
        empty = g_lo > TOLERANCE
        running = searching(owner[keep])
        tally(names, empty & keep, owner)
        alive = keep & ~empty.any(axis=0)
        lo, hi, owner, plo, phi, g_hi = _taken(alive, lo, hi, owner, plo, phi, g_hi)
        uncertain, at = g_hi > 0.0, np.flatnonzero(alive)
        if not alive.all():
            end(np.flatnonzero(running & ~searching(owner)),
                lambda j: Emptiness(True, int(evaluated[j]), decisive[j]))
        counts = np.bincount(owner, minlength=count)
        spreading = (counts > 0) & (evaluated > SURE_BOXES) & (counts > GROWTH * left)
        end(np.flatnonzero(spreading), lambda j: Emptiness(False, int(evaluated[j]), decisive[j]))  # not closing
        # in: give up
        left = np.where(counts > 0, counts, left)
        lo, hi, owner, uncertain, plo, phi, at = _taken(~spreading[owner], lo, hi, owner, uncertain, plo, phi, at)
        if not lo.shape[1]:
            break
        if len(at) < d_lo.shape[-1]:  # (at: the boxes left, in order; all of them: as they are)
            d_lo, d_hi = d_lo[..., at], d_hi[..., at]
        contracting = searching(owner)
        lo, hi, cut_empty, cut = contracted(lo, hi, centre[:, at], c_lo[:, at], d_lo, d_hi, TOLERANCE)
        carried = carries and rounds_begun > 1  # (from the searches' second evaluation on: a search that
        # ends at its first box, as most of a static sweep's do, costs what it did and ends the same whatever its
        # budget; carried back from the first box, the lever in design mode over 1x-10x its inertia: 40 points proven
        # in 8.0 s, from the second 37 in 5.7 s, the bench's static sweeps 1.2x-1.3x slower)
        if carried:  # each row's limit carried back through its expressions
            lo, hi, back_empty, back_cut = backward_contracted(row_tape(posed, functions), lo, hi, [(plo, phi)],
                                                               TOLERANCE, uncertain)
            cut_empty, cut = cut_empty | back_empty, cut | back_cut
        tally(names, cut, owner)  # the rows a proof rests on: those that cut, too
        whole = ~cut_empty
        if not whole.all():
            lo, hi, owner, uncertain, d_lo, d_hi, plo, phi, at = _taken(whole, lo, hi, owner, uncertain, d_lo, d_hi,
                                                                        plo, phi, at)
            end(np.flatnonzero(contracting & ~searching(owner)),
                lambda j: Emptiness(True, int(evaluated[j]), decisive[j]))
        if not lo.shape[1]:
            break
        lo, hi = _faces(lo, hi, d_lo, d_hi, uncertain)
        counts = np.bincount(owner, minlength=count)
        with np.errstate(divide="ignore"):  # few large batches: an iteration costs per call as much as per box
            rounds = np.maximum(1, np.ceil(np.log2(_batch(posed) / np.maximum(counts, 1)))).astype(int)
        if not posed.integer:  # without integers no box is dropped before the next evaluation (rounding keeps them
            # all) and each of its rounds splits in two every box with a width (a point box stays one): a search whose
            # boxes would then pass its budget ends here, as it would at the split that passes it, its outcome
            # the same (its boxes evaluated and decisive rows are those of the evaluations before), without the splits
            # (a sweep's 28 points past its region's edge searched alone at 64 boxes: 6 rounds of splits to 1,792
            # boxes for nothing, 8 ms)
            wide = np.any(hi > lo, axis=0) | np.any(phi > plo, axis=0)
            grown = np.bincount(owner, np.where(wide, 2.0 ** rounds[owner], 1.0), count)
            if pause is not None:  # (split: its budget ends it at the next iteration, where it then stands)
                grown[pause] = 0
            keep = within_budgets(owner, grown)
            if not keep.all():
                lo, hi, plo, phi = lo[:, keep], hi[:, keep], plo[:, keep], phi[:, keep]
                owner, at = owner[keep], at[keep]
                d_lo, d_hi, uncertain = d_lo[..., keep], d_hi[..., keep], uncertain[:, keep]
                if not lo.shape[1]:
                    break
        slope = (_slopes(d_lo, d_hi, uncertain) if not carried  # (once an iteration: each half inherits its box's)
                 else np.zeros((0, len(owner))))  # (none where the rows are carried back: _bisected)
        if not intervals:  # (no parameter interval to split: the boxes' parameters follow their boxes)
            for turn in range(int(rounds[owner].max())):
                lo, hi, owner, parents = _bisected_where(lo, hi, owner, slope, spans0, rounds[owner] > turn)
                plo, phi, slope = plo[:, parents], phi[:, parents], slope[:, parents]
            continue
        component, rate = _parameter_spread(plo, phi, p_width0[:, owner], (c_hi - c_lo)[:, at], uncertain)
        z_lo, z_hi = np.vstack([lo, plo]), np.vstack([hi, phi])  # (the design over the parameters through the turns)
        for turn in range(int(rounds[owner].max())):
            columns = np.arange(len(owner))
            relative = (z_hi[n:] - z_lo[n:])[component, columns] / np.where(p_width0[component, owner] > 0,
                                                                           p_width0[component, owner], np.inf)
            extra = np.full((z_lo.shape[0] - n, len(owner)), -1.0)
            extra[component, columns] = np.where(relative > 0, relative if carried else rate * relative,
                                                 -1.0)  # (carried back: its own relative width, as the design's)
            z_lo, z_hi, owner, parents = _bisected_where(z_lo, z_hi, owner, slope, spans0, rounds[owner] > turn, extra)
            slope, component, rate = slope[:, parents], component[parents], rate[parents]
        lo, plo, hi, phi = z_lo[:n], z_lo[n:], z_hi[:n], z_hi[n:]
    return outcomes


def _state(mask: np.ndarray, lo, hi, plo, phi, evaluated, left, rounds_begun: int, decisive: dict,
           budget) -> Paused:
    """A search's state at an iteration's start (``mask``: its boxes), copied (:class:`Paused`)."""
    return Paused(lo[:, mask], hi[:, mask], plo[:, mask], phi[:, mask], int(evaluated), float(left), rounds_begun,
                  dict(decisive), int(budget))


def _taken(mask: np.ndarray, *arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    """``arrays`` (boxes along their last axis) with only the boxes ``mask`` keeps; as they are where it keeps every
    one (an iteration filters its boxes six times, most often keeping them all: a copy of every array for nothing)."""
    return arrays if mask.all() else tuple(array[..., mask] for array in arrays)


def _batch(posed) -> int:
    """The boxes an iteration evaluates at least: BATCH, INTEGER_BATCH for a design with integer variables.

    Splitting a box k times before its halves are evaluated skips the emptiness tests, contractions and roundings
    of the k - 1 generations between: the ball's boxes, which those empty or cut within a few splits, paid for that
    in boxes more than an evaluation's cost per call saved (its five searches over 0.5x-2x its allowable contact
    stress: 2,853 boxes at 128, 941 at 32, 736 at 16; CPU 88-104, 65-70 and 77-79 ms). The lever's region searches
    (no integers, budget FEW_BOXES) keep 128: one evaluation then a round of splits past their budget ends those that
    cannot prove at once (at 32: 57 boxes to 953 over its friction coefficient, 5.4 to 13.5 ms)."""
    return INTEGER_BATCH if posed.integer else BATCH


def _same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a == b) | (np.isnan(a) & np.isnan(b))


def _parameter_spread(plo, phi, p_width0, c_width, uncertain) -> tuple[np.ndarray, np.ndarray]:
    """Where a box's parameters are an interval (a run of a sweep's points): the parameter widest relative to its
    search's interval, and how much the box's uncertain rows spread over that interval at its centre per unit of
    relative width (the rows' bounds at a point: all their width comes from the parameters, split where it exceeds
    the design variables' spread, :func:`_bisected`); 0 where the parameters are fixed or the spread unbounded."""
    with np.errstate(invalid="ignore", divide="ignore"):
        relative = np.where(p_width0 > 0, (phi - plo) / p_width0, 0.0)
    component = np.argmax(relative, axis=0)
    widest = relative[component, np.arange(relative.shape[1])]
    spread = np.where(uncertain & np.isfinite(c_width), c_width, 0.0).max(axis=0, initial=0.0)
    return component, np.where(widest > 0, spread / np.where(widest > 0, widest, 1.0), 0.0)


def _end_boxes(lo: np.ndarray, hi: np.ndarray, owner: np.ndarray, ranged: np.ndarray, integer: list[int]
               ) -> np.ndarray:
    """The boxes of searches over a parameter interval (``ranged``) whose centres, their integer variables whole,
    are tried at the interval's ends (:func:`_reached`), evaluated with the boxes (:func:`_bounds`)."""
    centre = 0.5 * (lo + hi)
    whole = np.all(centre[integer] == np.round(centre[integer]), axis=0)
    return np.flatnonzero(ranged[owner] & whole)


def _reached(at_ends: np.ndarray, boxes: np.ndarray, owner: np.ndarray, ended: dict[int, int]
             ) -> dict[int, int]:
    """The searches over a parameter interval, not ``ended`` already, where a box's centre (of ``boxes``:
    :func:`_end_boxes`) meets every row at one end of the interval (``at_ends``: the rows' upper bounds there, the
    interval's low ends' columns, then its high ends'): a design there, so the interval holds no proof (a run of a
    sweep's points reaching past its infeasible region: the search stops at once rather than at its budget); each
    with the first such box."""
    met = np.all(at_ends[:, :len(boxes)] <= 0.0, axis=0) | np.all(at_ends[:, len(boxes):] <= 0.0, axis=0)
    return _first_boxes(boxes[met & ~np.isin(owner[boxes], list(ended))], owner)


def _first_boxes(boxes: np.ndarray, owner: np.ndarray) -> dict[int, int]:
    """Each search's first box among ``boxes`` (ascending box numbers; ``owner``: each box's search), by search."""
    searches, first = np.unique(owner[boxes], return_index=True)
    return dict(zip(searches.tolist(), boxes[first].tolist()))


def _whole(lo: np.ndarray, hi: np.ndarray, integer: list[int]) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """The boxes with their integer variables' ranges rounded inwards to whole numbers (1e-9 of slack), those left
    without a whole number dropped (an integer design lies in what is left); how many each integer variable
    dropped."""
    lo, hi, none = _rounded(lo, hi, integer)
    kept = ~none.any(axis=0)
    return lo[:, kept], hi[:, kept], [int(row.sum()) for row in none]


def _rounded(lo: np.ndarray, hi: np.ndarray, integer: list[int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_whole`'s boxes rounded, all of them, and which each integer variable leaves without a whole number
    (a row per integer variable, a column per box)."""
    if not integer:
        return lo, hi, np.zeros((0, lo.shape[1]), dtype=bool)
    lo, hi = lo.copy(), hi.copy()
    lo[integer], hi[integer] = np.ceil(lo[integer] - 1e-9), np.floor(hi[integer] + 1e-9)
    return lo, hi, lo[integer] > hi[integer]


def _bisected_where(lo, hi, owner, slope, spans0, split, extra=None):
    """:func:`_bisected` of the boxes ``split`` selects (the others kept), every search's boxes in the order its
    own bisection gives (its boxes' first halves, then its second halves); the boxes and the box each came from. The
    boxes split in place and their second halves after them (:func:`_bisected`'s ``chosen``), in the order of their
    boxes in both parts: a stable sort by search and part is that order (a selection bisected apart and sorted by
    search, part and box had cost half again as much as the bisection, a third of the ball's searches' NumPy)."""
    lo, hi, parents = _bisected(lo, hi, slope, tuple(span[:, owner] for span in spans0), extra, split)
    if not len(owner) or not (owner != owner[0]).any():  # one search: as it is
        return lo, hi, owner[parents], parents
    order = np.argsort(2 * owner[parents] + (np.arange(len(parents)) >= len(owner)), kind="stable")
    return lo[:, order], hi[:, order], owner[parents][order], parents[order]


class BoxBounds(NamedTuple):
    """What one evaluation gives over boxes (:func:`_bounds`)."""

    rows: tuple[np.ndarray, np.ndarray]  # the rows' bounds over each box (rows x boxes)
    slopes: tuple[np.ndarray, np.ndarray]  # the Jacobian's (rows x variables x boxes)
    centre: np.ndarray  # each box's centre (variables x boxes)
    at_centre: tuple[np.ndarray, np.ndarray]  # the rows' bounds there (rows x boxes)
    at_ends: np.ndarray  # the rows' upper bounds at the further points asked for (rows x points)


def _bounds(functions, lo: np.ndarray, hi: np.ndarray, params: tuple[np.ndarray, np.ndarray],
            ends: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> BoxBounds:
    """Over each box: the rows' bounds (the natural interval extension met with the mean-value form
    g(c) + J(X) (X - c), which is tight on small boxes), the Jacobian's bounds (rows x variables x boxes), the centre
    and the rows' bounds there; ``params``: each box's parameters (a column), their lower and upper ends (the mean
    value form holds for each parameter vector between them: g(x, p) = g(c, p) + J(xi, p) (x - c)). ``ends``: boxes
    (their numbers) whose centres are evaluated too at two further parameter vectors each (the ends of a search's
    interval, one column a box each: :func:`_reached`). The declared nodes enclosed once over all of them, the
    Jacobian (which gives the rows too) replayed over the boxes and the rows alone over the centres and ends
    (``interval_nodes.split_bounds``): a box's bounds are its own (the rules work box by box), the same bits as one
    replay of the Jacobian's function over every column, which had cost the ball's searches its 359 instructions at
    each centre and end where its rows take 153 (about a third less of the replays' work an iteration)."""
    rows, slopes = functions
    count, n = lo.shape[1], lo.shape[0]
    centre = 0.5 * (lo + hi)
    x_lo, x_hi, p_lo, p_hi = [lo, centre], [hi, centre], [params[0]] * 2, [params[1]] * 2
    boxes = np.zeros(0, dtype=int) if ends is None else ends[0]
    for p_end in ((ends[1], ends[2]) if len(boxes) else ()):
        x_lo.append(centre[:, boxes]), x_hi.append(centre[:, boxes]), p_lo.append(p_end), p_hi.append(p_end)
    ((d_lo, d_hi), (g_lo, g_hi)), ((r_lo, r_hi),) = split_bounds(
        slopes, rows, [(np.hstack(x_lo), np.hstack(x_hi)), (np.hstack(p_lo), np.hstack(p_hi))], count)
    c_lo, c_hi, at_ends = r_lo[:, :count], r_hi[:, :count], r_hi[:, count:]
    m = g_lo.shape[0]
    d_lo, d_hi = d_lo.reshape(n, m, count).transpose(1, 0, 2), d_hi.reshape(n, m, count).transpose(1, 0, 2)
    step_lo, step_hi = (lo - centre)[None], (hi - centre)[None]
    with np.errstate(invalid="ignore"):
        corners = np.stack([d_lo * step_lo, d_lo * step_hi, d_hi * step_lo, d_hi * step_hi])
    corners = np.where(np.isnan(corners), 0.0, corners)  # 0 * inf: a variable the box fixes adds nothing
    mv_lo, mv_hi = c_lo + corners.min(axis=0).sum(axis=1), c_hi + corners.max(axis=0).sum(axis=1)
    mv_lo, mv_hi = np.where(np.isnan(mv_lo), -np.inf, mv_lo), np.where(np.isnan(mv_hi), np.inf, mv_hi)
    return BoxBounds((np.maximum(g_lo, mv_lo), np.minimum(g_hi, mv_hi)), (d_lo, d_hi), centre, (c_lo, c_hi),
                     at_ends)


def _faces(lo: np.ndarray, hi: np.ndarray, d_lo: np.ndarray, d_hi: np.ndarray,
           uncertain: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each box shrunk to its face where every uncertain row is monotone in a variable (the side it may favour)."""
    relevant = uncertain[:, None, :]  # rows x 1 x boxes
    falling = np.all(~relevant | (d_hi <= 0.0), axis=0)  # variables x boxes: no uncertain row rises with it
    rising = np.all(~relevant | (d_lo >= 0.0), axis=0)
    return np.where(falling & ~rising, hi, lo), np.where(rising, lo, hi)


def _slopes(d_lo: np.ndarray, d_hi: np.ndarray, uncertain: np.ndarray) -> np.ndarray:
    """Each variable's largest |dg/dx| over a box's uncertain rows (variables x boxes; rows x variables x boxes of
    slope bounds in): what :func:`_bisected` splits by, taken once an iteration and inherited by the halves (the
    rows x variables x boxes bounds had been carried through every round of splits for it)."""
    return np.where(uncertain[:, None, :], np.maximum(np.abs(d_lo), np.abs(d_hi)), 0.0).max(axis=0)


def _bisected(lo: np.ndarray, hi: np.ndarray, slope: np.ndarray, spans0: tuple[np.ndarray, np.ndarray],
              extra: np.ndarray | None = None, chosen: np.ndarray | None = None
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each box split in two across the variable that spreads its uncertain rows most (largest |dg/dx| width,
    ``slope``: :func:`_slopes`; a variable whose slope is unbounded first, the widest of them relative to the design
    box), at its middle (a positive range over a factor 4: its geometric middle); the halves and the box each came
    from. ``spans0``: each box's design box's widths and, where a variable is positive throughout it, the log of its
    ends' ratio. Where the rows are carried back (:mod:`clutchopt.optimise.interval_backward`; ``slope`` without
    rows), across the variable widest relative to its design box instead, by the log of its ends' ratio where it is
    positive (a row carried back through a product bounds a variable by the ratios of the others' ends; the lever in
    design mode at 5x, 8x its inertia: proven in 7,139 and 1,021 boxes; split by the slopes, 7,644 and 1,365).
    ``extra``: the spread of further rows of the boxes below the design variables (a parameter interval's:
    :func:`_searched`); ``chosen``: the boxes that may split (the others kept as they are)."""
    (width0, ratio0), n = spans0, spans0[0].shape[0]
    x_lo, x_hi = lo[:n], hi[:n]
    with np.errstate(invalid="ignore", divide="ignore"):  # an unbounded slope times a zero width: the where's other
        # branch; a ratio of ends not positive: the difference's
        if len(slope):
            smear = np.where(np.isfinite(slope), slope * (x_hi - x_lo), 1e300 * (x_hi - x_lo) / width0)
        else:
            smear = np.where(np.isfinite(ratio0) & (x_lo > 0), np.log(x_hi / x_lo) / ratio0, (x_hi - x_lo) / width0)
    smear = np.where(x_hi > x_lo, smear, -1.0)
    if extra is not None:
        smear = np.vstack([smear, extra])
    widest = np.argmax(smear, axis=0)
    columns = np.arange(lo.shape[1])
    a, b = lo[widest, columns], hi[widest, columns]
    with np.errstate(invalid="ignore"):  # (the square root of a range across 0: the where's other branch)
        middle = np.where((a > 0) & (b > 4 * a), np.sqrt(a * b), 0.5 * (a + b))  # wide positive ranges: by ratio
    split = b > a
    if chosen is not None:
        split &= chosen
    halved = np.flatnonzero(split)
    count, rows = lo.shape[1], widest[halved]
    new_lo, new_hi = np.concatenate([lo, lo[:, halved]], axis=1), np.concatenate([hi, hi[:, halved]], axis=1)
    new_hi[rows, halved] = new_lo[rows, count + np.arange(len(halved))] = middle[halved]  # (the first half's upper
    # end and the second's lower at the middle; the rest of each half its box's)
    return new_lo, new_hi, np.concatenate([columns, halved])


def empty_design_space(posed, case, budget: int | None = None, resume: Emptiness | None = None) -> Emptiness | None:
    """:func:`search` over the design box of ``case`` in ``posed`` (with a start-up: its formulation's own
    constraints, without the start-up's: a design space empty without them is empty with them); the search a sweep
    ran for the same box with the same parameters where one is kept (:func:`keep_search`). ``budget``: the most boxes
    (a search that may end short of its outcome: the kept one is left for the search without a budget; one its budget
    ends says where it stood, ``Emptiness.paused``). ``resume``: such a search of this case, which the search without
    a budget goes on from (its outcome that search's; the boxes before the pause not evaluated again: the lever in
    design mode next to its edge, 2,113 of 3,802 at 3.6x its inertia); a kept search its budget ended is that
    search's where the budget is the same, and resumed by the search without one."""
    problem = _search_problem(posed, case)
    kept = posed.built("interval_kept", None, lambda _: {})
    kept = kept.get(_key(problem)) if budget is not None else kept.pop(_key(problem), None)
    if kept is not None and kept.paused is not None and kept.paused.budget != budget:  # (another budget ended it)
        if budget is None:  # (resumed by the search without one)
            resume = kept
        kept = None
    along = _along(posed)
    if kept:
        emptiness = kept
    elif "problems" in along and budget is not None:
        emptiness, outcomes, seconds = searched_along(posed, problem, budget, along.pop("problems"))
        if outcomes:
            along["outcomes"], along["seconds"] = outcomes, seconds
    else:
        emptiness = searches(posed, [problem], None if budget is None else [budget], pause=budget is not None,
                             resumed=resume.paused if budget is None and resume is not None else None)[0]
    if emptiness is not None and emptiness.proven:
        last_boxes(posed, emptiness.boxes)
    return emptiness


def searched_along(posed, problem: tuple[np.ndarray, ...], budget: int,
                   along: Callable[[], list[tuple[np.ndarray, ...]]]) -> tuple[Emptiness | None, list, float]:
    """``problem``'s search within ``budget`` boxes and the problems ``along()`` gives (a sweep's runs after a point,
    each within SURE_BOXES) in the same call: an iteration costs per call, and a point's proof takes about as many
    as its runs' (the ball's). The point's search leads (:func:`searches`' ``lead``): where its first box decides it,
    the others end there, those not ended yet given up (a point proven in a box has its runs searched point by
    point, not as regions, ``region_proof.Regions._one_by_one``, and a region's search may take far more iterations
    than the point's: the cable over 10x-20x its torque, 1 box a point). Its outcome, theirs and the call's
    seconds."""
    problems = along()
    began = time.perf_counter()
    own, *outcomes = searches(posed, [problem, *problems], [budget] + [SURE_BOXES] * len(problems), lead=True,
                              pause=budget < MAX_BOXES)  # (a search given up at MAX_BOXES is not resumed)
    return own, outcomes, time.perf_counter() - began


def search_along(posed, problems: Callable[[], list[tuple[np.ndarray, ...]]] | None) -> dict:
    """The problems ``problems()`` gives (a sweep's runs after a point: ``region_proof.Regions._next_runs``; built
    only where they are searched) searched in the same call as the next budgeted :func:`empty_design_space` of
    ``posed`` (a point's verdict's first search, before its retries), each within SURE_BOXES: an iteration costs per
    call. The dict returned gets their ``outcomes`` and the call's ``seconds`` if that search runs (None clears
    it)."""
    along = _along(posed)
    along.clear()
    if problems is not None:
        along["problems"] = problems
    return along


def _along(posed) -> dict:
    return posed.built("interval_along", None, lambda _: {})


def last_boxes(posed, boxes: int | None = None) -> int:
    """The boxes of the last search of ``posed`` that proved (``boxes``: record them): what a search near it may take
    (``region_proof``'s budget)."""
    kept = _proofs(posed)
    if boxes is not None:
        kept["boxes"], kept["proofs"] = boxes, kept["proofs"] + 1
    return kept["boxes"]


def carry_boxes(posed, boxes: int) -> None:
    """:func:`last_boxes` set as a run before this process left it, no proof counted (a resumed sweep's window starts
    its region proofs' budgets where the uninterrupted run's did: ``batch_carried``)."""
    _proofs(posed)["boxes"] = boxes


def proofs_recorded(posed) -> int:
    """How many searches of ``posed`` that proved :func:`last_boxes` has recorded (a verdict between two counts
    rests on one of them where the count grew)."""
    return _proofs(posed)["proofs"]


def boxes_evaluated(posed) -> int:
    """How many boxes the searches of ``posed`` have evaluated in this process (a batched sweep's window counts them
    as work: ``batch``'s BOX_WORK)."""
    return _proofs(posed)["evaluated"]


def _proofs(posed) -> dict[str, int]:
    return posed.built("interval_last", None, lambda _: {"boxes": 0, "proofs": 0, "evaluated": 0})


def _search_problem(posed, case) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The parameters (variable scales 1: x in SI) and the design box of ``case``'s search."""
    lower, upper, _ = posed.bounds_and_start(case, None)
    mesh = posed.start_up.initial_mesh(graded_part(posed.start_up.s.spec, case.values)) if posed.start_up else []
    p = np.concatenate([list(vars(posed.params(case)).values()), np.ones(len(lower)), [1.0], mesh])
    return p, lower, upper


def keep_search(posed, problem: tuple[np.ndarray, ...], emptiness: Emptiness | None) -> None:
    """Keep a search's outcome for :func:`empty_design_space` of the same problem (only the last one kept; one its
    budget ended, ``Emptiness.paused``, for a search within the same budget, and resumed by one without)."""
    kept = posed.built("interval_kept", None, lambda _: {})
    kept.clear()
    if emptiness is not None:
        kept[_key(problem)] = emptiness


def _key(problem: tuple[np.ndarray, ...]) -> tuple[bytes, ...]:
    return tuple(np.asarray(part, dtype=float).tobytes() for part in problem)

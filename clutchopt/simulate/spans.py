"""One phase of a start-up integrated by LSODA in spans, each span one call of ``scipy.integrate.odeint`` (its steps
in one Fortran loop: Python only for the right-hand side and its Jacobian), the phase's events found on the span's
samples afterwards. It takes the place of :mod:`clutchopt.simulate.stepping` for LSODA, whose ``solve_ivp``
machinery (a Python step, a dense output and every event at each step) was three quarters of a check's time
(docs/simulate.md, "Integrator and why"):

- samples: their spacing growing geometrically over the whole phase (so they crowd where a phase begins, where its
  fast transients are, as the solver's steps did, and the spacing has no jumps: the next mesh is adapted to the
  second differences of the samples); a span is SPAN_SAMPLES of them, cut short where the terminal events,
  extrapolated from the last two samples, are expected to end the phase; each span restarts LSODA;
- events: each evaluated on all of a span's samples at once (an event written with NumPy operations takes the
  arrays; one that does not is evaluated sample by sample); where one changes sign (as ``solve_ivp`` counts a
  crossing, see :func:`clutchopt.simulate.stepping.crosses`) between two samples, its root is found by Brent's
  method (a terminal event's to 4 eps, a sampled extremum's to EXTREMUM_XTOL of the interval) on the interpolant
  of the nearest LOCAL_NODES samples (a caller's ``nodes``); a sampled event's state is the interpolant's where the
  caller asks and the interpolant of as many samples one further agrees with it there within the solver's tolerance
  (:func:`_interpolated`), else, and a terminal event's always, it is integrated to from the sample before; then a
  terminal event's root is taken a Newton step further on the event's value there and the state integrated on to it.
  Where that interpolant is off the integrated state by more than TRUSTED (a motion too fast for the span's
  samples: the cable's torsional swings), the interval is integrated again sampled ZOOM_SAMPLES times and the
  same is done on those samples; a sampled event whose caller wants only the largest of a figure at its roots
  (its ``figure``, of samples: the cable's stress and twist) is not located where the figure's samples at both ends
  of the interval are below its largest so far by more than PEAK_MARGIN;
- a budget of solver steps shared by the phases of a run (:class:`~clutchopt.simulate.stepping.Budget`), counted
  after each span.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.integrate import ODEintWarning, odeint
from scipy.optimize import brentq

from clutchopt.simulate.stepping import EPS, Budget, Phase, crosses

FIRST_SAMPLES = 128  # the first 128 samples of a phase take ``span``, every next 128 eight times as long: the
SPACING_GROWTH = 8.0 ** (1.0 / FIRST_SAMPLES)  # ratio of consecutive samples' spacing (the next mesh is adapted to
# these samples: with 64 or 256 samples to the eightfold, the ball's accuracy loop took 11 to 21 solves, not 9)
SPAN_SAMPLES = 192  # samples of a span: each restart of LSODA costs some 20-40 steps (128: 10 % more steps, 384:
# 10-30 % more, as a span overshoots the phase's end)
ZOOM_SAMPLES = 32  # the interval where an event changes sign, integrated again with this many samples
LOCAL_NODES = 6  # samples of that interval interpolated (degree 5) to find the root (a caller may take more)
TRUSTED = 1e-6  # relative: an interpolant of a span's samples this near the state integrated to its root is used
PEAK_MARGIN = 1e-2  # relative: an extreme whose interval's samples are this far below the figure's largest sample
# so far is not located. Between samples h apart a swing of period P and amplitude A rises above the nearer sample by
# at most A (pi h / P)^2 / 2: 5.4e-4 A at 96 samples a swing, 8.6e-3 A where the swing is twice as fast as the period
# the samples are drawn for (simulate/elastic.py: up to 2x) and the figure (a stress, as the twist squared) swings at
# twice that; a figure >= 0 has A <= its peak / 2, so no such extreme can be the largest: the peaks are the same, the
# samples fewer (cable_motor_start's checks: 5-7 of 45-47 extremes, 9.1 -> 6.1 ms)
EXTREMUM_XTOL = 1e-9  # of the sample interval: a sampled event's root (a maximum, whose value moves by the square
# of the time's error; its state is integrated to the root found): 7.6 of Brent's steps a root, not 11
SUCCESS = "Integration successful."
AHEAD = 1.25  # a span ends this much beyond where its events' extrapolation expects the first terminal one
SHORTEST = 0.05  # of the span it would have been: no span shorter (an extrapolation that undershoots)


def _predicted(events, times: np.ndarray, states: np.ndarray, t: float, length: float) -> float:
    """Where the span should end so that it does not run far past the phase's end: AHEAD times as far as the
    first terminal event, extrapolated linearly from the last two samples, is expected to cross zero."""
    if len(times) < 2 or times[-1] <= times[-2]:
        return np.inf
    t_old, t_new = times[-2], times[-1]
    expected = np.inf
    for event in events:
        if not event.terminal:
            continue
        g_old, g_new = event(t_old, states[:, -2]), event(t_new, states[:, -1])
        if g_new == g_old or (g_new - g_old) * event.direction < 0:
            continue
        ahead = -g_new * (t_new - t_old) / (g_new - g_old)
        if ahead > 0:
            expected = min(expected, ahead)
    return t + max(AHEAD * expected, SHORTEST * length)


def integrate_spans(fun, jac, t0: float, y0: np.ndarray, bound: float, events: list, rtol: float, atol: np.ndarray,
                    budget: Budget, span: float, widest: float = np.inf, nodes: int = LOCAL_NODES,
                    extremes_interpolated: bool = False) -> Phase:
    """Integrate y' = fun(t, y) by LSODA (Jacobian ``jac``; ``fun`` may give one array it fills again at each call:
    ``odeint`` alone calls it, and copies it at once) from (t0, y0) towards ``bound`` until a terminal event,
    the bound, a failure or the end of ``budget``, as :func:`clutchopt.simulate.stepping.integrate` does; ``span``:
    the first FIRST_SAMPLES samples' time (their spacing grows from it), ``widest``: the largest spacing (a motion
    that swings: a fraction of its period, so that its extremes are found on the samples), ``nodes``: the samples
    an event's interpolant runs through; ``extremes_interpolated``: a sampled event's state taken from the
    interpolant where it is as accurate as the samples (:func:`_interpolated`)."""
    lsoda = _Lsoda(fun, jac, rtol, atol, budget, nodes, extremes_interpolated)
    peaks: dict[int, float] = {}  # each figure's largest sample so far (events with a ``figure``)
    times, states = [np.array([t0])], [np.array(y0, dtype=float).reshape(-1, 1)]
    t, y, first = t0, np.array(y0, dtype=float), 1
    ratio, spacing = SPACING_GROWTH, _first_spacing(span)
    widest = min(widest, (bound - t0) / FIRST_SAMPLES)  # (the spacing grows no further than the bound needs)
    with warnings.catch_warnings(), np.errstate(all="ignore"):  # NumPy's, all of them, once a phase
        warnings.simplefilter("ignore", ODEintWarning)  # a failed span is read from its message
        while t < bound:
            if budget.spent:
                return _phase(times, states, "budget")
            sequence = t0 + _offsets(np.arange(first, first + SPAN_SAMPLES + 1), spacing, ratio, widest)
            end = min(sequence[-1], bound, _predicted(events, times[-1], states[-1], t, sequence[-1] - t))
            if not end > t:  # a spacing below the time's resolution (or NaN): no span would ever advance
                return _phase(times, states, "failed", message=f"samples do not advance beyond t = {t:.17g} s")
            inside = sequence[(sequence > t) & (sequence < end)]
            grid = np.concatenate([[t], inside, [end]])
            first += len(inside) + 1
            samples = lsoda.run(y, grid)
            if samples is None:
                return _phase(times, states, "budget" if budget.spent else "failed", message=lsoda.message)
            terminal, sampled = _first_events(events, grid, samples, lsoda, peaks)
            if terminal is not None:
                interval, (root, state), number = terminal
                _extend(times, states, grid[1:interval + 1], samples[:, 1:interval + 1], sampled)
                times.append(np.array([root]))
                states.append(np.asarray(state, dtype=float).reshape(-1, 1))
                return _phase(times, states, "event", index=number)
            _extend(times, states, grid[1:], samples[:, 1:], sampled)
            t, y = end, samples[:, -1].copy()
    return _phase(times, states, "end")


def _first_spacing(span: float) -> float:
    """The spacing of a phase's first two samples, so that its first FIRST_SAMPLES samples take ``span``."""
    return span * (SPACING_GROWTH - 1.0) / (SPACING_GROWTH**FIRST_SAMPLES - 1.0)


def sample_times(t0: float, until: float, bound: float, span: float) -> np.ndarray:
    """The times of a phase's samples from ``t0`` strictly before ``until``, as :func:`integrate_spans` draws them
    towards ``bound`` (its spans' own ends left out): for a phase whose states are known in closed form."""
    spacing, widest = _first_spacing(span), (bound - t0) / FIRST_SAMPLES
    times, first = [], 1
    while True:
        sequence = t0 + _offsets(np.arange(first, first + SPAN_SAMPLES), spacing, SPACING_GROWTH, widest)
        times.append(sequence[sequence < until])
        if sequence[-1] >= until or not sequence[-1] > t0:
            return np.concatenate(times)
        first += SPAN_SAMPLES


def _offsets(indices: np.ndarray, spacing: float, ratio: float, widest: float) -> np.ndarray:
    """Time from a phase's start to its samples of these indices: spacings ``spacing`` x ``ratio``^i, each at most
    ``widest``."""
    if spacing >= widest:
        return widest * indices
    last = int(np.floor(np.log(widest / spacing) / np.log(ratio)))  # the last index of a spacing below ``widest``
    geometric = spacing * (ratio ** np.minimum(indices, last + 1) - 1.0) / (ratio - 1.0)
    return geometric + widest * np.maximum(indices - last - 1, 0)


class _Lsoda:
    """odeint runs from a state over a grid; their steps counted against the budget."""

    def __init__(self, fun, jac, rtol, atol, budget: Budget, nodes: int, interpolated: bool):
        self.fun, self.jac, self.rtol, self.atol, self.budget, self.nodes = fun, jac, rtol, atol, budget, nodes
        self.interpolated = interpolated  # a sampled event's state from the interpolant where it is as accurate
        self.message = ""
        self.refine = True  # roots on the spans' own samples first (:func:`_refined`)

    def run(self, y0, grid):
        """The states at the grid's times (columns), integrated from ``y0`` at grid[0]; None if LSODA failed."""
        left = max(self.budget.steps - self.budget.taken, 1)
        states, info = odeint(self.fun, y0, grid, Dfun=self.jac, tfirst=True, rtol=self.rtol, atol=self.atol,
                              full_output=True, mxstep=left)
        self.budget.taken += int(info["nst"][-1])
        if info["message"] != SUCCESS:
            self.message = f"LSODA: {info['message']}"
            if "Excess work" in info["message"]:  # mxstep: the budget's steps are spent
                self.budget.taken = max(self.budget.taken, self.budget.steps)
            return None
        return states.T


def _first_events(events, grid, samples, lsoda: _Lsoda, peaks: dict):
    """The first terminal event among a span's samples, (its sample interval, (root, state), its index) or None,
    and the sampled events' (time, state) before it (in the whole span if none) where they can be their figure's
    largest (:func:`_below_peak`, ``peaks``)."""
    crossings = [_crossings(event, _values(event, grid, samples)) for event in events]
    zooms: dict = {}
    first = min(((int(np.argmax(mask)), i) for i, (event, mask) in enumerate(zip(events, crossings))
                 if event.terminal and mask.any()), default=None)
    stop = None
    if first is not None:
        interval, i = first
        stop = _find(events[i], grid, samples, interval, zooms, lsoda, exact=True)
        if stop is None:  # the zoom found no crossing: the end of the interval nearer zero, as stepping's _root
            stop = _nearer(events[i], grid, samples, interval)
    sampled = []
    for number, (event, mask) in enumerate(zip(events, crossings)):
        if event.terminal:
            continue
        below = _below_peak(event, samples, peaks, number, None if first is None else first[0])
        for interval in np.flatnonzero(mask & ~below):
            if first is not None and interval > first[0]:
                break
            at = _find(event, grid, samples, interval, zooms, lsoda, exact=False)
            if at is not None and (stop is None or at[0] < stop[0]):
                sampled.append(at)
    sampled.sort(key=lambda pair: pair[0])
    return (None if first is None else (first[0], stop, first[1])), sampled


def _below_peak(event, samples, peaks: dict, number: int, last: int | None) -> np.ndarray:
    """Per sample interval of a span, whether a root of the sampled event ``number`` there cannot be the largest of
    its ``figure`` (a function of samples; none: False everywhere): the figure at both its samples below by more
    than PEAK_MARGIN the largest sample up to the interval's first (``peaks``: the spans' before, updated to
    ``last``, the span's last sample kept)."""
    figure = getattr(event, "figure", None)
    if figure is None:
        return np.zeros(samples.shape[1] - 1, dtype=bool)
    values = np.asarray(figure(samples), dtype=float)
    largest = np.maximum.accumulate(np.concatenate([[peaks.get(number, -np.inf)], values]))[1:]  # (NaN: kept)
    peaks[number] = largest[-1 if last is None else last]
    threshold = largest[:-1] - PEAK_MARGIN * np.abs(largest[:-1])
    return (values[:-1] < threshold) & (values[1:] < threshold)


def _nearer(event, grid, samples, interval: int):
    g = [event(grid[k], samples[:, k]) for k in (interval, interval + 1)]
    k = interval if abs(g[0]) < abs(g[1]) else interval + 1
    return grid[k], samples[:, k].copy()


def _values(event, times: np.ndarray, states: np.ndarray) -> np.ndarray:
    """The event at every sample: at once where it takes arrays, else sample by sample (within a phase: NumPy's
    floating-point warnings not shown)."""
    try:
        values = np.asarray(event(times, states), dtype=float)
        if values.shape == times.shape:
            return values
    except (TypeError, ValueError):
        pass
    return np.array([event(t, states[:, k]) for k, t in enumerate(times)], dtype=float)


def _crossings(event, g: np.ndarray) -> np.ndarray:
    """Per sample interval, whether the event crosses zero in it (:func:`~clutchopt.simulate.stepping.crosses`)."""
    return crosses(event, g[:-1], g[1:])


def _find(event, grid, samples, interval: int, zooms: dict, lsoda: _Lsoda, exact: bool):
    """(root, state) of the event's crossing in a span's sample interval: on the span's samples
    (:func:`_refined`), else on the interval integrated again (:func:`_zoom`, :func:`_locate`); None if neither
    shows one."""
    found = _refined(event, grid, samples, interval, lsoda, exact) if lsoda.refine else None
    if found is None:
        lsoda.refine = False  # the phase's motion is too fast for its spans' samples: zoom from now on
        found = _locate(event, _zoom(zooms, interval, grid, samples, lsoda), lsoda, exact)
    return found


def _refined(event, grid, samples, k: int, lsoda: _Lsoda, exact: bool):
    """The root on the interpolant of the span's samples around [k, k + 1] (Brent), the state integrated to it
    from sample k; a terminal event's root then taken one Newton step further on the event's exact value there
    (the interpolant's slope), the state integrated on to it. None where the interpolant does not bracket the
    root or the Newton step leaves the interval or does not bring the event nearer zero."""
    local, g_left, g_right = _opening(event, grid, samples, k, lsoda.nodes)
    if g_left == 0.0:
        return grid[k], samples[:, k].copy()
    if g_left * g_right >= 0:
        return None
    guess = _root(lambda s: event(s, local(s)), grid[k], grid[k + 1], exact)
    if guess is None or guess == grid[k]:
        return None
    if lsoda.interpolated and not exact and _interpolated(local, grid, samples, k, guess, lsoda):
        return guess, local(guess)  # (a terminal event's state integrated to, as ever: taken from the interpolant
        # too, it moved the ball's solves by 1e-13 and their IPOPT iterations from 133 to 172, its sweep's by 31 %;
        # the same of a slipping start's temperature peak moved them by one iteration: asked for by the cable's
        # start only, its 48 extremes)
    scale = lsoda.atol / lsoda.rtol
    state = lsoda.run(samples[:, k], np.array([grid[k], guess]))
    if state is None:
        return None
    state = state[:, -1]
    if np.any(np.abs(state - local(guess)) > TRUSTED * (np.abs(state) + scale)):
        return None  # the interpolant is off (a span too coarse for the motion): the root is not where it says
    if not exact:
        return guess, state
    g = event(guess, state)
    if g == 0.0:
        return guess, state
    h = TRUSTED * (grid[k + 1] - grid[k])
    slope = (event(guess + h, local(guess + h)) - event(guess - h, local(guess - h))) / (2.0 * h)
    root = guess - g / slope if slope else np.nan
    if not grid[k] < root <= grid[k + 1]:
        return None
    end = lsoda.run(state, np.array([guess, root])) if root != guess else state.reshape(-1, 1)
    if end is None or not abs(event(root, end[:, -1])) <= abs(g):
        return None
    return root, end[:, -1]


def _interpolated(local, grid, samples, k: int, s: float, lsoda: _Lsoda) -> bool:
    """Whether the interpolant ``local`` of the samples around [k, k + 1] is at ``s`` as accurate as the samples
    themselves: the interpolant of as many samples one further (its error estimate) agrees with it there
    within the solver's tolerance (rtol |y| + atol, each component). Then the state at a root is the interpolant's,
    not integrated again (LSODA restarted from sample k: some 20-40 steps a root)."""
    nodes = _nodes(k, len(grid), lsoda.nodes)
    other = nodes + (1 if nodes[-1] + 1 < len(grid) else -1)
    if len(nodes) < lsoda.nodes or other[0] < 0:
        return False
    here, there = local(s), _Interpolant(grid[other], samples[:, other])(s)
    return bool(np.all(np.abs(here - there) <= lsoda.rtol * np.abs(here) + lsoda.atol))


def _zoom(zooms: dict, interval: int, grid, samples, lsoda: _Lsoda):
    """A span's sample interval integrated again with ZOOM_SAMPLES samples (once for all its events): (times,
    states or None)."""
    if interval not in zooms:
        fine = np.linspace(grid[interval], grid[interval + 1], ZOOM_SAMPLES + 1)
        zooms[interval] = fine, lsoda.run(samples[:, interval], fine)
    return zooms[interval]


def _locate(event, zoom, lsoda: _Lsoda, exact: bool):
    """(root, state) of the event's first crossing in a zoomed interval (its state integrated to the root if
    ``exact``), or None where the interval integrated again shows none."""
    grid, samples = zoom
    if samples is None:
        return None
    mask = _crossings(event, _values(event, grid, samples))
    if not mask.any():
        return None
    k = int(np.argmax(mask))
    local, g_left, g_right = _opening(event, grid, samples, k, lsoda.nodes)
    if g_left == 0.0:
        return grid[k], samples[:, k].copy()
    if g_right == 0.0 or g_left * g_right > 0:
        root = grid[k + 1]
    else:
        root = _root(lambda s: event(s, local(s)), grid[k], grid[k + 1], exact)
        if root is None:  # not a number between: the sample nearer zero
            root = grid[k] if abs(g_left) < abs(g_right) else grid[k + 1]
    if not exact:
        return root, local(root)
    if root == grid[k]:
        return root, samples[:, k].copy()
    end = lsoda.run(samples[:, k], np.array([grid[k], root]))
    return root, (end[:, -1] if end is not None else local(root))


def _opening(event, grid, samples, k: int, nodes: int):
    """The interpolant of ``nodes`` samples around the interval [k, k + 1] and the event at its ends."""
    nodes = _nodes(k, len(grid), nodes)
    local = _Interpolant(grid[nodes], samples[:, nodes])
    return local, event(grid[k], samples[:, k]), event(grid[k + 1], samples[:, k + 1])


def _root(function, a: float, b: float, exact: bool = True) -> float | None:
    """Brent's method on [a, b], to 4 eps (``exact``: a terminal event's) or to EXTREMUM_XTOL of the interval (a
    sampled one); None where the function is not a number inside (an interpolated state outside the equations'
    domain)."""
    try:
        return brentq(function, a, b, xtol=4 * EPS if exact else EXTREMUM_XTOL * (b - a), rtol=4 * EPS)
    except ValueError:
        return None


def _nodes(k: int, count: int, nodes: int) -> np.ndarray:
    """``nodes`` sample indices around the interval [k, k + 1]."""
    first = min(max(k - nodes // 2 + 1, 0), max(count - nodes, 0))
    return np.arange(first, min(first + nodes, count))


class _Interpolant:
    """The polynomial through a few samples (barycentric form), each state component."""

    def __init__(self, times: np.ndarray, states: np.ndarray):
        self.t, self.y = times, states
        self.nodes = times.tolist()
        differences = times[:, None] - times[None, :]
        np.fill_diagonal(differences, 1.0)
        self.w = 1.0 / differences.prod(axis=1)

    def __call__(self, s: float) -> np.ndarray:
        if s in self.nodes:  # (a list's search: Brent calls this some 500 times a check of the cable)
            return self.y[:, self.nodes.index(s)].copy()
        c = self.w / (s - self.t)
        return self.y @ c / c.sum()


def _extend(times: list, states: list, grid: np.ndarray, samples: np.ndarray, sampled: list) -> None:
    """The span's samples and its sampled events' (time, state), in time order."""
    if sampled:
        t = np.concatenate([grid, [s for s, _ in sampled]])
        y = np.concatenate([samples, np.array([x for _, x in sampled]).T], axis=1)
        order = np.argsort(t, kind="stable")
        grid, samples = t[order], y[:, order]
    times.append(grid)
    states.append(samples)


def _phase(times: list, states: list, status: str, index: int | None = None, message: str = "") -> Phase:
    return Phase(np.concatenate(times), np.concatenate(states, axis=1), status, index, message)

"""Couplings of clutchopt as friction laws of a start-up, and designs checked against what they were sized for.

A centrifugal coupling's torque follows its driving speed: T = K (w_a^2 - w_e^2)^+, K = dT/d(w_a^2) from the
coupling's own torque equation at the design (its formulation's :class:`~clutchopt.model.SpeedLaw`: wedge eqs.
10-15, lever statics with new linings, ball eq. 8), w_e the engagement speed that spring preload and gravity set.
Sizing assumes the torque T_max = I_n w_a / t_p + T_c acts from the start at constant driving speed (constant
angular acceleration, wedge eqs. 5, 17): then the simulated start-up time is exactly I_n w_a / (T - T_c), which is
t_p when the torque constraint is active. A case with a ``[start_up]`` section is started on the drive it describes
(:func:`start_up_model`): that is the independent float64 check of the NLP's start-up.
"""

from __future__ import annotations

import json
import math
import threading
from collections import Counter
from pathlib import Path
from dataclasses import replace
from types import SimpleNamespace
from typing import NamedTuple

from clutchopt.errors import InputError, Problems, shown_value
from clutchopt.files import CASE_BYTES, read_text
from clutchopt.model import ElasticLaw
from clutchopt.simulate import effects as fx
from clutchopt.simulate.engine import Model, SimulationResult, simulate
from clutchopt.simulate.laws import CentrifugalFriction, InductionMotor, Load
from clutchopt.start_up.equations import RADIAL_EFFECTS, engagement_speed_squared, with_start_up
from clutchopt.units import float_text


MAX_TORQUE = 1e9  # N*m: the largest torque the simulator is tested with (clutchopt.simulate.scene.TORQUE)


def _formulation(coupling: str, mode: str | None):
    from clutchopt.formulations import get_coupling

    return get_coupling(coupling).formulation(mode)


def speed_law_missing(coupling: str, solution=None, slipping: bool = False) -> str | None:
    """Why a coupling (or its solution) cannot be started here, or None; ``slipping``: as a friction law of a
    scene (an elastic link starts through a case's [start_up] section only)."""
    from clutchopt.formulations import MODULES, get_coupling

    law = get_coupling(coupling).formulation().speed_law
    if slipping and isinstance(law, ElasticLaw):
        return (f"the {coupling} coupling is an elastic link, not a slipping one: start it through a case's "
                "[start_up] section (clutchopt solve; docs/start_up.md)")
    if law is None:
        available = [name for name in MODULES if get_coupling(name).formulation().speed_law is not None]
        return (f"the {coupling} coupling has no speed-dependent torque law in clutchopt.simulate yet "
                f"(available: {', '.join(available)})")
    if solution is not None and solution.status != "optimal":
        return f"the solution's status is {solution.status}, there is no design to start"
    return None


class DesignFile(NamedTuple):
    """A solved design read from its file: its mode, its design (SI), the choice of ``options.choose`` it was solved
    with (``{}`` where none) and whether it is a robust design (``solve --robust``: designed for the case's scatter)."""

    mode: str
    design: dict[str, float]
    choice: dict[str, str]
    robust: bool
    outputs: dict[str, float] = {}  # the derived quantities the solve wrote (at the case's nominal values)


def design_from_json(path: str | Path, coupling: str, case_path: str | Path | None = None,
                     start_up: bool = False) -> DesignFile:
    """A solved design (:class:`DesignFile`): the JSON of ``clutchopt solve --json`` (of the case ``case_path``; a
    case with a [start_up] section: ``start_up``, its design's spring preload read too, one of its variables).

    A design file is input like any other: a regular UTF-8 file, JSON without NaN or Infinity, every design
    variable a number within the variable's valid range (a design the solver could have returned)."""
    field = "coupling.design"
    text = read_text(path, CASE_BYTES, f"{field} ({Path(path).name})")
    try:
        data = json.loads(text, parse_constant=_no_constant, parse_float=float_text, object_pairs_hook=_once)
    except json.JSONDecodeError as exc:
        raise InputError(field, f"cannot read {path} as the JSON of clutchopt solve ({exc})") from None
    except ValueError as exc:
        raise InputError(field, f"{path}: {exc}") from None
    except RecursionError:
        raise InputError(field, f"{path}: JSON nested too deeply to be the output of clutchopt solve") from None
    if not isinstance(data, dict) or data.get("coupling") != coupling or not isinstance(data.get("design"), dict):
        raise InputError(field, f"{path} is not a solved {coupling} design (clutchopt solve --json)")
    if case_path is not None and Path(str(data.get("case", ""))).name != Path(case_path).name:
        raise InputError(field, f"{path} was solved for {shown_value(data.get('case'))}, "
                                f"not for {Path(case_path).name}")
    if data.get("status") != "optimal":
        raise InputError(field, f"{path}: the design's status is {shown_value(data.get('status'))}, not optimal")
    formulation = _formulation(coupling, str(data.get("mode")))
    if start_up:
        formulation = with_start_up(formulation)
    design, checked = data["design"], {}
    problems = Problems()
    known = {variable.name for variable in with_start_up(formulation).variables}  # (a start-up's design has its
    for name in design:  # spring preload beside the coupling's variables)
        if name not in known:
            problems.errors.append(InputError(f"{field} design.{name}", f"not a design variable of the {coupling} in "
                                                                        f"{formulation.mode} mode"))
    for variable in formulation.variables:
        value = design.get(variable.name)
        with problems.field():
            if variable.name not in design:
                raise InputError(f"{field} design.{variable.name}", "missing: `clutchopt solve --json` of the case "
                                 "writes every design variable (a start-up's spring preload too); solve the case again")
            number = isinstance(value, (int, float)) and not isinstance(value, bool)
            try:
                value = float(value) if number else math.nan
            except OverflowError:  # an integer beyond float64
                value = math.nan
            if not math.isfinite(value):
                raise InputError(f"{field} design.{variable.name}", f"must be a finite number (SI), got "
                                                                    f"{shown_value(design.get(variable.name))}")
            checked[variable.name] = variable.check(value, f"{field} design.{variable.name}")
    choice = data.get("choice", {})
    if not isinstance(choice, dict) or not all(isinstance(key, str) and isinstance(name, str)
                                               for key, name in choice.items()):
        problems.errors.append(InputError(f"{field} choice", f"must be the names of a choice of options.choose, got "
                                                             f"{shown_value(choice)}"))
    problems.raise_any()
    outputs = data.get("outputs") if isinstance(data.get("outputs"), dict) else {}
    return DesignFile(formulation.mode, checked, choice, "robust" in data,
                      {name: float(value) for name, value in outputs.items()
                       if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)})


def _no_constant(name: str):
    raise ValueError(f"{name} is not a number a solved design can hold")


def _once(pairs: list[tuple[str, object]]) -> dict:
    """A JSON object whose keys are given once each (a key given twice had kept its last value unsaid)."""
    twice = sorted(key for key, count in Counter(key for key, _ in pairs).items() if count > 1)  # (linear: a
    if twice:  # file of 1 MiB may hold 100,000 keys)
        raise ValueError(f"{', '.join(map(repr, twice))} given twice in one object")
    return dict(pairs)


def centrifugal_law(case, mode: str, design: dict[str, float], effects: tuple[str, ...],
                    spring_preload: float = 0.0) -> CentrifugalFriction:
    """The law of a design of ``case`` (solved in ``mode``); spring preload and gravity enter only if listed."""
    law = _formulation(case.coupling, mode).speed_law
    x, p = SimpleNamespace(**design), case.params()
    radial = [effect for effect in effects if effect in RADIAL_EFFECTS]
    if radial and law.mass_radius is None:
        raise InputError("effects", f"{radial[0]} does not apply to the {case.coupling} coupling (no weights held "
                                    "in by springs or their own weight)")
    force = _radial_force(law, x, p, effects, spring_preload)
    squared = engagement_speed_squared(force, law.mass_radius(x, p)) if force else 0.0
    coefficient = float(law.torque_coefficient(x, p))
    if not (math.isfinite(coefficient) and coefficient > 0 and math.isfinite(squared)
            and coefficient * p.speed**2 <= MAX_TORQUE):
        raise InputError("coupling.design", f"the design gives no usable torque law (dT/d(w^2) = {coefficient:.6g} "
                                            f"N*m*s^2, engagement at {math.sqrt(max(squared, 0.0)):.6g} rad/s): "
                                            f"torque at design speed must be positive and at most {MAX_TORQUE:g} N*m")
    return CentrifugalFriction(coefficient, float(squared))


def _radial_force(law, x, p, effects: tuple[str, ...], spring_preload: float) -> float:
    """F_s + m g per weight, each if listed: what holds a weight in against its centrifugal force."""
    force = 0.0
    if "spring_preload" in effects:
        force += fx.spring_preload(spring_preload)
    if "gravity" in effects:
        force += fx.gravity(law.weight_mass(x, p))
    return force


def worn_start_up_model(case, mode: str, design: dict[str, float], model):
    """``model`` (the design's start, :func:`start_up_model`) with worn linings, for a coupling whose torque changes
    as they wear (the lever; None for the others). Its worn torque is linear in w_a^2 and in the radial force F
    that holds a weight in, T_w = K_w w_a^2 - B (F + c dr): K_w = T_w(1 rad/s, 0) - T_w(0, 0) and
    w_e,worn^2 = -T_w(0, F) / K_w (docs/start_up.md, "Overload")."""
    law = _formulation(case.coupling, mode).speed_law
    if isinstance(law, ElasticLaw) or law.worn_torque is None:
        return None
    x, p = SimpleNamespace(**design), case.params()
    force = _radial_force(law, x, p, case.start_up.effects, design.get("spring_preload", p.spring_preload))
    worn = [float(law.worn_torque(x, p, speed, f)) for speed, f in ((1.0, 0.0), (0.0, 0.0), (0.0, force))]
    coefficient = worn[0] - worn[1]
    return replace(model, law=CentrifugalFriction(coefficient, max(-worn[2] / coefficient, 0.0)))


def ideal_start(case, mode: str, design: dict[str, float]) -> SimulationResult:
    """The start-up the sizing assumes: constant driving speed, constant resisting torque, no springs."""
    p = case.params()
    law = centrifugal_law(case, mode, design, ("slip_friction", "lockup"))
    return simulate(Model(law, p.inertia, Load(p.resisting_torque), ("slip_friction", "lockup"), driver_speed=p.speed))


CHECK_MARGIN = 1e-2  # the check's error at most this fraction of the contract (the start-up's tolerance)
ERROR_PER_RTOL = {False: 10.0, True: 1000.0}  # global error / rtol, measured at most 2.2 (slipping: LSODA at a
# tenth of rtol, with the Jacobian) and 730 (elastic: LSODA at rtol, through some 30 torsional swings), rounded up
CHECK_RTOL = (1e-12, 1e-6)  # the rtol range the error was measured over (docs/start_up.md, "The check's tolerance")
MESH_RTOL = 1e-11  # a slipping start's check also gives the samples the next mesh is adapted to: at 1e-9 the ball's
# accuracy loop took 11 solves, not 8 (docs/start_up.md); an elastic link's mesh is not adapted


def accuracy_rtol(tolerance: float, elastic: bool) -> float:
    """The loosest rtol at which the check's own error is at most CHECK_MARGIN of the start-up's relative
    ``tolerance`` (the contract): CHECK_MARGIN x tolerance / ERROR_PER_RTOL, within CHECK_RTOL (1e-9 for a slipping
    coupling at the default 1e-6, 1e-11 for an elastic link)."""
    return min(max(CHECK_MARGIN * tolerance / ERROR_PER_RTOL[elastic], CHECK_RTOL[0]), CHECK_RTOL[1])


def check_rtol(tolerance: float, elastic: bool) -> float:
    """The simulator's rtol for the check of a start-up of relative ``tolerance``: :func:`accuracy_rtol`, and for
    a slipping coupling at most MESH_RTOL (its samples adapt the mesh)."""
    rtol = accuracy_rtol(tolerance, elastic)
    return rtol if elastic else min(rtol, MESH_RTOL)


def start_up_model(case, mode: str, design: dict[str, float], rtol: float | None = None):
    """The start-up a case's [start_up] section describes, for a design (with its spring preload) of the case: a
    :class:`~clutchopt.simulate.engine.Model` of a slipping coupling, or an elastic link's
    :class:`~clutchopt.simulate.elastic.ElasticModel`; :func:`run_start_up` simulates either. ``rtol``: the
    simulator's (default 1e-11, an elastic link's 1e-10; the solve's check takes :func:`check_rtol`)."""
    spec, p = case.start_up, case.params()
    law = _formulation(case.coupling, mode).speed_law
    if isinstance(law, ElasticLaw):
        return _elastic_model(case, law, design, 1e-10 if rtol is None else rtol)
    rtol = 1e-11 if rtol is None else rtol
    preload = design.get("spring_preload", p.spring_preload)
    law = centrifugal_law(case, mode, design, spec.effects, preload)
    profile = spec.load_profile
    load = Load(over=profile.over, points=profile.points, values=profile.values) if profile else Load(p.load_torque)
    motor = (InductionMotor(p.synchronous_speed, p.breakdown_torque, p.breakdown_slip, p.motor_inertia)
             if spec.has("motor_curve") else None)
    heat = spec.has("friction_heat")
    return Model(law, p.driven_inertia, load, spec.effects, math.nan if motor else p.speed, motor,
                 p.heat_capacity if heat else math.nan, p.heat_conductance if heat else 0.0, rtol=rtol)


def _elastic_model(case, law: ElasticLaw, design: dict[str, float], rtol: float):
    from clutchopt.simulate.elastic import ElasticModel

    spec, p = case.start_up, case.params()
    x = SimpleNamespace(**design)
    motor = InductionMotor(p.synchronous_speed, p.breakdown_torque, p.breakdown_slip, p.motor_inertia)
    reduced = p.driven_inertia * p.motor_inertia / (p.driven_inertia + p.motor_inertia)
    stiffness = max(float(law.stiffness(x, p, p.speed)), 0.0)  # k <= 0 at the design speed (the cables' tension
    # below zero: a self-locking weight thread, a retry's start the NLP rules out): no reference stiffness, c = 0
    damping = 2.0 * float(law.damping_ratio(x, p)) * math.sqrt(stiffness * reduced)
    profile = spec.load_profile
    load = Load(over=profile.over, points=profile.points, values=profile.values) if profile else Load(p.load_torque)
    return ElasticModel(law, x, p, damping, p.driven_inertia, load, motor, p.min_lock_up_speed,
                        float(law.largest_twist(x, p)), spec.effects, rtol=rtol)


def until_lock_up(model, end_time: float):
    """A start-up model run only to its first lock-up (no locked run after it) and cut at ``end_time``: all a start
    guess needs, however long the locked run or the case's limits; an elastic link's every extreme sampled (the
    NLP's initial states are read off the samples)."""
    from clutchopt.simulate.elastic import ElasticModel

    guess = replace(model, effects=tuple(e for e in model.effects if e != "lockup"), end_time=end_time)
    return replace(guess, all_extremes=True) if isinstance(guess, ElasticModel) else guess


GUESSES = 16  # start guesses kept (a re-solve of a case starts from the same design: one simulation, not two)
_GUESSES: dict[tuple, tuple] = {}
_KEEPING = threading.Lock()  # solves of several threads (the run is simulated outside it)


def start_guess(case, mode: str, design: dict[str, float], rtol: float, end_time: float) -> tuple:
    """(model, result): the start of ``design`` on the case's drive up to its first lock-up (:func:`until_lock_up`),
    at ``rtol``: a start point for the NLP's states. The same case and design give the same run, so the last GUESSES
    are kept (a re-solve of a case, whose start design is its static optimum, simulates only its optimum's check);
    the result is read, never changed, by its users."""
    try:
        key = (case.coupling, mode, case.start_up, tuple(sorted(case.values.items())),
               tuple(sorted(design.items())), rtol, end_time)
        hash(key)
    except TypeError:  # a value that is no number (none in a checked case): simulated, not kept
        key = None
    kept = _GUESSES.get(key) if key is not None else None
    if kept is not None:
        return kept
    model = start_up_model(case, mode, design, rtol=rtol)
    result = model, run_start_up(until_lock_up(model, end_time))
    if key is not None:
        with _KEEPING:
            while len(_GUESSES) >= GUESSES:
                del _GUESSES[next(iter(_GUESSES))]  # the oldest
            _GUESSES[key] = result
    return result


def run_start_up(model) -> SimulationResult:
    """Simulate a start-up model of either kind."""
    from clutchopt.simulate.elastic import ElasticModel, simulate_elastic

    return simulate_elastic(model) if isinstance(model, ElasticModel) else simulate(model)


def verify(case, solution, afresh: bool = False) -> dict:
    """Simulate the optimised design from rest; achieved acceleration time against the sized t_p (SI). A design of
    a [start_up] case was started on its drive by the solve itself; ``afresh``: started again, at values of the
    case other than those it was solved for (a robust design at a corner of its scatter)."""
    missing = speed_law_missing(case.coupling, solution)
    if missing:
        return {"verified": False, "reason": missing}
    if solution.start_up is not None:  # started on the case's drive
        limit, effects = case.values["max_start_time"], ", ".join(case.start_up.effects)
        if afresh:
            head = run_start_up(start_up_model(case, solution.mode, solution.design)).headline
            start, work = head["start_time"], head["friction_work"]
            verified = bool(head["locks_up"]) and start <= limit * (1 + case.start_up.tolerance)
            reason = head["reason"]
        else:
            summary = solution.start_up
            start, work = summary["start_time_simulated"], summary["friction_work_simulated"]
            verified, reason = solution.status == "optimal", summary["reason"]
        return {"verified": verified, "reason": reason, "simulated_start_time": start, "max_start_time": limit,
                "friction_work": work, "assumption": f"the case's [start_up] drive ({effects})"}
    if "acceleration_time" not in case.values:
        return {"verified": False, "reason": f"the {case.coupling} case is sized without an acceleration time "
                                             "(give it a [start_up] section to design for a start)"}
    p = case.params()
    try:
        result = ideal_start(case, solution.mode, solution.design)
    except InputError as exc:  # a case beyond the simulator's ranges: the solution stands, unverified
        return {"verified": False, "reason": exc.problem}
    achieved = result.headline["start_time"]
    return {
        "verified": bool(result.headline["locks_up"]),
        "reason": result.headline["reason"],
        "sized_acceleration_time": p.acceleration_time,
        "simulated_acceleration_time": achieved,
        "relative_difference": achieved / p.acceleration_time - 1.0 if math.isfinite(achieved) else math.inf,
        "friction_work": result.headline["friction_work"],
        "assumption": "constant driving speed and resisting torque, no springs (the sizing's constant acceleration)",
    }


def verify_text(check: dict) -> str:
    if "max_start_time" in check:
        return (f"verify: started on {check['assumption']}: the start is over after {check['simulated_start_time']:.6g} s "
                f"against max_start_time {check['max_start_time']:.6g} s; friction work {check['friction_work']:.6g} J"
                if math.isfinite(check["simulated_start_time"]) else f"verify: no lock-up - {check['reason']}")
    if "sized_acceleration_time" not in check:
        return f"verify: not simulated - {check['reason']}"
    if not check["verified"]:
        return f"verify: the design does not start up - {check['reason']}"
    return (f"verify: start-up simulated at constant driving speed: acceleration time "
            f"{check['simulated_acceleration_time']:.6g} s against t_p = {check['sized_acceleration_time']:.6g} s "
            f"({check['relative_difference']:+.2e}); friction work {check['friction_work']:.6g} J")


def report_figure(case, solution):
    """(Figure, caption) of a solved design's start-up at constant driving speed, or (None, reason)."""
    missing = speed_law_missing(case.coupling, solution)
    if missing:
        return None, missing
    if "acceleration_time" not in case.values and case.start_up is None:
        return None, f"the {case.coupling} case defines no start-up (no driven inertia, no acceleration time)"
    try:
        return _start_figure(case, solution)
    except InputError as exc:  # a case beyond the simulator's ranges: the page shows why there is no figure
        return None, f"Start-up not simulated: {exc.problem}"


def _start_figure(case, solution):
    from clutchopt.simulate.plot import history_figure

    if case.start_up is not None:
        result = run_start_up(start_up_model(case, solution.mode, solution.design))
        h = result.headline
        caption = (f"Start-up of the optimised {case.coupling} design on the case's drive "
                   f"({', '.join(case.start_up.effects)}): "
                   + ((f"the machine at its start speed after {h['start_time']:.4g} s, the cables' stress at most "
                       f"{h['peak_stress'] / 1e6:.4g} MPa." if "peak_stress" in h else
                       f"lock-up after {h['start_time']:.4g} s, friction work {h['friction_work']:.4g} J.")
                      if h["locks_up"] else f"{h['reason']}."))
        return history_figure(result, case.title, nlp=solution.start_up), caption
    p = case.params()
    result = ideal_start(case, solution.mode, solution.design)
    h = result.headline
    if not h["locks_up"]:
        return history_figure(result, case.title), f"Start-up of the optimised design: {h['reason']}."
    caption = (f"Start-up of the optimised {case.coupling} design from rest at constant driving speed "
               f"{p.speed:.6g} rad/s against {p.resisting_torque:.6g} N*m: the driven machine reaches speed in "
               f"{h['start_time']:.4g} s (sized for t_p = {p.acceleration_time:.4g} s); friction work "
               f"{h['friction_work']:.4g} J, peak slip power {h['peak_slip_power']:.4g} W.")
    return history_figure(result, case.title), caption

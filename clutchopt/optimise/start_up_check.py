"""The NLP's start-up checked by the independent simulator, and the limits of the next solve where the simulated
start misses the case's (docs/start_up.md).
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from clutchopt.optimise.robust_models import corner_name
from clutchopt.optimise.verify import ACTIVE_TOL, check_constraints
from clutchopt.start_up.drive import Drive, graded_part, seen_constraints
from clutchopt.start_up.lining import UNITS as LINING_UNITS
from clutchopt.start_up.lining import lining_figures, lining_notes
from clutchopt.start_up.mesh import Meshes
from clutchopt.start_up.transcription import TRAJECTORY

BACK_OFF_STEPS = 4  # defect corrections of limits the simulated start misses (or binds at off the limit)
CENTRE = 0.25  # of the tolerance: the objective's error from a binding limit met off the limit that is corrected
BACK_OFF_INSIDE = 0.5  # of the tolerance: where a loop that never centres (an elastic link's) corrects a limit the
#                       simulated start misses, it aims this far inside it. A loop that centres aims at the limit: a
#                       landing within what CENTRE accepts needs no further solve, where one half a tolerance inside
#                       was centred by another (wedge_motor_start over max_temperature_rise: 3 solves a point -> 2)
LIMIT_OF = {"start_time": "max_start_time", "friction_work": "max_friction_work",
            "temperature_rise": "max_temperature_rise", "heat_per_hour": "heat_dissipation",
            "lining_temperature": "max_lining_temperature", "continuous_temperature": "max_continuous_temperature",
            "link_stress": "max_link_stress"}
UNITS = {"start_time": "s", "friction_work": "J", "temperature_rise": "K", "engagement_speed": "rad/s",
         "lock_up_speed": "rad/s", "engagement_time": "s", "lock_up_time": "s", "peak_link_stress": "Pa",
         "peak_twist": "rad", **LINING_UNITS}


def start_up_report(block, case, design: dict[str, float], formulation, seen, figures, used: np.ndarray):
    """The NLP's start beside the independent simulator's (stiff where the motor is, events, float64) at the design,
    and the start-up constraints re-checked with the simulated figures, each with the values ``seen(name)`` gives it
    (:func:`~clutchopt.start_up.drive.seen_constraints`): (summary in SI, constraint checks, the meshes: ``used``,
    the NLP's, and the one the simulated start suggests for the next solve, adapted where read: ``Meshes``; the NLP's
    own figures of the limits' checks). ``case`` and ``design``: as the start sees them."""
    values, *columns = figures
    nlp = dict(zip(block.outputs(), np.array(values).ravel()))
    trajectory = {name: np.array(column).ravel() for name, column in zip(TRAJECTORY, columns)}  # (block.trajectory()
    # builds the expressions: 5 ms a check for its names)
    s = block.s
    result, drive, checks = simulated_checks(block, case, design, formulation, seen)
    head = result.headline
    node_stresses = ([float(drive.link_stress(w, theta)) for w, theta in zip(trajectory["w_driver"], trajectory["twist"])]
                     if s.elastic else [])
    engaged = float(nlp.get("run_up_time", 0.0))
    summary = {
        "start_time": float(nlp["start_time"]),
        "start_time_simulated": head["start_time"],
        "friction_work": float(nlp["friction_work"]),
        "friction_work_simulated": head["friction_work"],
        "temperature_rise": float(trajectory["temperature_rise"].max()) if s.heat else None,
        "temperature_rise_simulated": head.get("temperature_rise"),
        "engagement_speed": float(nlp["engagement_speed"]),
        "engagement_time": engaged,
        "lock_up_time": float(nlp["start_time"]) - engaged,
        "lock_up_speed": float(nlp["lock_up_speed"]),
        "lock_up_speed_simulated": head["lock_up_speed"],
        "intervals": s.intervals,
        "phases": list(s.phases),
        "effects": list(s.spec.effects),
        "tolerance": s.spec.tolerance,
        "motor": case.start_up.motor_note,  # the case's, not the structure's (shared by every case of its shape)
        "locks_up": head["locks_up"],
        "reason": head["reason"],
        "discretisation_error": {name: _relative(float(nlp[name]), head[name])
                                 for name in ("start_time", "friction_work", "lock_up_speed")},
        "units": UNITS,
        "trajectory": {name: column.tolist() for name, column in trajectory.items()},
    }
    if not s.spec.overload:
        summary["overload"] = "overload not checked (start_up.overload.check = false): overload_torque left out"
    if getattr(formulation.speed_law, "worn_torque", None) is not None:  # the start with worn linings (the lever):
        summary["worn"] = None  # simulated for the design a solve returns only (:func:`worn_start`), in its place
    if s.elastic:  # the link's stress and twist: the NLP's quasi-static link beside the simulated dynamic one
        summary.update(peak_link_stress=max(node_stresses),
                       peak_link_stress_simulated=head["peak_stress"], peak_twist=float(trajectory["twist"].max()),
                       peak_twist_simulated=head["peak_twist"])
    if not s.elastic:  # the lining's temperature and wear at the NLP's start and at the simulated one
        summary.update(lining_figures(drive, summary["friction_work"], summary["temperature_rise"]))
        simulated_rise = head.get("temperature_rise") if s.heat else None
        summary.update({f"{name}_simulated": value for name, value in
                        lining_figures(drive, head["friction_work"], simulated_rise).items()})
        summary["ambient_temperature"] = float(drive.p.ambient_temperature) if s.heat else None
        summary["lining_notes"] = lining_notes(drive, case.coupling)
    times = [float(nlp[f"{phase}_time"]) for phase in s.phases]
    collocated = SimpleNamespace(start_time=summary["start_time"], friction_work=summary["friction_work"],
                                 temperatures=summary["temperature_rise"] or 0.0,
                                 lock_up_speed=summary["lock_up_speed"], stresses=np.array(node_stresses))
    own = {check.name: check.value for check in check_constraints(  # (the limits' rows alone checked)
        [c for c in seen_constraints(s, formulation.speed_law, collocated, seen, drive) if c.name in LIMIT_OF])}
    return summary, checks, Meshes(used, s, result.columns, times, graded_part(s.spec, case.values)), own


def simulated_checks(block, case, design: dict[str, float], formulation, seen):
    """The independent simulator's start at ``design`` (stiff where the motor is, events, float64) and the start-up
    constraints checked with its figures, each with the values ``seen(name)`` gives it: (the simulation's result, the
    drive at ``seen(None)``, the checks). ``case`` and ``design``: as the start sees them. What
    :func:`start_up_report` checks a solve with, and what the modifier's gradient differences
    (:mod:`clutchopt.optimise.modifier`)."""
    from clutchopt.start_up.simulation import check_rtol, run_start_up, start_up_model

    s = block.s
    result = run_start_up(start_up_model(case, formulation.mode, design, check_rtol(s.spec.tolerance, s.elastic)))
    head = result.headline
    stresses = result.columns["stress"] if s.elastic else 0.0
    simulated = SimpleNamespace(start_time=head["start_time"], friction_work=head["friction_work"],
                                temperatures=head.get("temperature_rise", 0.0), lock_up_speed=head["lock_up_speed"],
                                stresses=stresses if head["locks_up"] else math.inf)
    drive = Drive(s, formulation.speed_law, *seen(None))
    return result, drive, check_constraints(seen_constraints(s, formulation.speed_law, simulated, seen, drive),
                                            s.spec.tolerance)


def worn_start(summary: dict, case, design: dict[str, float], mode: str) -> None:
    """A solve's start-up ``summary`` completed with the same start on worn linings (the lever), simulated: reported,
    never checked (the new linings' start is), so it is run for the design a solve returns, not for each solve of
    its accuracy loop. ``case`` and ``design``: as the start sees them; a summary without the place (another
    coupling) or with it filled is left as it is."""
    from clutchopt.start_up.simulation import check_rtol, run_start_up, start_up_model, worn_start_up_model

    if "worn" not in summary or summary["worn"] is not None:
        return
    model = start_up_model(case, mode, design, check_rtol(summary["tolerance"], False))
    summary["worn"] = {**_headline(run_start_up(worn_start_up_model(case, mode, design, model)).headline),
                       "min_lock_up_speed": case.values.get("min_lock_up_speed"),
                       "units": {**{name: UNITS[name] for name in ("start_time", "friction_work",
                                                                    "temperature_rise", "lock_up_speed")},
                                 "min_lock_up_speed": "rad/s"}}


def _headline(head: dict) -> dict:
    """The figures of a simulated start (SI, as ``UNITS``)."""
    return {"start_time": head["start_time"], "friction_work": head["friction_work"],
            "temperature_rise": head.get("temperature_rise"), "lock_up_speed": head["lock_up_speed"],
            "locks_up": head["locks_up"]}


def _relative(nlp: float, simulated: float) -> float:
    """(NLP - simulated) / |simulated|: the collocation's error against the simulator (its own error ~1e-10)."""
    if not math.isfinite(simulated) or simulated == 0:
        return math.nan
    return (nlp - simulated) / abs(simulated)


def limit_gaps(solution):
    """Each simulated check of a start-up limit (``LIMIT_OF``: an upper limit, its figure a number): (the check, the
    limit's case quantity, the simulated figure less the limit the check holds it to)."""
    for check in solution.constraints:
        name = LIMIT_OF.get(check.name)
        if name is not None and check.sense == "<=" and math.isfinite(check.value):
            yield check, name, check.value - check.limit


def objective_error(check, gap: float) -> float:
    """The objective's relative error from a simulated start-up figure ``gap`` off the limit ``check`` holds it to
    (:func:`limit_gaps`): |elasticity x gap / limit| (the check's elasticity, d ln objective / d ln limit, at the
    NLP's optimum; none: 0). What the defect correction compares with CENTRE of the tolerance
    (:func:`corrected_case`)."""
    return abs((check.elasticity or 0.0) * gap / check.limit)


def corrected_case(solution, nlp_case, centre: bool = True):
    """The case of the next solve (defect correction): each limit L_k the NLP last saw (a scattered limit: its
    corner's, an NLP parameter) moved to L - (S - C), the case's limit L less what the simulated figure S adds to
    the NLP's own C (``Solution.collocated``) at this design: where the simulated start misses the limit (where the
    loop does not centre, half the tolerance more: BACK_OFF_INSIDE), and (``centre``) where it meets a limit the
    design binds at so far from it that the objective is off by more than CENTRE of the tolerance
    (:func:`objective_error`): the design is then the simulator's optimum, not the collocation's, whatever mesh the
    accuracy loop ended on. Where the NLP binds the limit (C = L_k within ACTIVE_TOL of its scale) this is
    L_k - (S - L); where it does not, the NLP's own slack L_k - C is taken in at once, not a step of S - L a solve
    (docs/start_up.md, "The defect correction's fixed point"). None where nothing is to be moved, or a limit cannot
    be."""
    summary, tolerance = solution.start_up, solution.start_up["tolerance"]
    collocated = getattr(solution, "collocated", None) or {}
    limits, corners = {}, {}
    for check, name, gap in limit_gaps(solution):
        if not check.feasible:
            if not centre:  # (a loop that centres aims at the limit itself: BACK_OFF_INSIDE)
                gap += BACK_OFF_INSIDE * tolerance * abs(check.limit)
        elif not (centre and objective_error(check, gap) > CENTRE * tolerance):
            continue
        corner = corner_name(name, check.name)
        key, moved = (corner, corners) if corner in nlp_case.values else (name, limits)
        moved[key] = nlp_case.values[key] - gap - nlp_slack(collocated.get(check.name), nlp_case.values[key], check)
        if not moved[key] > 0 or not summary["locks_up"]:
            return None
    if not limits and not corners:
        return None
    moved = nlp_case.with_values(**limits)
    return replace(moved, values={**moved.values, **corners})


def nlp_slack(figure: float | None, limit: float, check) -> float:
    """How far the NLP's own ``figure`` of ``check`` stays inside the ``limit`` it saw (an upper limit): 0 where it
    binds it (within ACTIVE_TOL of the check's scale, IPOPT's own margin at an active row), or is not known."""
    if figure is None or not math.isfinite(figure):
        return 0.0
    slack = limit - figure
    return slack if slack > ACTIVE_TOL * abs(check.scale) else 0.0

"""The review page's sections as blocks (clutchopt.report.page): requirements, the design with its sketch,
constraint margins, sensitivities, the comparison with the paper's method, the start-up simulation, the scatter and
a sweep. Tables use the same columns as ``clutchopt solve`` (clutchopt.output). A chart that would be empty is
replaced by a sentence saying why."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd

from clutchopt.cases import Case, quantity_table
from clutchopt.formulations import get_coupling
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.records import DESIGN_STATUSES
from clutchopt.output import (
    _shown,
    column_notes,
    comparison_rows,
    constraint_rows,
    derived_rows,
    design_rows,
    scatter_rows,
    sensitivity_rows,
    start_up_table,
)
from clutchopt.report.page import Bar, Figure, Heading, Items, Note, Table, safe_svg
from clutchopt.report.sketch import sketch
from clutchopt.report.verification import robust_label
from clutchopt.simulate.plot import literal

MAX_LINES = 6  # lines of a sweep plot, one per value of the second varied input (evenly picked)
NO_EFFECT = 1e-9  # a relative margin change below this is no bar of the tornado chart


def figure_svg(figure) -> str:
    """A matplotlib figure as inline SVG markup."""
    buffer = io.StringIO()
    figure.savefig(buffer, format="svg")
    text = buffer.getvalue()
    return text[text.index("<svg"):]


def requirements(case: Case) -> list:
    """The case's inputs; those the material library filled name their entry; the [scatter] the page's designs are
    checked (and a robust one designed) for (review 29: a page had not said which)."""
    names = {q.key: q.name for q in case.quantities}
    rows = [{"key": r["key"], "symbol": r["symbol"], "value": r["value"],
             "from the library": " = ".join(case.filled.get(names[r["key"]], ())), "description": r["description"]}
            for r in quantity_table(case.quantities, case.values)]
    scattered = [Heading("Scatter"), Table(scatter_rows(case), ())] if case.scatter else []
    return [Table(rows, ("value",)), *scattered]


def designed(solution: Solution) -> bool:
    """Whether the page has a design to review (optimal, or unverified: flagged), not the last point of a solve that
    found none (review 29: an infeasible page had been titled "Optimal design", its sketch "of the optimum" and its
    start "passed")."""
    return solution.status in DESIGN_STATUSES


def design_title(solution: Solution, robust=None) -> str:
    if not designed(solution):
        return "No design: the solver's last point"
    return ("Robust design" if robust is not None else "Optimal design") + (
        " (unverified)" if solution.status == "unverified" else "")


def design(solution: Solution, formulation) -> list:
    tables = [Table(design_rows(solution, formulation), ("value",)), Heading("Derived"),
              Table(derived_rows(solution), ("value",))]
    if designed(solution):
        return tables
    return [Note(f"The solve found no design (status {solution.status}: {solution.diagnosis or 'see the verification'}"
                 "). These are the values of its last point, which breaks the requirements the margins below show; "
                 "nothing on this page is a design to build.")] + tables


def drawing(case: Case, solution: Solution, formulation) -> list:
    if not designed(solution):
        return [Note(f"No sketch: the solve found no design (status {solution.status}).")]
    optimised = {v.name for v in formulation.variables if solution.at_bound(v.name) != "fixed"}
    effects = tuple(case.start_up.effects) if case.start_up is not None else ()
    svg = sketch(case.coupling, {**case.values, **solution.design},
                 {name: out.value for name, out in solution.outputs.items()}, optimised, effects)
    if svg is not None:
        chosen = [v.symbol or v.name for v in formulation.variables if v.name in optimised]
        return [Figure(safe_svg(svg), f"Dimensioned sketch of the optimum, to scale. Optimised (red): "
                                      f"{', '.join(chosen)}; every other dimension as the case gives it or as it "
                                      "follows from these.")]
    rows = [{"dimension": v.name, "symbol": v.symbol, "value": _shown(solution.design[v.name], v.unit),
             "unit": v.unit} for v in formulation.variables]
    return [Note(f"No sketch can be drawn for this {case.coupling} design (a dimension it needs is not given); its "
                 "dimensions are tabulated instead."), Table(rows, ("value",))]


def margins(case: Case, solution: Solution, robust=None) -> list:
    """The constraints re-evaluated in float64; a robust design's each where it was designed, its corner of the
    scatter or performance point named in a column ``at`` (review 29: a torque of 94.85 N*m against the same had
    been shown without its corner, beside the design's 118.56 N*m at the nominal values)."""
    rows, optimum = [], solution.status == "optimal"  # (elasticities are an optimum's: none at a last point)
    corners = robust.corners if robust is not None else {}
    declared = {q.name: q for q in case.quantities}
    for c, row in zip(solution.constraints, constraint_rows(solution)):
        moves = robust.bars.get(c.name, {}) if robust is not None else {}  # (a quantity that moves it not: left out,
        at = {"at": ", ".join(f"{q} {declared[q].show(v, 4)}" for q, v in corners.get(c.name, {}).items()  # as solve
                              if abs(moves.get(q, 1.0)) > 1e-12) or "nominal"} if robust is not None else {}  # does)
        rows.append({**{k: v for k, v in row.items() if k not in ("active", "elasticity")}, **at,
                     "margin bar": Bar(max(0.0, min(c.margin, 1.0)), c.active),
                     "active": row["active"], "elasticity": row["elasticity"] if optimum else "-"})
    where = (f"; each constraint where the {robust_label(robust)} design holds it (at: its corner of the scatter or "
             "performance point, or the nominal values where the scatter moves it not), the derived figures above at "
             "the nominal values") if robust is not None else ""
    return [Note("Re-evaluated in float64; margin relative to the limit; elasticity = d ln objective / d ln limit"
                 + ("" if optimum else f" (none: the point is no optimum, status {solution.status})") + where + "."),
            Table(rows, ("value", "limit", "margin", "elasticity"))]


def sensitivities(solution: Solution, formulation) -> list:
    rows = sensitivity_rows(solution, formulation, count=12)
    if not rows:
        return [Note("No sensitivities: they are the multipliers of a verified optimum, and this solve's status is "
                     f"{solution.status}." if solution.status != "optimal" else
                     "No sensitivities: no parameter moves the optimum's objective by an elasticity of 5e-5 or more.")]
    return [Note("Elasticity of the optimum, d ln objective / d ln parameter, from the multipliers (+1: the objective "
                 "grows in proportion)."), Table(rows, ("elasticity",))]


def comparison(case: Case, solution: Solution, options: SolverOptions, robust=None, scattered: list | None = None
               ) -> list:
    """The paper's method beside the optimiser's designs, solved with the page's ``options``; a start-up case's
    columns in the mode and objective of the page's ``solution``; a scatter case's the designs of its Scatter section
    (``scattered``: the page's robust design's RobustResult, ``robust``, else those of worst case and chance 0.999),
    not solved again."""
    from clutchopt.optimise.compare import compare_case
    from clutchopt.optimise.design import Robustness

    if get_coupling(case.coupling).comparison is None:
        return [Note("This coupling has no comparison with a paper method.")]
    method = None if robust is None else Robustness(robust.method, robust.target, robust.samples,
                                                    robust.start_up_samples or Robustness.starts)
    data = compare_case(case, options, method, scattered, solution.mode, solution.objective_name).as_dict()
    rows, _ = comparison_rows(data)
    notes = column_notes(data)
    for column, solve in data["solves"].items():  # (a column without a design says why: review 29, only "-")
        if solve["status"] not in DESIGN_STATUSES and column in notes:
            notes[column] += f"; no design, status {solve['status']}: {solve['diagnosis'] or '-'}"
    return [Table(rows, tuple(data["columns"])), Items(list(notes.items()))]


def simulation(case: Case, solution: Solution, robust=None) -> list:
    """The start-up simulation of the optimum: the one call site of the simulator's figure. A robust design's start is
    the one its table shows, at the scatter's point where it was designed (``robust.corners["start_up"]``; review 29:
    the figure had started the design at the nominal values, 6.84 s, beneath the table's corner, 10 s)."""
    from clutchopt.simulate import report_figure

    point = (robust.corners.get("start_up") or {}) if robust is not None and solution.start_up is not None else {}
    figure, caption = report_figure(case.with_values(**point) if point else case, solution)
    if figure is None:
        return [Note(caption)]
    declared = {q.name: q for q in case.quantities}
    at = (f" at the scatter's {', '.join(f'{name} {declared[name].show(value)}' for name, value in point.items())}, "
          "where the robust design's start-up limits bind (the nominal values start it otherwise)") if point else ""
    blocks = []
    if solution.start_up is not None:
        start = solution.start_up
        _, rows, _ = start_up_table(start)
        blocks = [Note(f"The start{at}, designed inside the NLP (Radau collocation, {start['intervals']} intervals per "
                       f"phase: {', '.join(start['phases'])}; points in the figure) beside the independent simulator "
                       "(lines)."), Table(rows, ("NLP", "simulated"))]
    return blocks + [Figure(safe_svg(figure_svg(figure)), caption + (f" (Simulated{at}.)" if at else ""))]


def scattered_designs(case: Case, solution: Solution, options: SolverOptions, robust=None) -> list:
    """The designs a review page shows under the case's scatter, made once for its Scatter and Comparison sections:
    ``[robust]`` (the page's robust design's :class:`~clutchopt.optimise.robust.RobustResult`), else the worst-case
    and chance 0.999 designs of the page's design's mode and objective, solved with its ``options`` (so that their
    nominal design is the page's)."""
    from clutchopt.optimise.compare import CHANCE_SHOWN
    from clutchopt.optimise.robust import CHANCE, WORST_CASE, solve_robust

    if robust is not None:
        return [robust]
    return [solve_robust(case, method, target, solution.mode, solution.objective_name, options)
            for method, target in ((WORST_CASE, None), (CHANCE, CHANCE_SHOWN))]


def scatter(case: Case, results: list, robust=None) -> tuple[list, tuple[str, float, int]]:
    """The designs under the case's scatter side by side (``results``, :func:`scattered_designs`: the nominal one, and
    the robust one of ``robust``, a :class:`~clutchopt.optimise.robust.RobustResult`; without it, the worst-case and
    chance 0.999 designs), each with its largest failure probability by Monte Carlo, and a tornado chart: how far each
    scattered quantity moves each constraint's margin over its range at the nominal design. Also the nominal design's
    likeliest failure: (constraint, probability, samples)."""
    from clutchopt.optimise.robust_models import failure_probabilities, tornado

    if robust is not None:  # (each row with the result it is of: a robust start-up's system has its limits)
        designs = [("nominal", robust.nominal, robust.nominal_failure, robust.nominal_reliability, robust),
                   (robust_label(robust), robust.solution, robust.failure, robust.reliability, robust)]
    else:
        worst, chance = results
        designs = [("nominal", worst.nominal, worst.nominal_failure, worst.nominal_reliability, worst),
                   ("worst case", worst.solution, worst.failure, worst.reliability, worst),
                   ("chance 0.999", chance.solution, failure_probabilities(worst.formulation, chance.solution.design,
                                                                           case.params(), case.scatter,
                                                                           correlation=case.correlation),
                    chance.reliability, chance)]
    first = results[0]
    rows = []
    for label, result_solution, failure, reliability, owner in designs:
        if not designed(result_solution):  # (no design: its last point's figures are none of a design's)
            rows.append({"design": label, "status": result_solution.status, result_solution.objective_name: "-",
                         "change": "-", "largest P(fail)": "-"})
            continue
        rows.append({"design": label, "status": result_solution.status,
                     result_solution.objective_name: f"{result_solution.objective:.6g} {result_solution.objective_unit}",
                     "change": f"{result_solution.objective / first.nominal.objective - 1:+.1%}",
                     "largest P(fail)": largest_failure(failure, first.samples),
                     **reliability_columns(case, reliability, *_with_start_up(owner, reliability))})
    name, (p, _, _) = max(first.nominal_failure.items(), key=lambda item: item[1][0])
    allocation = allocation_blocks(robust.allocation, robust) if robust is not None and robust.allocation else []
    chart = (tornado_chart(case, first, tornado(first.formulation, first.nominal.design, case.params(), case.scatter))
             if designed(first.nominal) else  # (review 31: a last point's, as a design's)
             Note("No tornado chart: the nominal solve found no design."))
    return [Table(rows, ("change", "largest P(fail)", "system P(fail)")), *allocation, chart], (name, p, first.samples)


def allocation_blocks(allocation, robust=None) -> list:
    """How a system chance design split 1 - P between its constraints: the claim, then each constraint's beta, its
    share of the first-order series bound and its own failure probability (importance sampling); the share each
    start-up limit the scatter moves took first (``robust.start_up_share``; review 29: left out)."""
    data = allocation.as_dict()
    rows = [{"constraint": name, "beta": f"{c['beta']:.4g}", "index shift": f"{c['index_shift']:+.3g}",
             "share of 1 - P": f"{c['share']:.3g}",
             "P(fail)": "-" if not c["failure_probability"] else
             "{probability:.3g} ({low:.3g} to {high:.3g}, {estimator})".format(**c["failure_probability"])}
            for name, c in data["constraints"].items()]
    share = robust.start_up_share if robust is not None else None
    first = (f". Each start-up limit the scatter moves took {share:.3g} of 1 - P first (a union bound); the "
             "constraints share the rest") if share else ""
    return [Note(f"Risk allocation (system chance): {data['claim']}{first}."),
            Table(rows, ("beta", "index shift", "share of 1 - P"))]


def largest_failure(failure: dict[str, list[float]], samples: int) -> str:
    """The largest Monte Carlo failure probability of any constraint with its 95 % Clopper-Pearson interval, the
    estimator, its sample count and the constraint: ``0.005 (0.00013 to 0.028, Monte Carlo, 200 samples; torque)``
    (bare, 1 failure in 200 read as five times the 0.001 a chance-0.999 design allows)."""
    from clutchopt.optimise.robust_models import largest_failure

    name, p, low, high = largest_failure(failure)
    return f"{p:.3g} ({low:.2g} to {high:.2g}, Monte Carlo, {samples} samples; {name})"


def _with_start_up(robust, reliability) -> tuple:
    """(system, apart) for the scatter table's row of ``reliability`` (of the result ``robust``): a robust design with
    a start-up has its system with the start-up limits (``RobustResult.design_failure``, a union bound); the nominal
    design beside it the constraints' alone, the start-up limits ``apart`` (not sampled for it; review 29: a page
    without --robust had shown the worst-case and chance designs' systems without their limits, and the nominal's
    without saying so)."""
    if robust is None or not robust.start_up_failure or reliability is None:
        return None, False
    return (robust.design_failure(), False) if reliability is robust.reliability else (None, True)


def reliability_columns(case: Case, reliability, system=None, apart: bool = False) -> dict[str, str]:
    """A design's system failure probability (importance sampling, 95 % interval; ``system`` where given, a robust
    start-up's with its limits; ``apart``: said to leave the start-up limits out) and the design point of the
    constraint likeliest to fail: its beta and the scattered quantities' values there."""
    if reliability is None:
        return {"system P(fail)": "-", "likeliest failure (design point)": "-"}
    quantities = {q.name: q for q in case.quantities}
    system = system or reliability.system
    name, likeliest = max(reliability.constraints.items(), key=lambda item: item[1].best.probability)
    where = (f"{name}: beta {likeliest.point.beta:.3g} at " + ", ".join(
        f"{q} {quantities[q].show(v, 4)}" for q, v in likeliest.values.items()) if likeliest.point.found
        else f"{name}: {likeliest.best.estimator}")
    return {"system P(fail)": f"{system.probability:.3g} ({system.low:.3g} to {system.high:.3g}, {system.estimator}"
                              + ("; the start-up limits apart)" if apart else ")"),
            "likeliest failure (design point)": where}


def tornado_chart(case: Case, result, bars: dict[str, dict[str, float]]):
    """The tornado chart of ``bars`` (constraint -> quantity -> relative margin change), or why there is none."""
    from matplotlib.figure import Figure as Chart

    shown = {name: effects for name, effects in bars.items() if any(abs(v) > NO_EFFECT for v in effects.values())}
    quantities = ", ".join(s.name for s in case.scatter)
    if not shown:
        simulated = (f"; the start-up, which is simulated rather than evaluated, is checked at "
                     f"{len(result.start_up_points)} corner(s) and by {result.start_up_samples} simulated starts"
                     if result.start_up_points else "")
        return Note(f"No tornado chart: over its range, {quantities} moves none of the {len(bars)} constraints' "
                    f"margins ({', '.join(bars)}) at the nominal design{simulated}.")
    figure = Chart(figsize=(6.5, 0.5 + 0.45 * max(1, len(shown) * len(case.scatter))), layout="constrained")
    axes = figure.add_subplot()
    labels, values = [], []
    for name, effects in shown.items():
        for quantity, change in effects.items():
            labels.append(f"{name}: {quantity}")
            values.append(change)
    axes.barh(range(len(values)), values, color=["#b03a2e" if v < 0 else "#2e86c1" for v in values])
    axes.set_yticks(range(len(values)), labels, fontsize=8)
    axes.axvline(0.0, color="black", lw=0.8)
    axes.set_xlabel("relative margin change, low to high end of the range")
    axes.invert_yaxis()
    axes.grid(axis="x", alpha=0.3)
    return Figure(safe_svg(figure_svg(figure)),
                  "Nominal design: how each scattered quantity moves each constraint's margin over its range (red: "
                  "the margin shrinks as the quantity rises), one quantity at a time from the low to the high end of "
                  "its range, the others nominal.")  # (review 29: it had been captioned Monte Carlo)


def sweep_plot(frame: pd.DataFrame) -> Figure:
    """The objective against the first varied input, one line per value of the second."""
    from matplotlib.figure import Figure as Chart

    status = list(frame.columns).index("status")
    inputs = list(frame.columns[1:status])
    objective = frame.columns[status + 1]
    figure = Chart(figsize=(6.5, 4), layout="constrained")
    axes = figure.add_subplot()
    optimal = frame[frame["status"] == "optimal"]
    groups = [(None, optimal)]
    if len(inputs) > 1:
        levels = sorted(optimal[inputs[1]].unique())
        shown = [levels[round(i)] for i in np.linspace(0, len(levels) - 1, min(len(levels), MAX_LINES))]
        groups = [(value, optimal[optimal[inputs[1]] == value]) for value in shown]
    for value, group in groups:
        axes.plot(group[inputs[0]], group[objective], ".-",
                  label=None if value is None else f"{literal(inputs[1])} = {value:.4g}")
    failed = frame[frame["status"] != "optimal"]
    if len(failed):
        axes.plot(failed[inputs[0]], [optimal[objective].min()] * len(failed) if len(optimal) else [0] * len(failed),
                  "x", color="#b03a2e", label="not optimal")
    if len(inputs) > 1 or len(failed):
        axes.legend(fontsize=7, ncol=2)
    axes.set_xlabel(literal(inputs[0]))
    axes.set_ylabel(literal(objective))
    axes.grid(alpha=0.3)
    caption = (f"Sweep: {len(frame)} points, {len(optimal)} optimal"
               + (f", {len(failed)} not (crosses at the bottom)" if len(failed) else ""))
    return Figure(safe_svg(figure_svg(figure)), caption)

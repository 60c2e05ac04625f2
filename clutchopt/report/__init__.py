"""Design-review report: one self-contained HTML page (inline CSS, inline SVG figures, no scripts, no links out).

Sections: requirements, the optimal design with a dimensioned sketch, constraint margins, sensitivities,
the comparison with the paper's method, the start-up simulation, and a sweep plot when a sweep table is given.
Tables use the same columns as ``clutchopt solve`` (clutchopt.output).
"""

from __future__ import annotations

import io
from datetime import datetime, timezone
from html import escape

import numpy as np
import pandas as pd

from clutchopt.cases import Case, quantity_table
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import case_formulation
from clutchopt.optimise.solution import Solution
from clutchopt.output import (
    _shown,
    column_notes,
    comparison_rows,
    constraint_rows,
    derived_rows,
    design_rows,
    html_table,
    sensitivity_rows,
    start_up_table,
)
from clutchopt.report.sketch import sketch
from clutchopt.simulate.plot import literal
from clutchopt.store import versions

MAX_LINES = 6  # lines of a sweep plot, one per value of the second varied input (evenly picked)
_CSS = """
body{font:14px/1.45 system-ui,sans-serif;color:#1d2733;max-width:1100px;margin:24px auto;padding:0 16px}
h1{font-size:22px;margin-bottom:4px}h2{font-size:17px;border-bottom:1px solid #c8d0d8;margin-top:28px}
table{border-collapse:collapse;margin:8px 0}td,th{padding:3px 9px;border-bottom:1px solid #e3e7eb;text-align:left}
td.n{text-align:right;font-variant-numeric:tabular-nums}th{background:#f2f4f6}
.status{display:inline-block;padding:2px 8px;border-radius:4px;color:#fff;background:#2e7d32}
.status.bad{background:#b03a2e}.note{color:#55606b}.bar{background:#7fa7d1;height:10px;display:inline-block}
.bar.active{background:#b03a2e}figure{margin:8px 0}figcaption{color:#55606b;font-size:13px}
"""


def _table(rows: list[dict], numeric: tuple[str, ...] = ()) -> str:
    return html_table(rows, numeric, markup=("margin bar",))


def figure_svg(figure) -> str:
    """A matplotlib figure as inline SVG markup."""
    buffer = io.StringIO()
    figure.savefig(buffer, format="svg")
    text = buffer.getvalue()
    return text[text.index("<svg"):]


def _section(title: str, body: str, anchor: str) -> str:
    return f'<section id="{anchor}"><h2>{escape(title)}</h2>{body}</section>'


def requirements(case: Case) -> str:
    """The case's inputs; those the material library filled name their entry."""
    names = {q.key: q.name for q in case.quantities}
    rows = [{"key": r["key"], "symbol": r["symbol"], "value": r["value"],
             "from the library": " = ".join(case.filled.get(names[r["key"]], ())), "description": r["description"]}
            for r in quantity_table(case.quantities, case.values)]
    return _table(rows, ("value",))


def design(solution: Solution, formulation) -> str:
    return (_table(design_rows(solution, formulation), ("value",)) + "<h3>Derived</h3>"
            + _table(derived_rows(solution), ("value",)))


def drawing(case: Case, solution: Solution, formulation) -> str:
    optimised = {v.name for v in formulation.variables if solution.at_bound(v.name) != "fixed"}
    svg = sketch(case.coupling, {**case.values, **solution.design},
                 {name: out.value for name, out in solution.outputs.items()}, optimised)
    if svg is not None:
        chosen = [v.symbol or v.name for v in formulation.variables if v.name in optimised]
        return (f"<figure>{svg}<figcaption>Dimensioned sketch of the optimum, to scale. Optimised "
                f"(red): {escape(', '.join(chosen))}; every other dimension as the case gives it or as it follows "
                "from these.</figcaption></figure>")
    rows = [{"dimension": v.name, "symbol": v.symbol, "value": _shown(solution.design[v.name], v.unit),
             "unit": v.unit} for v in formulation.variables]
    return (f'<p class="note">No sketch can be drawn for this {escape(case.coupling)} design (a dimension it needs '
            "is not given); its dimensions are tabulated instead.</p>" + _table(rows, ("value",)))


def margins(solution: Solution) -> str:
    rows = []
    for c, row in zip(solution.constraints, constraint_rows(solution)):
        width = max(0.0, min(c.margin, 1.0)) * 200
        bar = f'<span class="bar{" active" if c.active else ""}" style="width:{width:.0f}px"></span>'
        rows.append({**{k: v for k, v in row.items() if k not in ("active", "elasticity")}, "margin bar": bar,
                     "active": row["active"], "elasticity": row["elasticity"]})
    return ('<p class="note">Re-evaluated in float64; margin relative to the limit; elasticity = '
            "d ln objective / d ln limit.</p>" + _table(rows, ("value", "limit", "margin", "elasticity")))


def sensitivities(solution: Solution, formulation) -> str:
    rows = sensitivity_rows(solution, formulation, count=12)
    return ('<p class="note">Elasticity of the optimum, d ln objective / d ln parameter, from the multipliers '
            "(+1: the objective grows in proportion).</p>" + _table(rows, ("elasticity",)))


def comparison(case: Case, robust=None) -> str:
    """The paper's method beside the optimiser's designs; a scatter case's robust column by the method the page's
    design was made with (``robust``: its RobustResult), else worst case and chance 0.999."""
    from clutchopt.optimise.compare import compare_case
    from clutchopt.optimise.design import Robustness

    if get_coupling(case.coupling).comparison is None:
        return '<p class="note">This coupling has no comparison with a paper method.</p>'
    method = None if robust is None else Robustness(robust.method, robust.target, robust.samples,
                                                    robust.start_up_samples or Robustness.starts)
    data = compare_case(case, robust=method).as_dict()
    rows, _ = comparison_rows(data)
    notes = "".join(f"<li><b>{escape(name)}</b>: {escape(note)}</li>" for name, note in column_notes(data).items())
    return _table(rows, tuple(data["columns"])) + f'<ul class="note">{notes}</ul>'


def simulation(case: Case, solution: Solution) -> str:
    """The start-up simulation of the optimum: the one call site of the simulator."""
    try:
        from clutchopt.simulate import report_figure
    except ImportError:
        return '<p class="note">Start-up simulation: not available in this build (no clutchopt.simulate).</p>'
    figure, caption = report_figure(case, solution)
    if figure is None:
        return f'<p class="note">{escape(caption)}</p>'
    table = ""
    if solution.start_up is not None:
        start = solution.start_up
        _, rows, _ = start_up_table(start)
        table = (f'<p class="note">The start designed inside the NLP (Radau collocation, {start["intervals"]} intervals '
                 f'per phase: {", ".join(start["phases"])}; points in the figure) beside the independent simulator '
                 "(lines).</p>" + _table(rows, ("NLP", "simulated")))
    return f"{table}<figure>{figure_svg(figure)}<figcaption>{escape(caption)}</figcaption></figure>"


def scatter(case: Case, robust=None) -> tuple[str, str]:
    """The designs under the case's scatter side by side (the nominal one, and the robust one of ``robust``, a
    :class:`~clutchopt.optimise.robust.RobustResult`; without it, the worst-case and chance 0.999 designs), each with
    its largest failure probability by Monte Carlo, and a tornado chart: how far each scattered quantity moves each
    constraint's margin over its range at the nominal design. Also the nominal design's worst failure, in words."""
    from matplotlib.figure import Figure

    from clutchopt.optimise.robust import CHANCE, WORST_CASE, solve_robust
    from clutchopt.optimise.robust_models import failure_probabilities, tornado

    if robust is not None:
        results = [robust]
        designs = [("nominal", robust.nominal, robust.nominal_failure),
                   (robust.method + (f" {robust.target:g}" if robust.target else ""), robust.solution, robust.failure)]
    else:
        results = [solve_robust(case, WORST_CASE), solve_robust(case, CHANCE, 0.999)]
        worst, chance = results
        designs = [("nominal", worst.nominal, worst.nominal_failure), ("worst case", worst.solution, worst.failure),
                   ("chance 0.999", chance.solution, failure_probabilities(worst.formulation, chance.solution.design,
                                                                           case.params(), case.scatter))]
    first, params = results[0], case.params()
    rows = []
    for label, result_solution, failure in designs:
        rows.append({"design": label, "status": result_solution.status,
                     result_solution.objective_name: f"{result_solution.objective:.6g} {result_solution.objective_unit}",
                     "change": f"{result_solution.objective / first.nominal.objective - 1:+.1%}",
                     "largest P(fail)": f"{max(p for p, _, _ in failure.values()):.3g}"})
    name, (p, _, _) = max(first.nominal_failure.items(), key=lambda item: item[1][0])
    worst_failure = f"{name} fails with probability {p:.3g} under the scatter"
    bars = tornado(first.formulation, first.nominal.design, params, case.scatter)
    shown = {name: effects for name, effects in bars.items() if any(abs(v) > 1e-9 for v in effects.values())}
    figure = Figure(figsize=(6.5, 0.5 + 0.45 * max(1, len(shown) * len(case.scatter))), layout="constrained")
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
    caption = (f"Nominal design: how each scattered quantity moves each constraint's margin over its range "
               f"(red: the margin shrinks as the quantity rises). Monte Carlo with {first.samples} samples.")
    return (_table(rows, ("change", "largest P(fail)")) +
            f"<figure>{figure_svg(figure)}<figcaption>{escape(caption)}</figcaption></figure>"), worst_failure


def sweep_plot(frame: pd.DataFrame) -> str:
    """The objective against the first varied input, one line per value of the second."""
    from matplotlib.figure import Figure

    status = list(frame.columns).index("status")
    inputs = list(frame.columns[1:status])
    objective = frame.columns[status + 1]
    figure = Figure(figsize=(6.5, 4), layout="constrained")
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
    return f"<figure>{figure_svg(figure)}<figcaption>{escape(caption)}</figcaption></figure>"


def build_report(case: Case, solution: Solution, sweep: pd.DataFrame | None = None, robust=None,
                 notes: tuple[str, ...] = ()) -> str:
    """The HTML page for a case and its solution (and a sweep table, if given); with ``robust`` (a
    :class:`~clutchopt.optimise.robust.RobustResult`) the solution is its robust design, the nominal one beside it
    under Scatter; ``notes``: lines of the command's own to show under the headline (the choice it made)."""
    formulation = case_formulation(case, solution.mode)
    ok = solution.status == "optimal"
    scattered = scatter(case, robust) if case.scatter else None
    kind = f"Robust design ({escape(robust.method)}" + (f" {robust.target:g}" if robust.target else "") + ")" \
        if robust is not None else "Design"
    nominal = ("" if robust is not None or scattered is None else
               f"<p><b>Nominal design:</b> the case's [scatter] is not designed for, and the {escape(scattered[1])}; "
               "<code>report --robust worst-case</code> or <code>--robust chance=P</code> puts the robust design "
               "here (the section Scatter compares them).</p>")
    header = (f"<h1>Design review: {escape(case.title or case.path)}</h1>"
              f'<p>{escape(formulation.title)}. Case <code>{escape(case.path)}</code>. {kind}: '
              f'status <span class="status{"" if ok else " bad"}">{escape(solution.status)}</span>, '
              f"objective ({escape(solution.objective_name)}) <b>{solution.objective:.6g} "
              f"{escape(solution.objective_unit)}</b>.</p>"
              + "".join(f"<p>{escape(note)}</p>" for note in notes) + nominal
              + (f"<p><b>Diagnosis:</b> {escape(solution.diagnosis)}</p>" if solution.diagnosis else "")
              + f'<p class="note">Generated {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC; '
              + ", ".join(f"{escape(k)} {escape(v)}" for k, v in versions().items()) + ".</p>")
    sections = [
        ("Requirements", requirements(case), "requirements"),
        ("Robust design" if robust is not None else "Optimal design", design(solution, formulation), "design"),
        ("Dimensioned sketch", drawing(case, solution, formulation), "sketch"),
        ("Constraint margins", margins(solution), "margins"),
        ("Sensitivities", sensitivities(solution, formulation), "sensitivities"),
        ("Comparison with the paper's method", comparison(case, robust), "comparison"),
        ("Start-up simulation", simulation(case, solution), "simulation"),
    ]
    if scattered is not None:
        sections.append(("Scatter", scattered[0], "scatter"))
    if sweep is not None:
        sections.append(("Sweep", sweep_plot(sweep), "sweep"))
    body = header + "".join(_section(*s) for s in sections)
    return (f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>Design review: '
            f"{escape(case.title or case.path)}</title><style>{_CSS}</style></head><body>{body}</body></html>")

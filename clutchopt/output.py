"""One layout for every table: design, outputs, constraints with margins and sensitivities; JSON in SI."""

from __future__ import annotations

import json
import math

import pandas as pd

from clutchopt.model import Formulation
from clutchopt.optimise.compare import ComparisonTable
from clutchopt.optimise.problem import Solution
from clutchopt.units import from_si


def _clean(value):
    """JSON-safe: NaN/inf become null, numpy scalars become floats."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def to_json(data: dict) -> str:
    return json.dumps(_clean(data), indent=2, allow_nan=False)


def _shown(value: float | None, unit: str) -> str:
    if value is None or not math.isfinite(value):
        return "-"
    return f"{from_si(value, unit):.6g}"


def _signed(value: float | None) -> str:
    if value is None:
        return "-"
    return "0" if abs(value) < 5e-5 else f"{value:+.4f}"


def _frame(rows: list[dict]) -> str:
    return pd.DataFrame(rows).to_string(index=False) if rows else "(none)"


def solution_text(solution: Solution, formulation: Formulation, title: str = "") -> str:
    lines = [f"{formulation.title}" + (f"  -  {title}" if title else ""),
             f"status: {solution.status}"
             f"   objective ({solution.objective_name}): {solution.objective:.6g} {solution.objective_unit}"]
    if solution.diagnosis:
        lines.append(f"diagnosis: {solution.diagnosis}")
    lines += ["", "Design"]
    lines.append(_frame([
        {"variable": v.name, "symbol": v.symbol, "value": _shown(solution.design[v.name], v.unit), "unit": v.unit,
         "at bound": solution.at_bound(v.name) or "-", "description": v.description} for v in formulation.variables]))
    if solution.outputs:
        lines += ["", "Derived"]
        lines.append(_frame([
            {"quantity": name, "value": _shown(out.value, out.unit), "unit": out.unit, "description": out.description}
            for name, out in solution.outputs.items()]))
    lines += ["", "Constraints (re-evaluated in float64; margin relative; elasticity = d ln objective / d ln limit)"]
    lines.append(_frame([
        {"constraint": c.name, "eq.": c.equation, "value": _shown(c.value, c.unit), "sense": c.sense,
         "limit": _shown(c.limit, c.unit), "unit": c.unit, "margin": f"{c.margin:+.2e}",
         "active": "yes" if c.active else "no", "elasticity": _signed(c.elasticity)}
        for c in solution.constraints]))
    if solution.start_up is not None:
        lines += ["", *start_up_lines(solution.start_up)]
    if solution.sensitivities:
        lines += ["", "Most sensitive parameters (elasticity = d ln objective / d ln parameter; +1: grows in proportion)"]
        lines.append(_frame(sensitivity_rows(solution, formulation)))
    s = solution.solver
    lines += ["", f"solver: {s.name}  status: {s.status}  iterations: {s.iterations}  solves: {s.solves}  "
                  f"time: {s.time_s * 1e3:.1f} ms"]
    if solution.integer_search:
        lines.append("integer neighbours tried: " + "; ".join(
            ", ".join(f"{k}={v}" for k, v in entry.items() if k not in ("status", "feasible", "objective"))
            + (f" -> {entry['objective']:.6g}" if entry["feasible"] else " -> infeasible")
            for entry in solution.integer_search))
    return "\n".join(lines)


START_UP_ROWS = (  # figure, display unit, meaning
    ("start_time", "s", "switch-on to lock-up"),
    ("friction_work", "kJ", "heat released by slip"),
    ("temperature_rise", "K", "largest temperature rise of the friction parts"),
    ("lock_up_speed", "rpm", "speed at lock-up"),
    ("engagement_speed", "rpm", "driving speed at which the weights engage"),
    ("engagement_time", "s", "motor running up unloaded"),
    ("lock_up_time", "s", "the coupling slips under load"),
)


def start_up_lines(start_up: dict) -> list[str]:
    """The NLP's start beside the simulator's, figure by figure."""
    rows = []
    for name, unit, meaning in START_UP_ROWS:
        nlp, simulated = start_up.get(name), start_up.get(f"{name}_simulated")
        if nlp is None:
            continue
        difference = "-" if simulated is None or not math.isfinite(simulated) or simulated == 0 \
            else f"{nlp / simulated - 1:+.1e}"
        rows.append({"figure": name, "NLP": _shown(nlp, unit), "simulated": _shown(simulated, unit), "unit": unit,
                     "NLP/sim - 1": difference if simulated is not None else "-", "meaning": meaning})
    head = (f"Start-up on the case's drive ({', '.join(start_up['effects'])}): Radau collocation, "
            f"{start_up['intervals']} intervals per phase ({', '.join(start_up['phases'])}), beside the simulator")
    lines = [head, _frame(rows)]
    if not start_up["locks_up"]:
        lines.append(f"simulated: {start_up['reason']}")
    return lines


def sensitivity_rows(solution: Solution, formulation: Formulation, count: int = 8) -> list[dict]:
    """The ``count`` largest elasticities, largest first, with the parameter's description."""
    described = {q.name: q.description for q in (*formulation.quantities, *formulation.variables)}
    ranked = sorted(solution.sensitivities.items(), key=lambda item: -abs(item[1]))[:count]
    return [{"parameter": name, "elasticity": _signed(value), "description": described.get(name, "")}
            for name, value in ranked if abs(value) >= 5e-5]


def comparison_text(table: ComparisonTable) -> str:
    rows = []
    for row in table.rows:
        entry = {"quantity": row["quantity"], "unit": row["display_unit"]}
        for column in table.columns:
            entry[column] = _shown(row[column], row["display_unit"])
        rows.append(entry)
    rel = []
    for row in table.rows:
        entry = {"quantity": row["quantity"]}
        for column in table.columns:
            if column != table.baseline:
                value = row.get(f"rel_{column}")
                entry[column] = "-" if value is None else ("0" if abs(value) < 5e-5 else f"{value:+.2%}")
        rel.append(entry)
    lines = [f"Comparison for the {table.coupling} coupling (values in the unit of each row)", _frame(rows), "",
             f"Relative difference against {table.baseline}", _frame(rel), "", "Columns:"]
    lines += [f"  {name}: {note}" for name, note in table.notes.items() if name in table.columns]
    for column, solution in table.solutions.items():
        lines.append(f"  {column}: status {solution.status}, {solution.solver.iterations} iterations"
                     + (f"; {solution.diagnosis}" if solution.diagnosis else ""))
    return "\n".join(lines)

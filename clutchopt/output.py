"""One layout for every table: design, outputs, constraints with margins and sensitivities; JSON in SI.

A solution (:class:`clutchopt.optimise.problem.Solution`) is read by its fields and a comparison is the plain data
of ``ComparisonTable.as_dict()``: this module imports nothing of the optimiser, so that its results can show
themselves (``_repr_html_``) without an import circle (docs/architecture.md).
"""

from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING

from clutchopt.records import DESIGN_STATUSES, UNRANKED, lock_up_verdict, target_text
from clutchopt.units import from_si, si_unit
from clutchopt.scatter import correlation_text, shown_spread

if TYPE_CHECKING:  # JSON needs neither pandas nor the solver: ``solve --json`` starts faster without them
    from clutchopt.model import Formulation


_PLAIN = (str, int, bool, type(None))


def _clean(value):
    """JSON-safe: NaN/inf become null, numpy scalars become floats."""
    kind = type(value)
    if kind is float:  # most values: the common cases first
        return value if math.isfinite(value) else None
    if kind in _PLAIN:
        return value
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def to_json(data: dict, indent: int | None = 2) -> str:
    """JSON for people (indented, the standard library's encoder) or, with ``indent=None``, compact for the run store
    (orjson: about 15x faster on a solution). NaN and infinities become null, NumPy scalars plain numbers. Data that
    is JSON as it is (finite floats, no NumPy integers or booleans: most) is encoded without cleaning; the encoder
    refuses the rest, which is cleaned first."""
    if indent is None:
        import orjson

        try:
            return orjson.dumps(data, option=orjson.OPT_SERIALIZE_NUMPY | orjson.OPT_NON_STR_KEYS).decode()
        except orjson.JSONEncodeError:  # e.g. an integer beyond 64 bits, nesting deeper than 254
            pass
    try:
        return json.dumps(data, indent=indent, allow_nan=False)
    except (ValueError, TypeError):
        return json.dumps(_clean(data), indent=indent, allow_nan=False)


def from_json(text: str | bytes):
    """The value of a JSON text: by orjson (about 3x faster on a stored solution; an integer beyond 64 bits becomes a
    float), else by the standard library, which reads what orjson refuses (NaN and Infinity tokens of older stores)
    or raises ValueError or RecursionError (nesting deeper than about 1000)."""
    import orjson

    try:
        return orjson.loads(text)
    except orjson.JSONDecodeError:
        return json.loads(text)


UNITLESS = ""  # the unit of a count, an id, a ratio, a relative margin or error, an elasticity


def with_units(data: dict, units: dict) -> dict:
    """``data`` with ``units`` merged into its ``units`` mapping, one of the JSON's two ways of giving a number its
    unit (the other: ``{"value": ..., "unit": ...}``): beside each key, the SI unit of that key's number (``""``:
    none), or, for a mapping by name or a list of rows, a mapping of the units by name or by column (a string: one
    unit for all of them, e.g. a list of numbers). Units of keys ``data`` lacks are left out."""
    merged = _merged(data.get("units"), _fitted(data, units))
    return {**data, "units": merged} if merged != {} else data


def _merged(old, new):
    if isinstance(old, dict) and isinstance(new, dict):
        return {**old, **{key: _merged(old.get(key), value) for key, value in new.items()}}
    return new


def _fitted(data, units):
    """``units`` for the keys ``data`` has (a list: the keys of its rows), without empty mappings."""
    if not isinstance(units, dict):
        return units
    if isinstance(data, list):
        keys = {key for row in data if isinstance(row, dict) for key in row}
        return {key: unit for key, unit in units.items() if key in keys}
    fitted = {key: _fitted(data[key], unit) for key, unit in units.items() if isinstance(data, dict) and key in data}
    return {key: unit for key, unit in fitted.items() if unit != {}}


SOLVER_UNITS = {"iterations": UNITLESS, "solves": UNITLESS, "time_s": "s"}
CONSTRAINT_UNITS = dict.fromkeys(("margin", "multiplier", "elasticity", "tolerance"), UNITLESS)  # the rest: ``unit``
TRAJECTORY_UNITS = {"t": "s", "w_driver": "rad/s", "w_driven": "rad/s", "friction_work": "J", "temperature_rise": "K",
                    "twist": "rad"}


def robust_json(result, case) -> dict:
    """A robust design's ``as_dict()`` with units: the corners' quantities, the nominal design and objective, the
    constraint checks; probabilities, counts and changes of relative margins are unitless."""
    from clutchopt.records import scatter_record

    quantities = {q.name: q.si_unit for q in case.quantities}
    data = {**result.as_dict(), "scatter": scatter_record(case)}
    design = {name: si_unit(unit) for name, unit in result.nominal.design_units.items()}
    spread = {name: {key: quantities[name] for key in ("low", "high", "mean", "sd")} for name in data["scatter"]}
    return with_units(data, {
        "scatter": {name: {**units, "correlation": UNITLESS} for name, units in spread.items()},
        "target": UNITLESS, "samples": UNITLESS, "confidence": UNITLESS, "failure_probability": UNITLESS,
        "nominal_failure_probability": UNITLESS, "margin_sensitivity": UNITLESS, "monte_carlo_above_target": UNITLESS,
        "corners": {name: quantities for name in data["corners"]}, "checks": CONSTRAINT_UNITS,
        "nominal_checks": CONSTRAINT_UNITS, "nominal_design": design, "performance_point_beta": UNITLESS,
        "system_allocation": ALLOCATION_UNITS, "system_failure_probability": ESTIMATE_UNITS,
        "start_up_verification": {"corners": quantities, "simulations": UNITLESS, "failure_probability": UNITLESS,
                                  "performance_point_beta": UNITLESS, "share_of_target": UNITLESS},
        **{key: reliability_units(data[key], quantities) for key in ("reliability", "nominal_reliability")
           if data.get(key)}})


ESTIMATE_UNITS = dict.fromkeys(("probability", "low", "high"), UNITLESS)
ALLOCATION_UNITS = {"target": UNITLESS, "budget": UNITLESS, "series_bound": UNITLESS, "system": ESTIMATE_UNITS,
                    "constraints": UNITLESS}  # a system chance design's split of 1 - P: probabilities and betas


def reliability_units(data: dict, quantities: dict) -> dict:
    """The units of a ``Reliability.as_dict()``: probabilities and beta unitless, a design point's quantities SI."""
    estimate = dict.fromkeys(("probability", "low", "high"), UNITLESS)
    return {"constraints": {name: {"beta": UNITLESS, "design_point": quantities, "estimates": estimate,
                                   "failure_probability": estimate} for name in data["constraints"]},
            "system": estimate}


def shown_point(record: dict) -> dict:
    """A sweep point's record as its table and ``runs export`` show it: where its status has no design (infeasible,
    not_found), no objective value, design or outputs (review 30: a point proven infeasible over a region had shown the
    design its proof was carried from, the point before's 950.755 kg, where ``solve`` of it alone shows its own
    last point); its verdict, diagnosis and constraints as they are."""
    if record.get("status") in DESIGN_STATUSES or "objective" not in record:
        return record
    return {**record, "objective": {**record["objective"], "value": None}, "design": None, "outputs": None}


def comparison_json(table) -> dict:  # a ComparisonTable (optimise.compare): read by its fields
    """The comparison's ``as_dict()`` with units: each row's values in its ``unit``, the relative differences and
    the solver's counts unitless, each optimum's objective in its unit."""
    return with_units(table.as_dict(), {
        "rows": {"relative": UNITLESS},
        "solves": {column: {"objective": s.objective_unit, "solver": SOLVER_UNITS}
                   for column, s in table.solutions.items()}})


HEADLINE_UNITS = {  # a simulated start-up's figures (clutchopt.simulate), and the closed form's
    "start_time": "s", "friction_work": "J", "source_work": "J", "lock_up_speed": "rad/s", "peak_slip_power": "W",
    "end_time": "s", "total_friction_work": "J", "final_driver_speed": "rad/s", "final_driven_speed": "rad/s",
    "temperature_rise": "K", "peak_twist": "rad", "peak_stress": "Pa", "start_time_printed_eq9": "s",
    "source": {"engagement_speed": "rad/s", "design_torque": "N*m"}}
SIMULATION_UNITS = {"headline": HEADLINE_UNITS, "events": {"time": "s", "torque": "N*m"}, "analytic": HEADLINE_UNITS}
CHECK_UNITS = {"sized_acceleration_time": "s", "simulated_acceleration_time": "s", "relative_difference": UNITLESS,
               "simulated_start_time": "s", "max_start_time": "s", "friction_work": "J"}  # a design's start-up check


def solution_json(record: dict) -> dict:
    """A solution as JSON (``Solution.as_dict()`` or a stored one) with the unit of every number: ``units`` names,
    besides the design and outputs, the constraints' relative columns (their values and limits are in their
    ``unit``), the solver's counts and time, the bounds, the sensitivities (elasticities), the integer search and
    the start-up."""
    design = record.get("units", {}).get("design", {})
    record = with_units(record, {"constraints": CONSTRAINT_UNITS, "solver": SOLVER_UNITS, "bounds": design,
                                 "sensitivities": UNITLESS,
                                 "integer_search": {**design, "objective": record["objective"].get("unit")},
                                 "solve_alone": {"objective": record["objective"].get("unit")}})
    start_up = record.get("start_up")
    if start_up:
        figures = start_up.get("units", {})
        record["start_up"] = with_units(start_up, {
            **{f"{name}_simulated": unit for name, unit in figures.items()}, "intervals": UNITLESS,
            "tolerance": UNITLESS, "discretisation_error": UNITLESS, "trajectory": TRAJECTORY_UNITS})
    return record


def _shown(value: float | None, unit: str) -> str:
    if value is None or not math.isfinite(value):
        return "-"
    return f"{from_si(value, unit):.6g}"


def _signed(value: float | None) -> str:
    if value is None:
        return "-"
    return "0" if abs(value) < 5e-5 else f"{value:+.4f}"


_ESCAPED = str.maketrans({"\t": "\\t", "\n": "\\n", "\r": "\\r"})  # (as pandas shows them in a table)


def _frame(rows: list[dict]) -> str:
    """The rows (text cells, by column name) as a fixed-width text table: each column as wide as its widest cell or
    name, right-aligned, one space between, a missing cell NaN; the text pandas' ``DataFrame.to_string(index=False)``
    gives (tests/test_output_table.py), without pandas's import (0.3 s, half of a text ``solve``)."""
    if not rows:
        return "(none)"
    names = list(dict.fromkeys(name for row in rows for name in row))
    columns = [[str(name), *(str(row.get(name, "NaN")) for row in rows)] for name in names]
    columns = [[cell.translate(_ESCAPED) for cell in column] for column in columns]
    widths = [max(map(len, column)) for column in columns]
    return "\n".join(" ".join(column[i].rjust(width) for column, width in zip(columns, widths))
                     for i in range(len(rows) + 1))


def design_rows(solution, formulation: Formulation) -> list[dict]:
    return [{"variable": v.name, "symbol": v.symbol, "value": _shown(solution.design[v.name], v.unit), "unit": v.unit,
             "at bound": solution.at_bound(v.name) or "-", "description": v.description}
            for v in formulation.variables]


def derived_rows(solution) -> list[dict]:
    return [{"quantity": name, "value": _shown(out.value, out.unit), "unit": out.unit, "description": out.description}
            for name, out in solution.outputs.items()]


def constraint_rows(solution) -> list[dict]:
    return [{"constraint": c.name, "eq.": c.equation, "value": _shown(c.value, c.unit), "sense": c.sense,
             "limit": _shown(c.limit, c.unit), "unit": c.unit, "margin": f"{c.margin:+.2e}",
             "active": "yes" if c.active else "no", "elasticity": _signed(c.elasticity)}
            for c in solution.constraints]


CONSTRAINTS_TITLE = "Constraints (re-evaluated in float64; margin relative; elasticity = d ln objective / d ln limit)"
SENSITIVITIES_TITLE = ("Most sensitive parameters (elasticity = d ln objective / d ln parameter; +1: grows in "
                       "proportion)")


def headline(solution, formulation: Formulation, title: str = "") -> list[str]:
    lines = [f"{formulation.title}" + (f"  -  {title}" if title else ""),
             f"status: {solution.status}"
             f"   objective ({solution.objective_name}): {solution.objective:.6g} {solution.objective_unit}"]
    return lines + ([f"diagnosis: {solution.diagnosis}"] if solution.diagnosis else []) + \
        ([f"starts tried: {', '.join(solution.starts)}"] if solution.starts else [])


def solution_tables(solution, formulation: Formulation) -> list[tuple[str, list[dict], list[str]]]:
    """The tables of a solution as (title, rows, notes below), in the order ``clutchopt solve`` prints them."""
    tables = [("Design", design_rows(solution, formulation), [])]
    if solution.outputs:
        tables.append(("Derived", derived_rows(solution), []))
    tables.append((CONSTRAINTS_TITLE, constraint_rows(solution), []))
    if solution.start_up is not None:
        tables.append(start_up_table(solution.start_up))
    if solution.sensitivities:
        tables.append((SENSITIVITIES_TITLE, sensitivity_rows(solution, formulation), []))
    return tables


def solver_line(solution) -> str:
    s = solution.solver
    iterations = "-" if s.iterations is None else s.iterations
    return (f"solver: {s.name}  status: {s.status}  iterations: {iterations}  solves: {s.solves}  "
            f"time: {s.time_s * 1e3:.1f} ms")


def solution_text(solution, formulation: Formulation, title: str = "") -> str:
    lines = headline(solution, formulation, title)
    for table_title, rows, notes in solution_tables(solution, formulation):
        lines += ["", table_title, _frame(rows), *notes]
    lines += ["", solver_line(solution)]
    if solution.integer_search:
        lines.append("integer neighbours tried: " + "; ".join(
            ", ".join(f"{k}={v}" for k, v in entry.items() if k not in ("status", "feasible", "objective"))
            + (f" -> {entry['objective']:.6g}" if entry["feasible"] else f" -> {_not_feasible(entry)}")
            for entry in solution.integer_search))
    return "\n".join(lines)


def _not_feasible(entry: dict) -> str:
    """What an integer search entry without a design says: ``not solved (why)`` for one left unsolved (UNRANKED),
    ``unverified (objective)`` for a design whose simulated start missed a limit (a start-up's own loop, modifier
    adaptation, or its design at the case's limits: not shown infeasible), else infeasible (a solve's verdict, or a
    constraint of the fixed variables alone broken)."""
    status = entry.get("status", "")
    if status.startswith(UNRANKED):
        return f"not solved ({status[len(UNRANKED):]})"
    if status.endswith(": unverified"):
        return f"unverified ({entry['objective']:.6g})"
    return "infeasible"


def html_table(rows: list[dict], numeric: tuple[str, ...] = ("value", "limit", "margin", "elasticity"),
               markup: tuple[str, ...] = ()) -> str:
    """Rows as an HTML table: values escaped except in the ``markup`` columns; ``numeric`` ones right-aligned."""
    from html import escape

    if not rows:
        return '<p class="note">(none)</p>'
    head = "".join(f"<th>{escape(str(column))}</th>" for column in rows[0])
    body = "".join("<tr>" + "".join(f'<td{" class=n" if column in numeric else ""}>'
                                    f"{value if column in markup else escape(str(value))}</td>"
                                    for column, value in row.items()) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def solution_html(solution) -> str:
    """A solution as Jupyter shows it: the tables of ``clutchopt solve``, as HTML."""
    from html import escape

    from clutchopt.formulations import get_coupling
    from clutchopt.start_up.equations import with_start_up

    formulation = get_coupling(solution.coupling).formulation(solution.mode)
    if solution.start_up is not None:
        formulation = with_start_up(formulation)
    parts = [f"<p>{'<br>'.join(escape(line) for line in headline(solution, formulation))}</p>"]
    for title, rows, notes in solution_tables(solution, formulation):
        parts.append(f"<h4>{escape(title)}</h4>{html_table(rows)}" + "".join(f"<p>{escape(n)}</p>" for n in notes))
    return "<div>" + "".join(parts) + f"<p>{escape(solver_line(solution))}</p></div>"


def library_text(case) -> str:
    """The fields the material library filled, by role, with each entry's friction scatter where it has one."""
    from clutchopt.materials import filled_by

    lines = []
    for key, item in filled_by(case).items():
        scatter = item.get("friction_range")
        values = ", ".join(f"{q.name} {q.show(v)}" + (f" (scatter {scatter[0]:g} to {scatter[1]:g})"
                                                       if scatter and q.name == "friction_coefficient" else "")
                           for q, v in item["values"].values())
        lines.append(f"  {key} = {item['entry']}: {values}")
    return "\n".join(["From the material library (values the case gives itself win):", *lines]) if lines else ""


def library_json(case) -> dict:
    """``library_text`` as JSON: per role the entry, its source, each filled value with its SI unit and the friction
    coefficient's scatter (no unit)."""
    from clutchopt.materials import filled_by

    return {key: with_units({"entry": item["entry"], "source": item["source"],
                             **({"friction_range": list(item["friction_range"])} if "friction_range" in item else {}),
                             "values": {q.name: {"value": v, "unit": q.si_unit, "display_unit": q.unit}
                                        for q, v in item["values"].values()}}, {"friction_range": UNITLESS})
            for key, item in filled_by(case).items()}


def choices_text(ranked: list, kept: dict[str, str] | None = None) -> str:
    """The variants of ``options.choose`` (``clutchopt.optimise.design.Designed``), best first: choice, status,
    objective; ``kept``: what a chosen role would fill but the case gives itself (quantity -> role), said in a
    line, since every choice then uses the case's value."""
    rows = [{"rank": str(i + 1), **d.choice, "status": d.solution.status,
             f"{d.solution.objective_name} [{d.solution.objective_unit}]":
                 _shown(d.solution.objective if d.solution.status == "optimal" else None, "")}
            for i, d in enumerate(ranked)]
    why = [f"  {', '.join(d.choice.values())}: {d.solution.diagnosis}" for d in ranked if d.solution.diagnosis]
    robust = f" ({ranked[0].robust.method} designs)" if ranked[0].robust is not None else ""
    same = [f"given by the case, the same for every choice: {', '.join(f'{q} ({role})' for q, role in kept.items())}"] \
        if kept else []
    return "\n".join([f"Choices of options.choose, best first{robust}", _frame(rows), *why, *same, "",
                      f"Below: the best, {ranked[0].choice_text}."])

def choice_text(choice: dict) -> str:
    """``clutchopt choose-coupling``: the couplings (``clutchopt.optimise.choose.choice_json``), verified optima first
    by like-for-like mass; their parts; why each loses; what did not apply."""
    rows = [{"rank": str(c["rank"] or "-"), "coupling": c["coupling"], "mode": c["mode"], "status": c["status"],
             "mass [kg]": _shown(c["envelope_mass"], "kg"), "cost [EUR]": _shown(c["cost"], "EUR"),
             "diameter [mm]": _shown(c["envelope_diameter"], "mm"), "length [mm]": _shown(c["envelope_length"], "mm"),
             "sized for [N*m]": _shown(c["sized_for"], "N*m")} for c in choice["couplings"]]
    parts = [{"coupling": c["coupling"], **{f"{name} [kg]": _shown(mass, "kg") for name, mass in c["parts"].items()}}
             for c in choice["couplings"] if c["parts"]]
    ranking = "; ".join(f"by {what}: {', '.join(names) or '-'}" for what, names in choice["ranking"].items())
    checks = [{"coupling": c["coupling"], "check": name, "value": _shown(entry["value"], entry["display_unit"]),
               "limit": _shown(entry["limit"], entry["display_unit"]), "unit": entry["display_unit"],
               "margin": f"{entry['margin']:+.3g}"} for c in choice["couplings"] for name, entry in c["checks"].items()]
    lines = [f"Which coupling  -  {choice['title']}",
             f"duty: T_max = I w / t_p + T_c = {choice['required_torque']:.6g} N*m; each coupling designed for least "
             "like-for-like mass (objective envelope_mass, docs/envelope.md) and verified in float64",
             *([f"drive: {choice['drive']}"] if choice.get("drive") else []), "",
             _frame(rows), f"ranked {ranking}", "", "Like-for-like mass by part", _frame(parts), "",
             "The drive's checks of each verified design (float64)", _frame(checks), "",
             "Why the others lose", *(f"  {c['coupling']}: {c['why']}" for c in choice["couplings"])]
    notes = [f"  {c['coupling']}: {note}" for c in choice["couplings"] for note in c["notes"]]
    return "\n".join(lines + (["", "Posed with", *notes] if notes else []))


START_UP_ROWS = (  # figure, display unit, meaning
    ("start_time", "s", "switch-on to lock-up"),
    ("friction_work", "kJ", "heat released by slip"),
    ("temperature_rise", "K", "largest temperature rise of the friction parts"),
    ("lock_up_speed", "rpm", "speed at lock-up"),
    ("engagement_speed", "rpm", "driving speed at which the weights engage"),
    ("engagement_time", "s", "motor running up unloaded"),
    ("lock_up_time", "s", "the coupling slips under load"),
    ("lining_temperature", "degC", "peak lining temperature: ambient + steady of repeated starts + the start's rise"),
    ("steady_temperature", "degC", "steady lining temperature of repeated starts (starts_per_hour)"),
    ("wear_per_start", "um", "lining worn per start, k_w L / A"),
    ("starts_until_worn", "", "starts until the wear allowance is gone"),
    ("life", "h", "hours of starts (starts_per_hour) until worn"),
)
ELASTIC_START_UP_ROWS = (  # an elastic link (the cable coupling): the NLP's link quasi-static, the simulator's dynamic
    ("start_time", "s", "switch-on until the machine runs at the start speed"),
    ("lock_up_speed", "rpm", "the start speed (min_lock_up_speed)"),
    ("peak_link_stress", "MPa", "largest stress of the link during the start"),
    ("peak_twist", "deg", "largest twist of the halves during the start"),
    ("friction_work", "J", "energy the link's damping takes (none in the quasi-static NLP)"),
)


def start_up_table(start_up: dict) -> tuple[str, list[dict], list[str]]:
    """The NLP's start beside the simulator's, figure by figure: title, rows, a note if it does not lock up."""
    rows = []
    elastic = "locked" in start_up["phases"]
    for name, unit, meaning in ELASTIC_START_UP_ROWS if elastic else START_UP_ROWS:
        nlp, simulated = start_up.get(name), start_up.get(f"{name}_simulated")
        if nlp is None:
            continue
        difference = "-" if simulated is None or not math.isfinite(simulated) or simulated == 0 \
            else f"{nlp / simulated - 1:+.1e}"
        rows.append({"figure": name, "NLP": _shown(nlp, unit), "simulated": _shown(simulated, unit), "unit": unit,
                     "NLP/sim - 1": difference if simulated is not None else "-", "meaning": meaning})
    head = (f"Start-up on the case's drive ({', '.join(start_up['effects'])}): Radau collocation, "
            f"{start_up['intervals']} intervals per phase ({', '.join(start_up['phases'])}), beside the simulator"
            + (" (the NLP takes the elastic link as quasi-static, the simulator follows its dynamics)" if elastic
               else ""))
    notes = ([start_up["motor"]] if start_up.get("motor") else []) + start_up.get("lining_notes", [])
    if start_up.get("worn"):
        notes.append(worn_note(start_up["worn"]))
    if start_up.get("overload"):
        notes.append(start_up["overload"])
    return head, rows, notes + ([] if start_up["locks_up"] else [f"simulated: {start_up['reason']}"])


def worn_note(worn: dict) -> str:
    """The start with worn linings (the lever), simulated, in a line."""
    if not worn["locks_up"]:
        return f"worn linings (simulated): {'no lock-up' if lock_up_verdict(worn) == 'no' else 'not decided'}"
    heat = f", {worn['temperature_rise']:.4g} K" if worn.get("temperature_rise") is not None else ""
    least = worn.get("min_lock_up_speed")
    early = (f" (below min_lock_up_speed {least * 30 / math.pi:.5g} rpm: the motor runs the machine up locked)"
             if least is not None and worn["lock_up_speed"] < least else "")
    return (f"worn linings (simulated): lock-up after {worn['start_time']:.4g} s at "
            f"{worn['lock_up_speed'] * 30 / math.pi:.5g} rpm{early}, {worn['friction_work'] / 1e3:.4g} kJ{heat}")


def sensitivity_rows(solution, formulation: Formulation, count: int = 8) -> list[dict]:
    """The ``count`` largest elasticities, largest first, with the parameter's description."""
    described = {q.name: q.description for q in (*formulation.quantities, *formulation.variables)}
    ranked = sorted(solution.sensitivities.items(), key=lambda item: -abs(item[1]))[:count]
    return [{"parameter": name, "elasticity": _signed(value), "description": described.get(name) or _held(name)}
            for name, value in ranked if abs(value) >= 5e-5]


def _held(name: str) -> str:
    """What a robust design's NLP parameter is (review 29: listed without a word): ``q@c`` the value of a scattered
    quantity ``q`` where the constraint ``c`` is held (its corner or performance point; ``start_up``: the start's),
    ``direction_q@c`` the direction of c's performance point in q's standard normal variable."""
    quantity, at, where = name.partition("@")
    if not at:
        return ""
    if quantity.startswith("direction_"):
        return f"direction of {where}'s performance point in {quantity.removeprefix('direction_')}"
    return (f"{quantity} where {'the start' if where == 'start_up' else where} is held (its corner of the scatter or "
            "performance point)")


def comparison_rows(comparison: dict) -> tuple[list[dict], list[dict]]:
    """The values of every column in each row's unit, and the relative differences against the baseline."""
    rows, rel = [], []
    for row in comparison["rows"]:
        rows.append({"quantity": row["quantity"], "unit": row["display_unit"],
                     **{column: _shown(row[column], row["display_unit"]) for column in comparison["columns"]}})
        entry = {"quantity": row["quantity"]}
        for column in comparison["columns"]:
            if column != comparison["baseline"]:
                value = row["relative"].get(column)
                entry[column] = "-" if value is None else ("0" if abs(value) < 5e-5 else f"{value:+.2%}")
        rel.append(entry)
    return rows, rel


def comparison_titles(comparison: dict) -> tuple[str, str]:
    return (f"Comparison for the {comparison['coupling']} coupling (values in the unit of each row)",
            f"Relative difference against {comparison['baseline']}")


def column_notes(comparison: dict) -> dict[str, str]:
    """The notes of the columns shown."""
    return {name: note for name, note in comparison["column_notes"].items() if name in comparison["columns"]}


def comparison_text(comparison: dict) -> str:
    """The comparison as ``clutchopt compare`` prints it, from ``ComparisonTable.as_dict()``."""
    rows, rel = comparison_rows(comparison)
    title, rel_title = comparison_titles(comparison)
    lines = [title, _frame(rows), "", rel_title, _frame(rel), "", "Columns:"]
    lines += [f"  {name}: {note}" for name, note in column_notes(comparison).items()]
    for column, solve in comparison["solves"].items():
        lines.append(f"  {column}: status {solve['status']}, {solve['solver']['iterations']} iterations"
                     + (f"; {solve['diagnosis']}" if solve["diagnosis"] else ""))
    return "\n".join(lines)


def comparison_html(comparison: dict) -> str:
    """The comparison as Jupyter shows it: the tables of ``clutchopt compare``, as HTML."""
    from html import escape

    rows, rel = comparison_rows(comparison)
    title, rel_title = comparison_titles(comparison)
    numeric = tuple(comparison["columns"])
    notes = "".join(f"<li><b>{escape(name)}</b>: {escape(note)}</li>"
                    for name, note in column_notes(comparison).items())
    return (f"<div><h4>{escape(title)}</h4>{html_table(rows, numeric)}<h4>{escape(rel_title)}</h4>"
            f"{html_table(rel, numeric)}<ul>{notes}</ul></div>")


def materials_text(kind: str, title: str) -> str:
    """One table of the material library: values in display units, a legend, then each entry's source."""
    from textwrap import wrap

    import pandas as pd

    from clutchopt.materials import FIELDS, library, rows

    fields = FIELDS[kind]
    headers = {q.name: f"{q.symbol or q.name} [{q.unit}]" if q.unit else q.symbol or q.name for q in fields}
    frame = pd.DataFrame(rows(kind)).rename(columns=headers)
    table = frame.to_string(index=False, float_format=lambda v: f"{v:.4g}", na_rep="-")
    legend = wrap("; ".join(f"{q.symbol or q.name}: {q.description}" for q in fields), 116)
    sources = [line for e in library()[kind].values() for line in wrap(
        f"{e.name}: {e.description}. Source: {e.source}" + (f". Note: {e.notes}" if e.notes else ""), 116,
        initial_indent="  ", subsequent_indent="      ")]
    return "\n".join([f"{title} (clutchopt/data/materials.toml)", table, "", *legend, "", *sources])


ESTIMATORS = {"importance sampling": "IS", "Monte Carlo": "MC", "FORM": "FORM", "SORM (Breitung)": "SORM"}


def _estimate(estimate) -> str:
    """A failure probability with its interval and, abbreviated, the estimator that gave it."""
    short = ESTIMATORS.get(estimate.estimator)
    if math.isnan(estimate.probability):
        return f"- {short or estimate.estimator} (not defined here)"
    if short is None:
        return f"{estimate.probability:.3g} ({estimate.estimator})"
    if estimate.low == estimate.high:
        return f"{estimate.probability:.3g} {short}"
    return f"{estimate.probability:.3g} ({estimate.low:.3g}-{estimate.high:.3g}) {short}"


def reliability_lines(result, case) -> list[str]:
    """The system's failure probability (robust and nominal design) and each constraint's design point with its
    reliability index and estimates (robust design)."""
    if result.reliability is None:
        return []
    quantities = {q.name: q for q in case.quantities}
    lines = [f"System (any constraint fails{'; the start-up limits apart, simulated' if result.start_up_points else ''}): robust {_estimate(result.reliability.system)}, nominal "
             f"{_estimate(result.nominal_reliability.system)}",
             *([f"System with the start-up limits (any constraint or limit fails; union bound): robust "
                f"{_estimate(result.design_failure())}"] if result.start_up_failure else []),
             "Design points of the robust design (most probable failure point; beta = its distance in standard "
             "normal space): estimates FORM, SORM (Breitung), IS (importance sampling at the design point, 95% "
             "interval)"]
    for name, c in result.reliability.constraints.items():
        if not c.point.found:
            lines.append(f"  {name}: {_estimate(c.best)}")
            continue
        at = ", ".join(f"{q} {quantities[q].show(v, 5)}" for q, v in c.values.items())
        lines.append(f"  {name}: beta {c.point.beta:.4g} at {at}: " + ", ".join(_estimate(e) for e in c.estimates))
    return lines


def allocation_lines(allocation) -> list[str]:
    """How a system chance design split 1 - P between its constraints (``RiskAllocation``): the claim, then each
    constraint's beta, the index importance sampling added, its share and its estimate."""
    data = allocation.as_dict()
    lines = [f"Risk allocation (system chance): {data['claim']}"]
    for name, c in data["constraints"].items():
        estimate = c["failure_probability"]
        lines.append(f"  {name}: beta {c['beta']:.4g}, index shift {c['index_shift']:+.3g}, share {c['share']:.3g}"
                     + (f", P(fail) {estimate['probability']:.3g} ({estimate['low']:.3g} to {estimate['high']:.3g}, "
                        f"{estimate['estimator']})" if estimate else ""))
    return lines


def _probability(triple: list[float]) -> str:
    p, low, high = triple
    return "0 (<{:.2g})".format(high) if p == 0 else f"{p:.3g} ({low:.2g}-{high:.2g})"


def scatter_rows(case) -> list[dict]:
    """The case's [scatter]: each quantity's range or distribution and its nominal value, in its display unit."""
    quantities = {q.name: q for q in case.quantities}
    return [{"quantity": s.name, "scatter": s.describe(quantities[s.name].show,
                                                       lambda v, q=quantities[s.name]: shown_spread(q, v)),
             "nominal": quantities[s.name].show(case.values[s.name])} for s in case.scatter]


def robust_text(result, case) -> str:
    """The robust design beside the nominal one: the scatter, what robustness costs, each constraint at its worst
    (corner or back-off) and its Monte Carlo failure probability, and what drives it (tornado rows)."""
    quantities, scatter = {q.name: q for q in case.quantities}, scatter_rows(case)
    how = ("worst case: every constraint at its own worst corner of the ranges (a normal quantity: mean +- 3 sd), "
           "all 2^n corners checked" if result.method == "worst-case" else
           f"{'system ' if result.method == 'system_chance' else ''}chance {target_text(result.target)}: "
           + (f"the design (any constraint{' or start-up limit' if result.start_up_points else ''}) holds"
              if result.method == "system_chance" else
              "each constraint holds") + " with that probability, each constraint at its performance point (PMA), "
           + ("1 - P split between the constraints by the NLP (optimal risk allocation), the system verified by "
              "importance sampling" if result.allocation else "beta corrected until importance sampling meets the "
                                                               "target")
           + ((", each start-up limit at its performance point too (simulated starts)"
               + (", each one the scatter moves with its share of 1 - P (a union bound)"
                  if result.start_up_share else "") if result.start_up_beta
               is not None else ", a start-up designed at the corner of the quantiles where it binds")
              if result.start_up_points else ""))
    robust, nominal = result.solution, result.nominal
    change = robust.objective / nominal.objective - 1 if nominal.objective else float("nan")
    nominal_checks = {c.name: c for c in result.nominal_checks}

    def corner(name: str) -> str:
        """The quantities that move the constraint, at its worst corner (the others do not matter)."""
        values, effects = result.corners.get(name, {}), result.bars.get(name, {})
        shown = [f"{q} {quantities[q].show(v)}" for q, v in values.items() if abs(effects.get(q, 1.0)) > 1e-12]
        return ", ".join(shown) or ("any" if values else "-")

    failure = {**result.failure, **result.start_up_failure}  # a start-up's from simulated starts
    rows = [{"constraint": c.name, **({"worst corner": corner(c.name)} if result.method == "worst-case" else {}),
             "robust margin": f"{c.margin:+.2e}",
             "nominal margin": f"{nominal_checks[c.name].margin:+.2e}" if c.name in nominal_checks else "-",
             "robust P(fail)": (_estimate(result.reliability.constraints[c.name].best)
                                if result.reliability and c.name in result.reliability.constraints else
                                _probability(failure[c.name]) + " MC" if c.name in failure else "-"),
             "nominal P(fail)": _probability(result.nominal_failure[c.name]) + " MC" if c.name in
             result.nominal_failure else "-"} for c in result.checks]
    names = [s.name for s in case.scatter]
    bars = [{"constraint": name, **{q: f"{effects.get(q, 0.0):+.3g}" for q in names}}
            for name, effects in result.bars.items() if any(abs(v) > 1e-12 for v in effects.values())]
    lines = [f"Robust design ({how}): status {result.status}"
             + (f" - {result.diagnosis}" if result.diagnosis else ""), result.verification,
             _frame(scatter), *filter(None, [correlation_text(case.scatter, case.correlation)]), "",
             f"{robust.objective_name}: robust {robust.objective:.6g} {robust.objective_unit}, nominal "
             f"{nominal.objective:.6g} {nominal.objective_unit} ({change:+.1%})", "",
             ("Constraints under scatter: margin at the worst corner of the ranges" if result.method == "worst-case"
              else "Constraints under scatter: margin at its performance point")
             + f", and the failure probability: IS by importance sampling at the design point (95% interval), MC from "
               f"{result.samples} Monte Carlo samples ({result.as_dict()['confidence']:.0%} Clopper-Pearson interval)"
             + ((f" (a start-up's: margin at its performance point, P(fail) by importance sampling of "
                 f"{result.start_up_samples} simulated starts, FORM or exact)" if result.start_up_beta is not None
                 else f" (a start-up's: margin at its worst simulated corner, P(fail) from {result.start_up_samples} "
                      "simulated starts)") if result.start_up_points else ""), _frame(rows)]
    if result.allocation is not None:
        lines += ["", *allocation_lines(result.allocation)]
    if result.reliability is not None:
        lines += ["", *reliability_lines(result, case)]
    if bars:
        lines += ["", "What drives it: change of each relative margin as a quantity goes from low to high, the "
                      "others nominal (robust design)", _frame(bars)]
    return "\n".join(lines)

"""A batched sweep point's record in two parts: its own numbers (compact), and a template of what the points of its
window share (names, equations, units, bounds, the solver). ``expand(compact, template)`` is the point's
``Solution.as_dict()``.

The run store keeps a batched point as its compact part and each template once (``templates``, by key), where every
point used to repeat each constraint's equation and description: 41 % of the full record's bytes on the cable, 46 %
on the wedge, built in less than half the time. Pure Python: the store reads records without importing the solvers.
"""

from __future__ import annotations

import hashlib
import json

TEMPLATE = "template"  # the key that marks a compact record, holding its template's key
STATUSES = ("optimal", "unverified", "infeasible", "solver_failed")  # how a solve ends
CONSTRAINT_COLUMNS = ("value", "limit", "margin", "active", "feasible", "scale", "multiplier", "elasticity")


def template_key(template: dict) -> str:
    """A template's key: a hash of its canonical JSON (equal templates share one key)."""
    text = json.dumps(template, sort_keys=True, separators=(",", ":"))  # an infinite bound hashes as Infinity
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def is_compact(record) -> bool:
    return isinstance(record, dict) and TEMPLATE in record


def status_and_objective(record: dict) -> tuple[str, float | None]:
    """A record's status and objective value, compact or full."""
    objective = record["objective"]
    return record["status"], objective if is_compact(record) else objective["value"]


def expand(compact: dict, template: dict) -> dict:
    """The full record (``Solution.as_dict()``'s keys, in its order) of a compact record and its template; KeyError,
    IndexError, TypeError or ValueError if they do not fit each other."""
    constraints = compact["constraints"]
    count = len(template["constraints"])
    columns = [constraints[name] for name in CONSTRAINT_COLUMNS]
    if any(len(column) != count for column in columns):
        raise ValueError("the constraints do not fit the template")
    return {
        "coupling": template["coupling"], "mode": template["mode"], "status": compact["status"],
        "objective": {"name": template["objective"]["name"], "value": compact["objective"],
                      "unit": template["objective"]["unit"]},
        "design": _named(template["design"], compact["design"]),
        "outputs": _named(template["outputs"], compact["outputs"]),
        "units": template["units"],
        "constraints": [
            {"name": static["name"], "equation": static["equation"], "sense": static["sense"], "value": value,
             "limit": limit, "margin": margin, "active": active, "feasible": feasible, "unit": static["unit"],
             "description": static["description"], "scale": scale, "multiplier": multiplier, "elasticity": elasticity,
             "tolerance": static["tolerance"], "display_unit": static["display_unit"]}
            for static, value, limit, margin, active, feasible, scale, multiplier, elasticity
            in zip(template["constraints"], *columns)],
        "solver": {**template["solver"], **compact["solver"]},
        "diagnosis": compact["diagnosis"],
        "integer_search": compact["integer_search"],
        "bounds": template["bounds"],
        "sensitivities": compact["sensitivities"],
    }


def _named(names: list[str], values: list) -> dict:
    if len(names) != len(values):
        raise ValueError("the values do not fit the template's names")
    return dict(zip(names, values))


def check_solution(record) -> dict:
    """``record`` if it has the shape of a ``Solution.as_dict()`` where tables, exports and resumed sweeps read it
    (fields of older clutchopt versions may be missing; those present must have their types), else ValueError naming
    the first field that does not."""
    _expect(isinstance(record, dict), "the solution", "an object")
    _expect(record.get("status") in STATUSES, "status", "one of " + ", ".join(STATUSES))
    objective = record.get("objective")
    _expect(isinstance(objective, dict) and _number(objective.get("value")), "objective", "an object with a value")
    _expect(_mapping(record.get("design"), _number), "design", "numbers by name")
    for key in ("outputs", "sensitivities"):
        _expect(key not in record or _mapping(record[key], _number), key, "numbers by name")
    units = record.get("units", {})
    _expect(_mapping(units, lambda names: _mapping(names, lambda unit: isinstance(unit, str))), "units",
            "unit names by name")
    constraints = record.get("constraints")
    _expect(isinstance(constraints, list) and all(map(_constraint, constraints)), "constraints",
            "a list of named constraints with numbers, flags and text")
    solver = record.get("solver")
    _expect(isinstance(solver, dict) and _whole(solver.get("iterations")) and _number(solver.get("time_s")), "solver",
            "an object with whole iterations and time_s")
    _expect(record.get("diagnosis") is None or isinstance(record["diagnosis"], str), "diagnosis", "text")
    _expect(isinstance(record.get("integer_search", []), list), "integer_search", "a list")
    _expect(isinstance(record.get("bounds", {}), dict), "bounds", "an object")
    return record


CONSTRAINT_NUMBERS = ("value", "limit", "margin", "scale", "multiplier", "elasticity", "tolerance")
CONSTRAINT_TEXTS = ("equation", "sense", "unit", "description", "display_unit")


def _constraint(item) -> bool:
    return (isinstance(item, dict) and isinstance(item.get("name"), str)
            and all(isinstance(item.get(key, False), bool) for key in ("active", "feasible"))
            and all(_number(item.get(key)) for key in CONSTRAINT_NUMBERS)
            and all(isinstance(item.get(key, ""), str) for key in CONSTRAINT_TEXTS))


def _number(value) -> bool:
    """A number as JSON keeps it (null where it was NaN or infinite)."""
    return value is None or (isinstance(value, (int, float)) and not isinstance(value, bool))


def _whole(value) -> bool:
    return value is None or (isinstance(value, int) and not isinstance(value, bool))


def _mapping(value, item) -> bool:
    return isinstance(value, dict) and all(isinstance(key, str) and item(v) for key, v in value.items())


def _expect(ok: bool, field: str, what: str) -> None:
    if not ok:
        raise ValueError(f"its {field} is not {what}")

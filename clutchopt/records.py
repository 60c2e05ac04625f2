"""A batched sweep point's record in two parts: its own numbers (compact), and a template of what the points of its
window share (names, equations, units, bounds, the solver). ``expand(compact, template)`` is the point's
``Solution.as_dict()``.

A window's compact records are built from its arrays (``clutchopt.window_records``); the run store keeps the arrays,
and each template once (``templates``, by key), where every point used to repeat each constraint's equation and
description. A store of an older clutchopt keeps a batched point as its compact part, a row each (41 % of the full
record's bytes on the cable, 46 % on the wedge), read back by :func:`expand` as well. Pure Python: the store reads
records without importing the solvers.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict

TEMPLATE = "template"  # the key that marks a compact record, holding its template's key
STATUSES = ("optimal", "unverified", "infeasible", "not_found", "solver_failed")  # how a solve ends (infeasible: proven)
DESIGN_STATUSES = STATUSES[:2]  # a solve with these has a design to show (unverified: flagged)
CONSTRAINT_COLUMNS = ("value", "limit", "margin", "active", "feasible", "scale", "multiplier", "elasticity")
NOMINAL = "nominal"  # how a design was made without --robust; else worst-case or chance=P, as --robust spells it
UNRANKED = "not solved: "  # an integer search entry a start-up's first mesh left to the next (too coarse to rank
#                            it), why after it (clutchopt.optimise.problem.Problem._unranked)
RECORD_KEYS = ("coupling", "mode", "status", "objective", "design", "outputs", "units", "constraints", "solver",
               "diagnosis", "integer_search", "bounds", "sensitivities")  # a full record's, in :func:`expand`'s order
OBJECTIVE_KEYS = ("name", "value", "unit")
CONSTRAINT_KEYS = ("name", "equation", "sense", "value", "limit", "margin", "active", "feasible", "unit", "description",
                   "scale", "multiplier", "elasticity", "tolerance", "display_unit")
CONSTRAINT_STATICS = ("name", "equation", "sense", "unit", "description", "tolerance", "display_unit")  # a template's
SOLVER_STATICS = ("name", "status", "iterations")  # a template's; a point's own: time_s, solves
SOLVER_KEYS = (*SOLVER_STATICS, "time_s", "solves")



def lock_up_verdict(headline: dict) -> str:
    """A simulated start's lock-up in words: ``yes``, ``no`` or ``not decided`` (``locks_up`` None: the run stopped
    without a verdict), the one reading of the headline's three values."""
    return {True: "yes", False: "no"}.get(headline["locks_up"], "not decided")

def method_text(method: str, target: float | None) -> str:
    """A robust method as --robust spells it: ``worst-case``, ``chance=0.999``."""
    return method if target is None else f"{method}={target_text(target)}"


def target_text(target: float) -> str:
    """A chance target P as given: ``0.999999999`` (``:g`` wrote it 1, a probability no design holds with)."""
    return f"{target:.15g}"


def method_of(outputs) -> str | None:
    """How a stored design was made, read from its robust result where its run does not say (a store of an older
    clutchopt); None where nothing says."""
    robust = outputs.get("robust") if isinstance(outputs, dict) else None
    if not isinstance(robust, dict) or robust.get("method") not in ("worst-case", "chance", "system_chance"):
        return None
    target = robust.get("target")
    return method_text(robust["method"], target if isinstance(target, float) else None)


def design_inputs(case, values: dict[str, float], method: str = NOMINAL) -> dict:
    """A design's inputs as the store keeps them: the SI ``values`` it was solved for, the case's free variables
    and bounds, how it was designed (``method``) and, for a robust design, the case's scatter (SI)."""
    scatter = {"scatter": scatter_record(case)} if method != NOMINAL else {}
    return {"values": values, "free": list(case.free), "bounds": case.bounds, "method": method, **scatter}


def scatter_record(case) -> dict[str, dict]:
    """A case's scatter as the store keeps it: quantity -> kind, worst-case range, mean and sd (SI), and where it is
    correlated (``[scatter.correlation]``) ``correlation``: the other quantity -> rho of their normal scores."""
    record = {s.name: {k: v for k, v in asdict(s).items() if k != "name"} for s in case.scatter}
    for i, a in enumerate(case.scatter):
        for j, b in enumerate(case.scatter):
            if i != j and case.correlation is not None and case.correlation[i][j]:
                record[a.name].setdefault("correlation", {})[b.name] = case.correlation[i][j]
    return record


def template_key(template: dict) -> str:
    """A template's key: a hash of its canonical JSON (equal templates share one key; orjson's, 0.03 ms against the
    standard library's 0.4: an older clutchopt's templates keep their keys, a new one is stored beside them)."""
    import orjson

    return hashlib.sha256(orjson.dumps(template, option=orjson.OPT_SORT_KEYS)).hexdigest()[:32]


def is_keyed_by(template, key: str) -> bool:
    """Whether a template read back from the store is the one its key was made of (a body changed in place, still
    JSON of a template's shape: a unit, a name, an equation, is not): its key by :func:`template_key`, or by the
    standard library's JSON as an older clutchopt made it, which hashed an infinite bound as ``Infinity`` where the
    body holds null (the null put back as the infinity it stands for)."""
    if type(template) is not dict:
        return False
    for form in (template_key, _older_template_key):
        try:
            if key == form(template):
                return True
        except (TypeError, ValueError):  # (what orjson refuses: a whole number beyond 64 bits)
            pass
    bounds = template.get("bounds")
    if type(bounds) is not dict or not all(type(pair) is list and len(pair) == 2 for pair in bounds.values()):
        return False
    infinite = {name: [-math.inf if low is None else low, math.inf if high is None else high]
                for name, (low, high) in bounds.items()}
    return infinite != bounds and key == _older_template_key({**template, "bounds": infinite})


def _older_template_key(template: dict) -> str:
    """A template's key as an older clutchopt made it (the standard library's JSON)."""
    return hashlib.sha256(json.dumps(template, sort_keys=True, separators=(",", ":")).encode()).hexdigest()[:32]


def laid_out(record: dict) -> bool:
    """Whether a full record has exactly the keys, in their order, that :func:`expand` gives a compact record and
    its template (not so: a design's choice or robust result, a start-up's path, a record of an older clutchopt)."""
    return (tuple(record) == RECORD_KEYS and tuple(record["objective"]) == OBJECTIVE_KEYS
            and type(record["solver"]) is dict and tuple(record["solver"]) == SOLVER_KEYS
            and all(type(c) is dict and tuple(c) == CONSTRAINT_KEYS for c in record["constraints"]))


def template_of(record: dict) -> dict:
    """What :func:`expand` takes from a template, read from a full record (:func:`laid_out`): what the points of one
    formulation solved alike share (names, equations, units, bounds, the solver's name, status and iterations)."""
    objective, solver = record["objective"], record["solver"]
    return {"coupling": record["coupling"], "mode": record["mode"],
            "objective": {"name": objective["name"], "unit": objective["unit"]},
            "design": list(record["design"]), "outputs": list(record["outputs"]), "units": record["units"],
            "constraints": [{key: c[key] for key in CONSTRAINT_STATICS} for c in record["constraints"]],
            "solver": {key: solver[key] for key in SOLVER_STATICS}, "bounds": record["bounds"]}


def is_compact(record) -> bool:
    return isinstance(record, dict) and TEMPLATE in record


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
    the first field that does not. For records read from JSON (exact types; type sets compared, not values walked,
    so that an export of 20,000 cable points spends 10 us a point here)."""
    _expect(type(record) is dict, "the solution", "an object")
    _expect(record.get("status") in STATUSES, "status", "one of " + ", ".join(STATUSES))
    objective = record.get("objective")
    _expect(type(objective) is dict and type(objective.get("value")) in NUMBERS, "objective", "an object with a value")
    _expect(_by_name(record.get("design"), NUMBERS), "design", "numbers by name")
    for key in ("outputs", "sensitivities"):
        _expect(key not in record or _by_name(record[key], NUMBERS), key, "numbers by name")
    units = record.get("units", {})
    _expect(type(units) is dict and _types(units) <= TEXTS and all(_by_name(names, TEXTS) for names in units.values()),
            "units", "unit names by name")
    constraints = record.get("constraints")
    _expect(type(constraints) is list and all(map(_constraint, constraints)), "constraints",
            "a list of named constraints with numbers, flags and text")
    solver = record.get("solver")
    _expect(type(solver) is dict and type(solver.get("iterations")) in WHOLE
            and type(solver.get("time_s")) in NUMBERS, "solver", "an object with whole iterations and time_s")
    _expect(type(record.get("diagnosis")) in (str, type(None)), "diagnosis", "text")
    _expect(type(record.get("integer_search", [])) is list, "integer_search", "a list")
    _expect(type(record.get("bounds", {})) is dict, "bounds", "an object")
    return record


NUMBERS = frozenset({int, float, type(None)})  # as JSON keeps a number (null where it was NaN or infinite); no bool
WHOLE = frozenset({int, type(None)})
TEXTS = frozenset({str})
FLAGS = ("active", "feasible")
CONSTRAINT_NUMBERS = ("value", "limit", "margin", "scale", "multiplier", "elasticity", "tolerance")
CONSTRAINT_TEXTS = ("equation", "sense", "unit", "description", "display_unit")


def _constraint(item) -> bool:
    return (type(item) is dict and type(item.get("name")) is str
            and _types(map(item.get, FLAGS, (False,) * len(FLAGS))) <= {bool}
            and _types(map(item.get, CONSTRAINT_NUMBERS)) <= NUMBERS
            and _types(map(item.get, CONSTRAINT_TEXTS, ("",) * len(CONSTRAINT_TEXTS))) <= TEXTS)


def _by_name(value, kinds: frozenset) -> bool:
    """A JSON object of values of the types ``kinds``, by text keys."""
    return type(value) is dict and _types(value) <= TEXTS and _types(value.values()) <= kinds


def _types(values) -> set:
    return set(map(type, values))


def _expect(ok: bool, field: str, what: str) -> None:
    if not ok:
        raise ValueError(f"its {field} is not {what}")

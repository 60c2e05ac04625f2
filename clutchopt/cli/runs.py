"""``clutchopt runs list|show|export``: the run store.

Tables for a person: whole-number ids, the mode as the user asked for it, the objective with its unit, no
objective for a run without a design (infeasible; its diagnosis stays). ``export`` columns carry their SI unit
(``input.speed [rad/s]``, ``design.weight_mass [kg]``, one objective column per objective, ``mass [kg]``).
A damaged store: ``list`` and ``show`` refuse it in one line; ``export`` saves every run that can still be read.
"""

from __future__ import annotations

import math

from clutchopt.cli.options import LARGEST_ID, Checked, Parser, add_json_option, add_parser, path, whole_number
from clutchopt.errors import InputError

KINDS = ("solve", "sweep", "pareto", "simulation")
NO_DESIGN = ("infeasible", "not_found", "solver_failed")  # statuses whose objective value belongs to no design


def add_command(commands) -> None:
    runs = add_parser(
        commands, "runs", "list, show or export the runs recorded in the run store",
        "Every solve, sweep point, Pareto point and simulation is recorded (./clutchopt-runs.sqlite unless\n"
        "--store or $CLUTCHOPT_STORE says otherwise), with its inputs, outputs, status and versions.",
        ("clutchopt runs list", "clutchopt runs show 3", "clutchopt runs export -o runs.csv --kind sweep"))
    actions = runs.add_subparsers(dest="action", required=True, metavar="ACTION", parser_class=Parser)
    run_id = whole_number(1, LARGEST_ID)
    listing = actions.add_parser("list", help="recorded runs, newest first, and the sweeps")
    listing.add_argument("--kind", choices=KINDS, help="only runs of this kind")
    listing.add_argument("--sweep", action=Checked, check=run_id, metavar="ID",
                         help="only the points of sweep ID (clutchopt runs list shows the sweeps)")
    listing.add_argument("--limit", action=Checked, check=whole_number(0, LARGEST_ID), default=20,
                         help="show at most this many runs, newest first (default 20; 0: all)")
    add_json_option(listing)
    show = actions.add_parser("show", help="one run with its inputs, outputs and versions (JSON)")
    show.add_argument("id", action=Checked, check=run_id, help="the run's id, as runs list shows it")
    export = actions.add_parser("export", help="runs as a table (.csv, .parquet, .md): status, objective, SI inputs "
                                               "and design with their units, active constraints; from a damaged "
                                               "store, every run that can still be read")
    export.add_argument("-o", "--out", required=True, action=Checked, check=path, metavar="FILE",
                        help="the table to write: .csv, .parquet or .md")
    export.add_argument("--kind", choices=KINDS, help="only runs of this kind")
    export.add_argument("--sweep", action=Checked, check=run_id, metavar="ID", help="only the points of sweep ID")
    for action in (listing, show, export):
        action.add_argument("--store", action=Checked, check=path, metavar="PATH",
                            help="run store (default $CLUTCHOPT_STORE, then ./clutchopt-runs.sqlite)")
    runs.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.output import to_json, with_units
    from clutchopt.store import RunStore

    if args.action == "export":
        return export(args)
    with RunStore(args.store, writable=False) as store:
        if args.action == "show":
            return to_json(run_json(store.run(args.id)))
        listed, swept = store.runs(args.kind, args.sweep, args.limit or None), store.sweeps()
    _known_sweep(args.sweep, swept, store.path)
    if args.json:
        runs = [_objective_unit(_shown_run(run)) for run in listed]
        return to_json(with_units({"store": str(store.path), "runs": runs,
                                   "sweeps": swept}, {"runs": IDS, "sweeps": {**IDS, "points": "", "stored": ""}}))
    return listing_text(store.path, listed, swept if args.sweep is None else [])


def _shown_run(run: dict) -> dict:
    """A run as ``runs list --json`` and ``runs show`` give it: a sweep point without a design without an objective,
    design or outputs (:func:`~clutchopt.output.shown_point`), as the text listing and ``runs export`` give it
    (reviews 30, 31)."""
    from clutchopt.output import shown_point
    from clutchopt.records import DESIGN_STATUSES

    if run["kind"] != "sweep" or run["status"] in DESIGN_STATUSES:
        return run
    outputs = run.get("outputs")
    return {**run, "objective": None, **({"outputs": shown_point(outputs)} if isinstance(outputs, dict) else {})}


IDS = dict.fromkeys(("id", "sweep_id", "point"), "")  # a run's id, its sweep's and its point's index: no unit


def _objective_unit(run: dict) -> dict:
    from clutchopt.output import with_units

    return with_units(run, {"objective": run["objective_unit"] or ""})


def run_json(run: dict) -> dict:
    """A stored run with the unit of every number: its inputs by its coupling's quantities (a robust design's
    scatter too), its outputs as a solution's or a simulation's."""
    from clutchopt.output import CHECK_UNITS, HEADLINE_UNITS, SIMULATION_UNITS, solution_json, with_units
    from clutchopt.store import nested

    run = _shown_run(run)
    outputs = run["outputs"]
    if isinstance(outputs, dict) and isinstance(outputs.get("objective"), dict):
        outputs = solution_json(outputs)
    elif isinstance(outputs, dict):
        outputs = with_units(outputs, {**SIMULATION_UNITS, **CHECK_UNITS})
    units = _input_units(run["coupling"])
    scattered = nested(run["inputs"], "scatter")
    scattered = scattered if isinstance(scattered, dict) else {}
    inputs = {"values": units, "bounds": units, "design": units, "source": HEADLINE_UNITS["source"],
              "scatter": {name: dict.fromkeys(SCATTER_NUMBERS, units.get(name, "")) for name in scattered}}
    return with_units({**_objective_unit(run), "outputs": outputs}, {**IDS, "inputs": inputs})


SCATTER_NUMBERS = ("low", "high", "mean", "sd")  # of a scattered quantity as the store keeps it, in its SI unit


def listing_text(path: str, listed: list[dict], swept: list[dict]) -> str:
    import pandas as pd

    from clutchopt.store import shown_mode

    rows = [{"id": run["id"], "kind": run["kind"], "sweep": _whole(run["sweep_id"]), "point": _whole(run["point"]),
             "created (UTC)": _created(run["created"]), "coupling": run["coupling"] or "-",
             "mode": shown_mode(run["mode"]) or "-", "method": run["method"] or "-", "status": run["status"] or "-",
             "objective": _objective(run),
             "case": run["case_path"] or "-"} for run in listed]
    lines = [f"Runs in {path} (newest first)", pd.DataFrame(rows).to_string(index=False) if rows else "(none)"]
    if swept:
        sweeps = [{"sweep": s["id"], "created (UTC)": _created(s["created"]), "case": s["case_path"] or "-",
                   "coupling": s["coupling"], "mode": shown_mode(s["mode"]), "objective": s["objective"],
                   "points": s["points"], "stored": s["stored"]} for s in swept]
        lines += ["", "Sweeps", pd.DataFrame(sweeps).to_string(index=False)]
    return "\n".join(lines)


def _whole(value) -> str:
    return "-" if value is None else str(int(value))


def _created(stamp: str | None) -> str:
    return (stamp or "-")[:19].replace("T", " ")


def _objective(run: dict) -> str:
    """``mass 0.282095 kg``; ``-`` where the run has no design (its objective value would mean nothing)."""
    value = run["objective"]
    if value is None or not math.isfinite(value) or run["status"] in NO_DESIGN:
        return "-"
    return f"{run['objective_name']} {value:.6g} {run['objective_unit'] or ''}".rstrip()


def _known_sweep(sweep_id: int | None, swept: list[dict], path) -> None:
    """Refuse ``--sweep`` naming a sweep the store does not hold (its points would read as none: review 25)."""
    if sweep_id is not None and all(sweep["id"] != sweep_id for sweep in swept):
        raise InputError("--sweep", f"no sweep {sweep_id} in {path} (clutchopt runs list shows the sweeps)")


def export(args) -> str:
    import pandas as pd

    from clutchopt.optimise.sweep_table import table_format, write_frame
    from clutchopt.store import RunStore, StoreError

    table_format(args.out)
    with RunStore(args.store, writable=False, check=False) as store:
        entries, lost, open_end = store.readable_runs(args.kind, args.sweep)
        if args.sweep is not None and not entries:  # (no point of it could be read: a sweep the store names?)
            try:
                _known_sweep(args.sweep, store.sweeps(), store.path)
            except StoreError:  # (its sweeps unreadable too: the empty table is what can be rescued)
                pass
    frame = pd.DataFrame([export_row(entry) for entry in entries])
    for column in ("sweep", "point"):  # whole numbers, blank for a run that is no sweep point
        if column in frame:
            frame[column] = frame[column].astype("Int64")
    write_frame(frame, args.out)
    text = f"{len(frame)} runs written to {args.out}"
    if lost:
        text += f"; {lost} damaged runs could not be read from {store.path}"
    if open_end is not None:
        text += f"; nothing after run {open_end} could be read (a damaged page: runs after it may be lost)"
    return text


def export_row(entry: dict) -> dict:
    """One run as a flat row, every quantity's column named with its SI unit; how it was designed (``method``,
    ``scatter``)."""
    from clutchopt.store import nested, shown_mode

    outputs = entry["outputs"] if isinstance(entry["outputs"], dict) else {}
    designed = entry["status"] not in NO_DESIGN
    units = _input_units(entry["coupling"])
    row = {"id": entry["id"], "kind": entry["kind"], "sweep": entry["sweep_id"], "point": entry["point"],
           "created": entry["created"], "coupling": entry["coupling"], "mode": shown_mode(entry["mode"]),
           "method": entry.get("method") or "", "scatter": _scatter_text(nested(entry["inputs"], "scatter"), units),
           "status": entry["status"], "case": entry["case_path"], "title": entry["title"]}
    unit = entry.get("objective_unit") or nested(outputs, "objective", "unit") or ("s" if entry["kind"] ==
                                                                                    "simulation" else "")
    if entry["objective_name"]:
        value = entry["objective"]
        row[_column(entry["objective_name"], unit)] = value if designed and value is not None else None
    inputs = entry["inputs"].get("values", {}) if isinstance(entry["inputs"], dict) else {}
    row.update({_column(f"input.{name}", units.get(name, "")): value for name, value in inputs.items()})
    design_units = nested(outputs, "units", "design") or {}
    for name, value in (outputs.get("design") or {}).items():
        row[_column(f"design.{name}", design_units.get(name) or units.get(name, ""))] = value if designed else None
    row["active"] = " ".join(c.get("name", "") for c in outputs.get("constraints") or []
                             if isinstance(c, dict) and c.get("active")) if designed else ""
    row["diagnosis"] = outputs.get("diagnosis") or ""
    # how it was designed beside method and scatter (review 30: a choice, a start-up or a robust verification could
    # not be told from the export): the choice kept, the simulated start, what the robust design's check found
    choice = outputs.get("choice")
    row["choice"] = ", ".join(f"{role} = {name}" for role, name in choice.items()) if isinstance(choice, dict) else ""
    start = outputs.get("start_up")
    row["start_up.start_time_simulated [s]"] = (start.get("start_time_simulated") if isinstance(start, dict)
                                                and designed else None)
    robust = outputs.get("robust")
    row["robust verification"] = (robust.get("verification") or "") if isinstance(robust, dict) else ""
    return row


def _scatter_text(scatter, units: dict[str, str]) -> str:
    """A robust design's scatter as one cell: ``friction_coefficient range 0.12 to 0.18; inertia normal, mean 12
    kg*m^2, sd 0.6 kg*m^2`` (SI); a stored entry of another shape as it is."""
    from clutchopt.scatter import Scatter

    if not isinstance(scatter, dict):
        return ""
    parts = []
    for name, item in scatter.items():
        try:
            unit = "" if units.get(name) in (None, "1") else units[name]  # "1": a ratio
            parts.append(f"{name} " + Scatter(name, **item).describe(lambda v: f"{v:g} {unit}".rstrip()))
        except (TypeError, ValueError):  # a damaged or foreign entry
            parts.append(f"{name} {item}")
    return "; ".join(parts)


def _column(name: str, unit: str) -> str:
    return f"{name} [{unit}]" if unit and unit != "1" else name


_UNITS: dict[str, dict[str, str]] = {}


def _input_units(coupling: str | None) -> dict[str, str]:
    """SI unit of each quantity and design variable of a coupling, of a start-up's quantities and of a Pareto
    point's cost cap."""
    from clutchopt.errors import InputError
    from clutchopt.formulations import get_coupling
    from clutchopt.start_up.equations import QUANTITIES, SPRING_PRELOAD
    from clutchopt.optimise.pareto import CAP
    from clutchopt.units import si_unit

    if coupling not in _UNITS:
        try:
            declared = get_coupling(coupling)
        except InputError:  # a simulation (no coupling), or a store of a newer clutchopt
            _UNITS[coupling] = {}
        else:
            _UNITS[coupling] = {q.name: q.si_unit for q in (*declared.quantities, *declared.variables, *QUANTITIES,
                                                            SPRING_PRELOAD)}
            objectives = {o.name: o for f in declared.formulations.values() for o in f.objectives}
            if "cost" in objectives:
                _UNITS[coupling][CAP] = si_unit(objectives["cost"].unit)
    return _UNITS[coupling]

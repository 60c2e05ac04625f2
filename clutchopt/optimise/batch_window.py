"""A window of a batched sweep's points: their arrays checked in float64 together, and the window's solutions.

The batched points (``clutchopt.optimise.batch``) are re-evaluated by the formulation's own equations (constraints,
objective; ``verify``'s arithmetic), vectorised over the points. A window's table rows (``Solutions.table``) and
records (each point's ``Solution.as_dict()``, as arrays as the run store keeps them: ``Solutions.stored``) are built
together when asked for, from the window's arrays; a point's :class:`Solution` is built from its record when the
point is read.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from clutchopt.model import Output, namespace
from clutchopt.optimise.posed import Posed
from clutchopt.optimise.sensitivity import limit_elasticities, sense_sign, sensitivity_table
from clutchopt.optimise.solution import Solution, SolverInfo
from clutchopt.optimise.table import active_names, placed, solution_table
from clutchopt.optimise.verify import FEASIBILITY_TOL, ConstraintCheck, column_figures, column_outputs, margin_flags
from clutchopt.records import STATUSES
from clutchopt.window_records import KINDS, WindowRecords, gathered_solutions, in_order
from clutchopt.units import si_unit

BATCHED = "batched, KKT verified"  # a batched point's solver status
UNVERIFIED = "SQP reported a KKT point but the float64 check finds a constraint violated"


class Block:
    """Batched points, one column each: the solver's primal-dual points, their steps from the point before (the
    predictor's, see ``chain.chained_sqp``) and scaled objectives, the NLP parameters and bounds, each point's
    share of its batch's time and its solver calls."""

    KEYS = ("x", "lam_x", "lam_g", "dx", "dlam_x", "dlam_g", "f", "p", "lbx", "ubx", "time", "solves")

    def __init__(self, index: np.ndarray, **arrays: np.ndarray):
        self.index, self.arrays = index, arrays

    def block(self, passed: int, begin: int = 0) -> "Block":
        """The first ``passed`` points (from ``begin``), views of these arrays."""
        return Block(self.index[begin:passed], **{key: value[:, begin:passed] for key, value in self.arrays.items()})

    @classmethod
    def joined(cls, blocks: list["Block"]) -> "Block":
        return cls(np.concatenate([b.index for b in blocks]),
                   **{key: np.concatenate([b.arrays[key] for b in blocks], axis=-1) for key in cls.KEYS})


class Solutions(Sequence):
    """A window's solutions in point order, each batched point built as a :class:`Solution` when first read."""

    def __init__(self, first: int, count: int, alone: dict[int, Solution], checked: "Checked | None",
                 names: list[str]):
        self._solutions = {k - first: solution for k, solution in alone.items()}  # by position in the window
        self._records: dict[int, dict] = {}  # the points solved alone's as_dict(), built once (held, records)
        self._names = names  # the design variables
        self._checked, self._column = checked, np.full(count, -1)
        if checked is not None:
            self._column[checked.block.index - first] = np.arange(len(checked.block.index))
        self.unverified = [] if checked is None else checked.block.index[~checked.feasible].tolist()

    def __len__(self) -> int:
        return len(self._column)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        i = range(len(self))[i]
        if i not in self._solutions:
            self._solutions[i] = self._checked[int(self._column[i])]
        return self._solutions[i]

    def replace(self, i: int, solution: Solution) -> None:
        self._solutions[i] = solution
        self._records.pop(i, None)

    def _record(self, i: int) -> dict:
        """The point ``i`` solved alone's ``Solution.as_dict()``, built once."""
        if i not in self._records:
            self._records[i] = self._solutions[i].as_dict()
        return self._records[i]

    def records(self) -> list[dict]:
        """Every point's ``Solution.as_dict()``, those of the batched points built together from the window's arrays
        (no Solution objects)."""
        return in_order(len(self), *self.held())

    def held(self) -> tuple[dict[int, dict], list[tuple[np.ndarray, WindowRecords]]]:
        """Each point solved alone's ``Solution.as_dict()`` by position, and the batched points' records as arrays
        (``clutchopt.window_records``) with their positions."""
        return {i: self._record(i) for i in sorted(self._solutions)}, self._batched()

    def stored(self) -> tuple[dict[int, dict], list[tuple[np.ndarray, WindowRecords]]]:
        """The records as the run store keeps them: :meth:`held`, but the points solved alone one after another that
        share a template (a region proof's points without a design) as arrays too, read from their Solutions without
        building their records (``window_records.gathered_solutions``: what the store's ``gathered`` makes of the
        records)."""
        alone, gathered = gathered_solutions(dict(sorted(self._solutions.items())))
        return {i: self._record(i) for i in alone}, gathered + self._batched()

    def _batched(self) -> list[tuple[np.ndarray, WindowRecords]]:
        """The batched points' records as arrays with their positions (none, or one window's)."""
        batched = np.flatnonzero(self._column >= 0)
        batched = batched[np.isin(batched, list(self._solutions), invert=True)]
        if not len(batched):
            return []
        columns = self._column[batched]
        whole = len(columns) == len(self._checked.block.index) and (columns == np.arange(len(columns))).all()
        return [(batched, self._checked.window_records(None if whole else columns))]

    def table(self) -> dict[str, np.ndarray]:
        """Every point's row of a sweep table (``clutchopt.optimise.table``), those of the batched points read from
        the window's arrays, those solved alone from their Solutions, without building any record."""
        names = self._names
        if self._checked is None:
            return solution_table([self._solutions[i] for i in range(len(self))], names)
        table = {key: column[..., self._column] for key, column in self._checked.table().items()}  # copies
        alone = sorted(self._solutions)
        if alone:
            placed(solution_table([self._solutions[i] for i in alone], names), alone, table)
        return table

    @property
    def statuses(self) -> list[str]:
        """Each point's status, without building the Solutions of batched points (optimal unless one failed its
        float64 check and was solved again)."""
        statuses = ["optimal"] * len(self)
        for i, solution in self._solutions.items():
            statuses[i] = solution.status
        return statuses


class Checked:
    """Batched points checked in float64 at once by the formulation's own equations (constraints, objective), one
    column per point; their outputs and Solutions are built when read."""

    def __init__(self, posed: Posed, block: Block, values: np.ndarray, bounds: tuple[np.ndarray, np.ndarray],
                 searches: dict[int, list[dict]]):
        f = posed.formulation
        self.posed, self.block, a = posed, block, block.arrays
        self.bounds, self.searches = bounds, searches  # the sweep's box (SI); the integer searches by point
        m, n, count = len(f.quantities), len(posed.names), len(block.index)
        self.design = a["x"][:n] * a["p"][m:m + n]
        self.design[posed.integer] = np.round(self.design[posed.integer])
        self.x = namespace(dict(zip(posed.names, self.design)))
        self.params = namespace({q.name: row for q, row in zip(f.quantities, values)})
        self.constraints, (self.value, self.limit, self.scale, self.margin), self.objective = column_figures(
            f, posed.objective, self.x, self.params, count)
        self.feasible = np.all(self.margin >= -FEASIBILITY_TOL, axis=0)
        self._outputs = None

    @property
    def outputs(self) -> dict[str, tuple[np.ndarray, Output]]:
        """The derived quantities of every point (evaluated together when a first point is read)."""
        if self._outputs is None:
            self._outputs = column_outputs(self.posed.formulation, self.x, self.params, len(self.block.index))
        return self._outputs

    def verdicts(self) -> tuple[np.ndarray, np.ndarray]:
        """Each point's status and diagnosis by the float64 check: optimal, or unverified with its diagnosis."""
        ok = self.feasible.astype(int)
        return np.array(["unverified", "optimal"], dtype=object)[ok], np.array([UNVERIFIED, None], dtype=object)[ok]

    def table(self) -> dict[str, np.ndarray]:
        """Every point's row of a sweep table (``clutchopt.optimise.table``), from the arrays: statuses and
        diagnoses by the float64 check, the names of the active constraints joined once per pattern."""
        (status, diagnosis), (active, _) = self.verdicts(), margin_flags(self.margin, FEASIBILITY_TOL)
        return {"status": status, "objective": self.objective, "design": self.design,
                "active": active_names(active, [c.name for c in self.constraints]), "diagnosis": diagnosis,
                "iterations": np.full(len(self.block.index), None)}

    def window_records(self, columns: np.ndarray | None = None) -> WindowRecords:
        """Every point's record (of the points ``columns`` only, if given) as arrays (``clutchopt.window_records``):
        the template the points share and their numbers, a column per point."""
        posed, f, names = self.posed, self.posed.formulation, self.posed.names
        cols = slice(None) if columns is None else np.asarray(columns, dtype=int)
        a = {key: value[:, cols] for key, value in self.block.arrays.items()}
        value, limit, margin, scale = (table[:, cols] for table in (self.value, self.limit, self.margin, self.scale))
        objective, feasible, index = self.objective[cols], self.feasible[cols], self.block.index[cols]
        m, n, n_c = len(f.quantities), len(names), len(self.constraints)
        with np.errstate(invalid="ignore", divide="ignore"):
            sign = np.array([sense_sign(c.sense) for c in self.constraints])[:, None]
            lam = a["lam_g"][:n_c]
            elasticity = limit_elasticities(sign, lam, a["p"][m + n], limit, scale, objective)
        active, fits = margin_flags(margin, FEASIBILITY_TOL)
        outputs = self.outputs
        out_values = np.empty((len(outputs), len(objective)))
        for row, (values, _) in zip(out_values, outputs.values()):
            row[:] = values[cols]
        template = {
            "coupling": f.coupling, "mode": f.mode,
            "objective": {"name": posed.objective.name, "unit": posed.objective.unit},
            "design": list(names), "outputs": list(outputs),
            "units": {"design": {v.name: si_unit(v.unit) for v in f.variables},
                      "outputs": {name: si_unit(out.unit) for name, (_, out) in outputs.items()}},
            "constraints": [{"name": c.name, "equation": c.equation, "sense": c.sense, "unit": si_unit(c.unit),
                             "description": c.description, "tolerance": FEASIBILITY_TOL, "display_unit": c.unit}
                            for c in self.constraints],
            "solver": {"name": "sqpmethod", "status": BATCHED, "iterations": None},
            "bounds": {name: [float(lo), float(hi)] for name, lo, hi in zip(names, *self.bounds)},
        }
        sensitivity_names, sensitivity, sensitive = sensitivity_table(
            posed, *(a[key] for key in ("x", "p", "lam_x", "lam_g", "lbx", "ubx")),
            np.where(feasible, objective, np.nan), window=True)
        found = sorted(set(self.searches) & set(index.tolist())) if self.searches else []  # points that ran one
        searches = dict(zip(np.searchsorted(index, found).astype(str).tolist(), map(self.searches.get, found)))
        arrays = {"status": np.where(feasible, STATUSES.index("optimal"), STATUSES.index("unverified")),
                  "diagnosis": np.where(feasible, -1, 0), "objective": objective,
                  "time_s": a["time"][0], "solves": a["solves"][0],
                  "priced": (objective != 0) & np.isfinite(objective),
                  "design": self.design[:, cols], "outputs": out_values,
                  "value": value, "limit": limit, "margin": margin, "active": active, "feasible": fits, "scale": scale,
                  "multiplier": lam, "elasticity": elasticity, "sensitivity": sensitivity, "sensitive": sensitive}
        labels = {"diagnoses": [UNVERIFIED], "sensitivities": sensitivity_names, "integer_search": searches}
        return WindowRecords(template, {name: np.ascontiguousarray(array, dtype=KINDS[name][0])
                                        for name, array in arrays.items()}, labels)

    def records(self, columns: np.ndarray | None = None) -> list[dict]:
        """Every point's ``Solution.as_dict()`` (of the points ``columns`` only, if given)."""
        return self.window_records(columns).records()

    def __getitem__(self, j: int) -> Solution:
        """Point ``j`` as the Solution ``Problem.solve`` returns (its record as objects, the display units of its
        outputs and constraints, its scales and multipliers for warm starts)."""
        record, f = self.records([j])[0], self.posed.formulation
        m, n = len(f.quantities), len(self.posed.names)
        a = {key: value[:, j] for key, value in self.block.arrays.items()}
        checks = [ConstraintCheck(**{key: value for key, value in c.items() if key != "display_unit"}
                                  | {"unit": c["display_unit"]}) for c in record["constraints"]]
        outputs = {name: Output(value, out.unit, out.description)
                   for (name, value), (_, out) in zip(record["outputs"].items(), self.outputs.values())}
        return Solution(
            record["coupling"], record["mode"], record["objective"]["name"], record["objective"]["unit"],
            record["status"], record["objective"]["value"], record["design"], outputs, checks,
            SolverInfo(**record["solver"]), record["diagnosis"], record["integer_search"],
            {name: tuple(pair) for name, pair in record["bounds"].items()}, record["sensitivities"],
            a["p"][m:m + n].copy(), (a["lam_x"].copy(), a["lam_g"].copy()), {v.name: v.unit for v in f.variables})

"""The limits a start-up's last NLP solved with, as a share of the case's, carried to a neighbouring design.

The defect correction (:func:`~clutchopt.optimise.start_up_check.corrected_case`) moves a start-up limit by what the
simulated start adds to the collocation's figure: the NLP of ``wedge_motor_start`` sees max_start_time 10 s less
2.4e-7 of it. Along a sweep that gap changes little from one point to the next, so the point before's moved limits,
as ratios to its case's, start the next point's loop: its first solve then meets the limit as the simulator sees it
and the correction is not solved again. The simulated start still decides, as for every solve: where the carried
ratio leaves the limit off by more than the correction tolerates, the loop corrects it from there.
"""

from __future__ import annotations

import math
from dataclasses import replace

from clutchopt.cases import Case


def limit_shift(case: Case, nlp_case: Case) -> dict[str, float]:
    """Each value the NLP solved with that the defect correction moved off the case's: name -> NLP's / case's."""
    return {name: value / case.values[name] for name, value in nlp_case.values.items()
            if name in case.values and value != case.values[name] and _ratio_defined(case.values[name])}


def shifted(case: Case, shift: dict[str, float] | None) -> Case:
    """``case`` with its limits moved by ``shift`` (:func:`limit_shift` of a neighbouring design), those it has."""
    moved = {name: case.values[name] * ratio for name, ratio in (shift or {}).items()
             if name in case.values and _ratio_defined(case.values[name])}
    if not moved:
        return case
    declared = {q.name for q in case.quantities}  # a robust design's corners are NLP parameters, not quantities
    limits = case.with_values(**{name: value for name, value in moved.items() if name in declared})
    return replace(limits, values={**limits.values, **{n: v for n, v in moved.items() if n not in declared}})


def _ratio_defined(value) -> bool:
    return isinstance(value, (int, float)) and math.isfinite(value) and value != 0

"""The independent check's own error against a reference (docs/start_up.md, "The check's tolerance"): at the
loosest rtol the case's tolerance allows (``accuracy_rtol``; the check takes no looser, ``check_rtol``), every
simulated figure the start-up constraints use is within CHECK_MARGIN (a hundredth) of that tolerance of the same start integrated by another method at rtol 1e-13,
on the four ``*_motor_start`` cases at their optimum and at a design 3 % lighter (every continuous variable x 0.97).

The reference: Radau IIA (implicit, L-stable, order 5) for a slipping coupling, whose motor makes the start stiff;
DOP853 for the cable's elastic link (not stiff there: 900 steps). At 1e-13 the two references agree with each other
to 1e-12 on every figure (measured), so what the test sees is the check's error, not the reference's."""

import math
from dataclasses import replace

import pytest

import clutchopt.simulate.elastic as elastic
import clutchopt.simulate.engine as engine
from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.problem import case_formulation
from clutchopt.start_up.drive import Structure
from clutchopt.start_up.simulation import (CHECK_MARGIN, MESH_RTOL, accuracy_rtol, check_rtol, run_start_up,
                                           start_up_model, worn_start_up_model)
from tests.conftest import CASES

FIGURES = ("start_time", "friction_work", "temperature_rise", "lock_up_speed", "peak_stress")
REFERENCE_RTOL = 1e-13


def _figures(result) -> dict:
    return {name: result.headline[name] for name in FIGURES if name in result.headline}


@pytest.mark.parametrize("name", ["wedge", "lever", "ball", "cable"])
def test_the_check_is_within_a_hundredth_of_the_tolerance(name, monkeypatch):
    monkeypatch.setattr(engine, "MAX_STEPS", 200_000)  # the reference's steps (Radau: 3,000-4,000)
    monkeypatch.setattr(elastic, "MAX_STEPS", 200_000)
    case = load_case(CASES / f"{name}_motor_start.toml")
    structure = Structure.of(case)
    tolerance = structure.spec.tolerance
    assert tolerance == 1e-6  # the cases' contract: the default
    rtol = accuracy_rtol(tolerance, structure.elastic)  # the loosest the contract allows: tested at it
    assert rtol == pytest.approx(1e-11 if structure.elastic else 1e-9, rel=1e-12)  # 1e-2 x 1e-6 / 1000 or / 10
    assert check_rtol(tolerance, structure.elastic) == (rtol if structure.elastic else MESH_RTOL)  # no looser
    solution = solve_case(case)
    integers = {v.name for v in case_formulation(case).variables if v.integer}
    lighter = {k: v if k in integers else 0.97 * v for k, v in solution.design.items()}
    for design in (solution.design, lighter):
        model = start_up_model(case, solution.mode, design, rtol)
        models = [model] + [m for m in [worn_start_up_model(case, solution.mode, design, model)] if m is not None]
        for checked in models:
            method = "DOP853" if structure.elastic else "Radau"
            reference = _figures(run_start_up(replace(checked, rtol=REFERENCE_RTOL, integrator=method)))
            figures = _figures(run_start_up(checked))
            assert reference.keys() == figures.keys() and len(reference) >= 4
            for figure, value in reference.items():
                assert math.isfinite(value) and value > 0
                error = abs(figures[figure] - value) / value
                assert error <= CHECK_MARGIN * tolerance, (figure, error, design)


def test_a_tighter_contract_tightens_the_check():
    """rtol = CHECK_MARGIN x tolerance / ERROR_PER_RTOL, held within the measured range 1e-12..1e-6; a slipping
    start's check no looser than MESH_RTOL (its samples adapt the mesh)."""
    assert accuracy_rtol(1e-4, False) == pytest.approx(1e-7, rel=1e-12)
    assert accuracy_rtol(1e-8, True) == 1e-12  # 1e-13 wanted: the range's floor
    assert accuracy_rtol(1e-2, False) == 1e-6  # 1e-5 wanted: the loosest rtol measured
    assert check_rtol(1e-4, False) == MESH_RTOL and check_rtol(1e-4, True) == pytest.approx(1e-9, rel=1e-12)
    assert check_rtol(1e-9, False) == pytest.approx(1e-12, rel=1e-12)  # 1e-12 wanted by the contract: tighter than MESH_RTOL

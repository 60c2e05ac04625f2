"""A start-up sweep's point deeper into a run of points without a design has ``solve``'s verdict and design, and a
resumed sweep the uninterrupted one's (clutchopt.optimise.sweep._solved, clutchopt.optimise.sampled_start).

ball_motor_start in paper mode at a contact stress of 1.5 GPa, listed over its power: 507.9 kW (480.455 kg, from the
papers' sizing), 900 kW (no design: ``solve`` alone not_found too) and 605.7 kW, where ``solve`` alone reaches
554.6854 kg only from the least violated sampled design (tests/test_hostile_agree2.py). The third point is deeper
than the first past a design: it followed its neighbour's design (the first point's: its retry, its continuation in
three steps lose the design at the last) and was ``not_found``, the sampled start left to the first point past a
design; a resume after the first point started the third point alone and found the design.
"""

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.sampled_start import SAMPLED
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.store import RunStore
from conftest import BALL_PAPER_STRESS, CASES, Interrupted, resumed_sweep, stopped_sweep
from test_hostile_agree import START_UP_RTOL

POWERS = (507916.19236376183, 900e3, 605693.4230086812)


def _sweep() -> Sweep:
    case = load_case(CASES / "ball_motor_start.toml").with_values(**BALL_PAPER_STRESS)
    quantity = next(q for q in case.quantities if q.name == "power")
    return Sweep(case, [Vary(quantity, POWERS)], mode="paper")


@pytest.fixture(scope="module")
def uninterrupted() -> list[dict]:
    return _sweep().run(progress=False).solutions


def test_a_point_deeper_than_the_first_past_a_design_is_retried_from_the_sampled_design(uninterrupted):
    first, between, deeper = uninterrupted
    assert first["status"] == "optimal"
    assert first["objective"]["value"] == pytest.approx(480.45534, rel=START_UP_RTOL)
    assert between["status"] == "not_found"  # (solve alone: not_found, its sampled start tried too)
    assert SAMPLED in between["starts"]
    assert deeper["status"] == "optimal"  # was not_found, its starts the sizing's, the relaxation's, the neighbour's
    assert deeper["objective"]["value"] == pytest.approx(554.6854, rel=START_UP_RTOL)  # solve's alone
    assert {c["name"] for c in deeper["constraints"] if c["active"]} == {"torque", "start_time"}


def test_a_sweep_resumed_after_its_first_point_has_the_uninterrupted_verdicts_and_designs(uninterrupted, tmp_path,
                                                                                         monkeypatch):
    original = RunStore.record_points

    def once(*args, **kwargs):  # the first point stored (a point with a design is stored as it is solved)
        original(*args, **kwargs)
        raise Interrupted

    resumed = resumed_sweep(stopped_sweep(tmp_path / "runs.sqlite", _sweep, monkeypatch, RunStore, "record_points",
                                          once), _sweep)
    assert (resumed.reused, resumed.solved) == (1, 2)
    assert [r["status"] for r in resumed.solutions] == [r["status"] for r in uninterrupted] \
        == ["optimal", "not_found", "optimal"]
    for again, once_run in zip(resumed.solutions, uninterrupted):
        if again["status"] == "optimal":
            assert again["objective"]["value"] == pytest.approx(once_run["objective"]["value"], rel=START_UP_RTOL)
            assert again["design"] == pytest.approx(once_run["design"], rel=START_UP_RTOL)

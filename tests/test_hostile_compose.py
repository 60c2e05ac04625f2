"""Commands that compose, against `solve` of the same point (a third hostile pass): pareto, choose-coupling,
compare, report, robust designs, options.choose, --json against the table, the overload, heat and life figures. The
hunt is /tmp/hostile/*.py (described in the branch's report); each test here is one finding's minimal repro, fixed
or a strict xfail naming its cause."""

import math

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from conftest import CASES


@pytest.mark.xfail(strict=True, reason="paper mode poses the paper's geometry as given and checks no flank angle: the "
                   "wedge's release condition alpha >= atan f + margin (above eq. 24) is a constraint of geometry mode "
                   "only (formulations/wedge/modes.py, _constructive_constraints), and no case check refuses a fixed "
                   "self-locking flank angle as the cable's check_threads refuses a self-locking thread (errata C8); "
                   "options.choose in paper mode then ranks a self-locking pair best")
def test_a_self_locking_wedge_is_not_optimal_in_paper_mode_when_geometry_mode_proves_it_infeasible():
    # wedge_paper.toml at f = 0.3 (organic_dry, sintered_bronze_dry of the library): the flank half-angle 15 deg is
    # below atan(0.3) + 2 deg = 16.70 + 2 = 18.70 deg (above eq. 24): the weights wedge in the groove and do not
    # release. Geometry mode, with the same fixed flank angle, proves it (not_self_locking, 1 box); paper mode called
    # the self-locking coupling optimal (0.35420 kg), and with options.choose = { friction_pair = [steel_steel_dry,
    # steel_steel_oiled, sintered_bronze_dry] } ranked sintered_bronze_dry (f 0.3) best, 0.20197 kg.
    case = load_case(CASES / "wedge_paper.toml").with_values(friction_coefficient=0.3)
    assert math.degrees(case.values["flank_angle"]) == pytest.approx(15.0)
    assert math.degrees(math.atan(0.3)) + 2.0 == pytest.approx(18.699244, abs=1e-6)
    geometry = solve_case(case, "geometry")
    assert geometry.status == "infeasible" and "not_self_locking" in geometry.diagnosis
    assert solve_case(case, "paper").status != "optimal"

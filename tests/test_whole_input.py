"""Inputs checked as a whole: every bad field of a case in one run, nested [start_up] and [scatter] sections
included, and nothing required that the chosen objective does not use (issue 23, point 5)."""

from pathlib import Path

import pytest

from clutchopt.cases import load_case
from clutchopt.cli import EXIT_BAD_INPUT, main
from clutchopt.errors import InputError

CASES = Path(__file__).resolve().parents[1] / "cases"
MOTOR = (CASES / "wedge_motor_start.toml").read_text()
CABLE_MOTOR = (CASES / "cable_motor_start.toml").read_text()
BALL = (CASES / "ball_crusher.toml").read_text()
NO_PRICES = BALL.replace('[cost]\nball_price = "2.5 EUR/kg"\nbody_price = "6 EUR/kg"\n', "")


def edit(text: str, *pairs: tuple[str, str]) -> str:
    for old, new in pairs:
        assert old in text, old  # each edit must change the case, or the test would test nothing
        text = text.replace(old, new, 1)
    return text


def errors(tmp_path, capsys, text: str, *argv: str) -> list[str]:
    """The error lines of a command on the case ``text``, which must refuse it as bad input (exit code 2)."""
    path = tmp_path / "case.toml"
    path.write_text(text)
    assert main([argv[0] if argv else "solve", str(path), "--no-store", *argv[1:]]) == EXIT_BAD_INPUT
    out, err = capsys.readouterr()
    lines = err.splitlines()
    assert out == "" and lines and all(line.startswith("error: ") for line in lines), err
    assert "Traceback" not in err
    return lines


def fields(lines: list[str]) -> list[str]:
    return [line.split(": ")[1] for line in lines]


DRIVER = ('synchronous_speed = "1000 rpm"', 'synchronous_speed = "50 Hz"\nrated_voltage = "400 V"\npole_pairs = 3')


def test_every_bad_field_of_the_driver_in_one_run(tmp_path, capsys):
    lines = errors(tmp_path, capsys, edit(MOTOR, DRIVER, ("breakdown_slip = 0.2", "breakdown_slip = 7")))
    assert fields(lines) == ["start_up.driver.synchronous_speed", "start_up.driver.rated_voltage",
                             "start_up.driver.pole_pairs", "start_up.driver.breakdown_slip"], lines
    assert "Hz and 1/s are refused" in lines[0] and "must be < 1, got 7" in lines[3]


def test_duty_start_up_and_scatter_reported_together(tmp_path, capsys):
    text = edit(MOTOR, DRIVER, ('speed = "1000 rpm"', 'speed = "-3 rpm"'),
                ('inertia = "0.5 kg*m^2"', 'inertia = "lots"'),
                ("[start_up.heat]", "[start_up.heat]\nmass = 3"), ("[options]", "[start_up.colour]\n\n[options]"))
    text += '\n[scatter]\nfriction_coefficient = [0.12, 0.1]\ninertia = [0.4, 0.6]\nbreakdown_slip = [0.1, 0.3]\n'
    lines = errors(tmp_path, capsys, text)
    assert fields(lines) == ["duty.inertia", "duty.speed", "start_up.colour", "start_up.driver.synchronous_speed",
                             "start_up.driver.rated_voltage", "start_up.driver.pole_pairs", "start_up.heat.mass",
                             "scatter.friction_coefficient"], lines
    # the start-up's driven inertia follows the broken duty.inertia: no second message for it; neither is the
    # scatter of a quantity whose own value is bad checked against that value
    assert not any("missing" in line or "scatter around" in line for line in lines), lines


HOSTILE = [
    ("driver.breakdown_torque", 'breakdown_torque = "37 N*m"', 'breakdown_torque = "1e300 N*m"'),
    ("driver.breakdown_slip", "breakdown_slip = 0.2", "breakdown_slip = nan"),
    ("driver.inertia", 'inertia = "0.012 kg*m^2"', "inertia = [1, 2]"),
    ("heat.capacity", 'capacity = "1400 J/K"', "capacity = true"),
    ("heat.conductance", 'conductance = "4 W/K"', 'conductance = "inf W/K"'),
    ("limits.max_temperature_rise", 'max_temperature_rise = "4 K"', "max_temperature_rise = { a = 1 }"),
    ("limits.starts_per_hour", 'starts_per_hour = "10 1/hour"', 'starts_per_hour = "-10 1/hour"'),
    ("spring_preload", 'spring_preload = "12 N"', 'spring_preload = "1e30 N"'),
]


def test_hostile_values_in_every_nested_table_all_reported(tmp_path, capsys):
    text = edit(MOTOR, *((old, new) for _, old, new in HOSTILE),
                ("[start_up.driver]", "intervals = 1e9\ntolerance = nan\n\n[start_up.driver]"))
    lines = errors(tmp_path, capsys, text)
    assert sorted(fields(lines)) == sorted([f"start_up.{name}" for name, _, _ in HOSTILE]
                                           + ["start_up.intervals", "start_up.tolerance"]), lines


def test_start_up_settings_and_tables_of_the_wrong_kind(tmp_path, capsys):
    text = edit(MOTOR, ('effects = ["slip_friction",', 'effects = ["sparks", "slip_friction",'),
                ("[start_up.heat]\ncapacity", "[start_up.heaat]\ncapacity"),
                ('spring_preload = "12 N"', 'spring_preload = "12 N"\ndriven = 5'))
    lines = errors(tmp_path, capsys, text)
    assert fields(lines) == ["start_up.heaat", "start_up.effects", "start_up.driven"], lines


def test_load_profile_and_resisting_torque_both_given_beside_a_bad_field(tmp_path, capsys):
    text = edit(MOTOR, ("[start_up.heat]", '[start_up.driven]\nresisting_torque = "5 N*m"\ninertia = "-1 kg*m^2"\n'
                                           'load_profile = { over = "speed", points = [0, 1000], torque = [1, 5] }'
                                           "\n\n[start_up.heat]"))
    lines = errors(tmp_path, capsys, text)
    assert fields(lines) == ["start_up.driven.inertia", "start_up.driven"], lines


def test_a_bad_start_up_value_is_not_replaced_by_the_duty_s(tmp_path, capsys):
    text = edit(MOTOR, ('inertia = "0.5 kg*m^2"', 'inertia = "1e10 kg*m^2"'),
                ("[start_up.heat]", '[start_up.driven]\ninertia = "-1 kg*m^2"\n\n[start_up.heat]'))
    lines = errors(tmp_path, capsys, text)
    assert fields(lines) == ["start_up.driven.inertia"] and "must be > 0" in lines[0], lines


def test_cross_field_checks_still_run_once_the_fields_are_sound(tmp_path, capsys):
    lines = errors(tmp_path, capsys, edit(MOTOR, ('capacity = "1400 J/K"\n', "")))
    assert lines == ["error: start_up.heat.capacity: missing (effect friction_heat)"]


def test_cable_start_up_fields_all_reported(tmp_path, capsys):
    text = edit(CABLE_MOTOR, ("[start_up.driver]", "[start_up.driver]\nvoltage = 400"))
    text = text.replace("breakdown_slip = ", "breakdown_slip = -", 1)
    lines = errors(tmp_path, capsys, text)
    assert fields(lines) == ["start_up.driver.voltage", "start_up.driver.breakdown_slip"], lines


# --- nothing required that the posed objective does not use ------------------------------------------------------

def test_prices_not_needed_to_minimise_mass(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(NO_PRICES)
    assert main(["solve", str(path), "--no-store"]) == 0
    out = capsys.readouterr().out
    assert "status: optimal   objective (mass)" in out
    assert [line.split() for line in out.splitlines() if line.split()[:1] == ["cost"]] == [
        ["cost", "-", "EUR", "balls", "and", "body", "priced", "per", "kg"]]


PRICE_LINES = ["error: cost.ball_price: missing (the cost objective needs it: price of the balls, in EUR/kg); or "
               "name a ball_material (clutchopt materials)",
               "error: cost.body_price: missing (the cost objective needs it: price of the clutch body (drum, rotor), "
               "machined, in EUR/kg)"]


@pytest.mark.parametrize("text, argv", [
    (NO_PRICES, ("solve", "--objective", "cost")),
    (NO_PRICES.replace("[bounds]", '[options]\nobjective = "cost"\n\n[bounds]'), ("solve",)),
    (NO_PRICES, ("pareto", "--points", "3")),
    (NO_PRICES, ("sweep", "--vary", "service_factor=1.1:1.3:2", "--objective", "cost")),
    (NO_PRICES, ("report", "--objective", "cost", "-o", "review.html")),
], ids=["solve", "case-option", "pareto", "sweep", "report"])
def test_a_cost_objective_refuses_by_name_before_any_solve(tmp_path, capsys, text, argv):
    assert errors(tmp_path, capsys, text, *argv) == PRICE_LINES


def test_the_library_refuses_too(tmp_path):
    from clutchopt.optimise import solve_case

    path = tmp_path / "case.toml"
    path.write_text(NO_PRICES)
    with pytest.raises(InputError) as refused:
        solve_case(load_case(path), objective="cost")
    assert [p.field for p in refused.value.problems] == ["cost.ball_price", "cost.body_price"]


def test_compare_without_prices_leaves_the_cost_optimum_out(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(NO_PRICES)
    assert main(["compare", str(path)]) == 0
    out = capsys.readouterr().out
    assert ("nlp_cost: not solved: the cost objective needs cost.ball_price, cost.body_price, which the case does "
            "not give") in out
    assert "nlp_mass: status optimal" in out


# --- a sweep table says which case it was swept from ------------------------------------------------------------

def sweep_table(folder: Path, suffix: str) -> Path:
    """A two-point sweep of the wedge paper's case written by the CLI."""
    table = folder / f"sweep.{suffix}"
    assert main(["sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=900,1000", "--out", str(table),
                 "--quiet", "--no-store"]) == 0
    return table


@pytest.fixture(scope="module", params=["csv", "parquet"])
def swept(request, tmp_path_factory):
    return sweep_table(tmp_path_factory.mktemp("swept"), request.param)


@pytest.fixture(scope="module")
def swept_csv(tmp_path_factory):
    return sweep_table(tmp_path_factory.mktemp("swept"), "csv")


def review(tmp_path, capsys, case: str, table) -> tuple[int, str]:
    code = main(["report", str(CASES / case), "-o", str(tmp_path / "review.html"), "--sweep", str(table),
                 "--no-store"])
    return code, capsys.readouterr().err


def test_a_sweep_table_of_its_own_case_is_shown(tmp_path, capsys, swept):
    assert review(tmp_path, capsys, "wedge_paper.toml", swept) == (0, "")


@pytest.mark.parametrize("case, differs", [
    ("lever_centrifuge.toml", "coupling 'wedge', not 'lever'"),
    ("wedge_fan.toml", "wedge_paper.toml', whose acceleration_time, allowable_pressure,"),
])
def test_a_sweep_table_of_another_case_is_refused_naming_what_differs(tmp_path, capsys, swept, case, differs):
    code, err = review(tmp_path, capsys, case, swept)
    assert code == EXIT_BAD_INPUT and err.count("\n") == 1, err
    assert err.startswith(f"error: {swept}: not a sweep of {CASES / case}: ") and differs in err, err


def test_a_table_whose_columns_contradict_its_identification_is_refused(tmp_path, capsys, swept_csv):
    edited = tmp_path / "edited.csv"
    first, header, rest = swept_csv.read_text().split("\n", 2)
    edited.write_text("\n".join([first, header.replace("speed [rpm]", "inertia [kg*m^2]"), rest]))
    code, err = review(tmp_path, capsys, "wedge_paper.toml", edited)
    assert code == EXIT_BAD_INPUT and ("quantities: its columns vary inertia [kg*m^2], its identification says "
                                       "speed [rpm]") in err, err


def test_an_older_table_without_identification_is_shown_with_a_warning(tmp_path, capsys, swept_csv):
    older = tmp_path / "older.csv"
    older.write_text(swept_csv.read_text().split("\n", 1)[1])
    code, err = review(tmp_path, capsys, "wedge_paper.toml", older)
    assert code == 0 and err == (f"warning: {older} does not say which case it was swept from (a table of an older "
                                 f"clutchopt); it is shown as a sweep of {CASES / 'wedge_paper.toml'}\n")

"""Hostile inputs for designs under scatter (issue 25), in the form of ``tests/hostile.py``: each scatter
distribution against the case's value, a scattered limit of each family (static, start-up upper and lower,
a limit that follows another quantity), quantities that enter only the start-up, design variables the case fixes or
frees, followed and following quantities, ``--robust`` with ``--verify`` and ``--starts``, and the run store read
after robust designs. ``tests/test_hostile_scatter.py`` runs them in process.

The runs commands read a store of robust designs (``ROBUST_RUNS``, built once by :func:`robust_store`)."""

from __future__ import annotations

import shutil
import sqlite3
from functools import lru_cache
from pathlib import Path

from hostile import CASES, WEDGE, Hostile, Special, case, command, edit

MOTOR = (CASES / "wedge_motor_start.toml").read_text()  # the paper's example on its motor, spring preload free
FIXED = edit(MOTOR, 'free = ["spring_preload"]', "free = []")  # the preload the case's value
CENTRIFUGE = (CASES / "wedge_centrifuge.toml").read_text()  # f, inertia (normal) and load scatter; free flank angle
CENTRIFUGE_BARE = CENTRIFUGE[:CENTRIFUGE.index("[scatter]")]
QUICK = ("--samples", "100")  # Monte Carlo samples: the fewest taken
STARTS = (*QUICK, "--starts", "10")  # and simulated starts: the fewest taken
ROBUST_RUNS = Special("robust runs")  # a run store of robust designs: worst case, chance, a start-up's, nominal
OLDER_RUNS = Special("older robust runs")  # the same, as a clutchopt before the method column wrote it


def scattered(base: str, table: str) -> str:
    return f"{base}\n[scatter]\n{table}\n"


def robust(name: str, base: str, table: str, expect, *extra: str, method: str = "worst-case") -> Hostile:
    """``solve --robust`` of ``base`` with a [scatter] ``table``."""
    quick = STARTS if "[start_up]" in base else QUICK
    return case(name, scattered(base, table), expect, "--robust", method, *quick, *extra)


def runs(name: str, *argv: str, store: Special = ROBUST_RUNS, expect=None) -> Hostile:
    """A runs command on a store of robust designs."""
    return command(name, ("runs", *argv, "--store", "{dir}/runs.sqlite"), expect, ("runs.sqlite", store))


FIVE = ('friction_coefficient = [0.14, 0.16]\nspeed = ["950 rpm", "1050 rpm"]\n'
        'allowable_pressure = ["3.8 MPa", "4.2 MPa"]\nallowable_bending_stress = ["150 MPa", "170 MPa"]\n'
        'resisting_torque = ["4.5 N*m", "5.5 N*m"]')
OWN_DRIVEN = edit(FIXED, "[start_up.driver]", '[start_up.driven]\ninertia = "0.6 kg*m^2"\n\n[start_up.driver]')
WINDOW = edit(edit(FIXED, 'min_engagement_speed = "350 rpm"', 'min_engagement_speed = "250 rpm"'),
              'max_engagement_speed = "600 rpm"', 'max_engagement_speed = "420 rpm"')

HOSTILE: list[Hostile] = [
    # --- each distribution against the case's value ----------------------------------------------------------------
    robust("normal-mean-not-the-case-value", WEDGE, "friction_coefficient = { normal = [0.3, 0.01] }",
           "scatter.friction_coefficient.normal: the mean 0.3 is not the case's value 0.15"),
    robust("normal-mean-with-a-unit-off", WEDGE, 'inertia = { normal = ["0.6 kg*m^2", "0.01 kg*m^2"] }',
           ("scatter.inertia.normal: the mean 0.6 kg*m^2 is not the case's value 0.5 kg*m^2",
            'normal = ["0.5 kg*m^2", "0.01 kg*m^2"]')),
    robust("normal-mean-in-another-unit", WEDGE, 'inertia = { normal = ["5000 kg*cm^2", "100 kg*cm^2"] }', None),
    robust("normal-mean-a-hair-off", WEDGE, "friction_coefficient = { normal = [0.1500001, 0.01] }",
           "scatter.friction_coefficient.normal: the mean 0.15 is not the case's value 0.15"),
    robust("normal-sd-zero", WEDGE, "friction_coefficient = { normal = [0.15, 0] }",
           "scatter.friction_coefficient.normal: the standard deviation must be positive"),
    robust("uniform-excludes-the-case-value", WEDGE, "friction_coefficient = { uniform = [0.2, 0.3] }",
           "scatter.friction_coefficient: the case's value 0.15 lies outside 0.2 .. 0.3"),
    robust("range-below-the-case-value", WEDGE, 'speed = ["500 rpm", "900 rpm"]',
           "scatter.speed: the case's value 1000 rpm lies outside 500 rpm .. 900 rpm"),
    robust("range-ends-at-the-case-value", WEDGE, "friction_coefficient = [0.15, 0.2]", None),
    robust("uniform-around-the-case-value", WEDGE, "friction_coefficient = { uniform = [0.12, 0.18] }", None,
           method="chance=0.99"),
    robust("weibull-not-a-distribution", WEDGE, "friction_coefficient = { weibull = [0.15, 0.01] }",
           "scatter.friction_coefficient: must be [low, high], { normal = [mean, sd] } or { uniform = [low, high] }"),
    robust("every-distribution-off-at-once", WEDGE,
           'friction_coefficient = { normal = [0.3, 0.01] }\ndensity = { uniform = ["8000 kg/m^3", "8100 kg/m^3"] }'
           '\nallowable_pressure = ["1 MPa", "2 MPa"]',
           ("scatter.friction_coefficient.normal: the mean", "scatter.density: the case's value 7850",
            "scatter.allowable_pressure: the case's value 4 MPa")),
    robust("start-up-quantity-mean-off", MOTOR, 'breakdown_torque = { normal = ["40 N*m", "1 N*m"] }',
           "scatter.breakdown_torque.normal: the mean 40 N*m is not the case's value 37 N*m"),
    robust("follower-mean-off-its-source", MOTOR, 'driven_inertia = { normal = ["0.6 kg*m^2", "0.01 kg*m^2"] }',
           "scatter.driven_inertia.normal: the mean 0.6 kg*m^2 is not the case's value 0.5 kg*m^2"),
    robust("follower-limit-range-off", MOTOR, 'max_start_time = ["11 s", "12 s"]',
           "scatter.max_start_time: the case's value 10 s lies outside 11 s .. 12 s"),
    # --- a scattered limit of each family --------------------------------------------------------------------------
    robust("static-upper-limit", WEDGE, 'allowable_bending_stress = ["140 MPa", "180 MPa"]', None),
    robust("static-limit-chance", WEDGE, 'allowable_pressure = { normal = ["4 MPa", "0.2 MPa"] }', None,
           method="chance=0.999"),
    robust("start-time-limit", MOTOR, 'max_start_time = ["8 s", "12 s"]', None),
    robust("start-time-limit-chance", MOTOR, 'max_start_time = { normal = ["10 s", "0.5 s"] }', None,
           method="chance=0.99"),
    robust("temperature-limit", MOTOR, 'max_temperature_rise = ["3.5 K", "4.5 K"]', None),
    robust("heat-dissipation-limit", MOTOR, 'heat_dissipation = ["14 W", "18 W"]', None),
    robust("starts-per-hour", MOTOR, 'starts_per_hour = ["8 1/hour", "12 1/hour"]', None),
    robust("engagement-window-lower", FIXED, 'min_engagement_speed = ["340 rpm", "360 rpm"]', None),
    robust("lock-up-speed-lower-limit", MOTOR, 'min_lock_up_speed = ["850 rpm", "950 rpm"]', None),
    robust("limit-without-start-up", WEDGE, 'max_start_time = ["8 s", "12 s"]',
           "scatter.max_start_time: not a quantity of this case"),
    robust("limit-the-case-does-not-set", MOTOR, 'max_friction_work = ["4 kJ", "6 kJ"]',
           "scatter.max_friction_work: the case gives no value of it to scatter around"),
    robust("limit-with-a-count-in-hz", MOTOR, 'starts_per_hour = ["8 Hz", "12 Hz"]', "scatter.starts_per_hour"),
    # --- quantities that enter only the start-up; design variables fixed or free -----------------------------------
    robust("breakdown-torque-start-up-only", MOTOR, 'breakdown_torque = ["35 N*m", "39 N*m"]', None),
    robust("motor-inertia-start-up-only", MOTOR, 'motor_inertia = { normal = ["0.012 kg*m^2", "0.001 kg*m^2"] }',
           None, method="chance=0.99"),
    robust("fixed-preload-reaches-the-window", WINDOW, 'spring_preload = ["6 N", "18 N"]', None),
    robust("fixed-preload-no-design-meets", FIXED, 'spring_preload = ["6 N", "18 N"]', None),
    robust("free-preload-refused", MOTOR, 'spring_preload = ["6 N", "18 N"]',
           "scatter.spring_preload: a design variable the optimiser chooses in mode paper"),
    robust("free-flank-angle-refused", CENTRIFUGE_BARE, 'flank_angle = ["14 deg", "16 deg"]',
           "scatter.flank_angle: a design variable the optimiser chooses in mode geometry", "--mode", "geometry"),
    robust("fixed-flank-angle-geometry", WEDGE, 'flank_angle = ["13 deg", "17 deg"]', None, "--mode", "geometry"),
    robust("whole-number-refused", WEDGE, "weight_count = [3, 5]", "scatter.weight_count: a whole number does not"),
    robust("price-only-the-objective-depends-on", WEDGE, 'material_price = ["2 EUR/kg", "3 EUR/kg"]',
           "scatter.material_price: only the cost objective depends on it, not a constraint", "--objective", "cost"),
    robust("price-nothing-depends-on", WEDGE, 'material_price = ["2 EUR/kg", "3 EUR/kg"]',
           "scatter.material_price: does not enter the wedge problem in mode paper"),
    robust("start-up-quantity-without-start-up", WEDGE, 'breakdown_torque = ["35 N*m", "39 N*m"]',
           "scatter.breakdown_torque: not a quantity of this case"),
    # --- followed and following quantities -------------------------------------------------------------------------
    robust("source-its-follower-follows", MOTOR, 'inertia = ["0.45 kg*m^2", "0.55 kg*m^2"]', None),
    robust("follower-itself", MOTOR, 'driven_inertia = ["0.45 kg*m^2", "0.55 kg*m^2"]', None),
    robust("source-of-the-start-time-limit", MOTOR, 'acceleration_time = ["9 s", "11 s"]', None),
    robust("source-with-its-own-follower", OWN_DRIVEN, 'inertia = ["0.45 kg*m^2", "0.55 kg*m^2"]',
           "scatter.inertia: driven_inertia is given here (0.6 kg*m^2"),
    # --- --robust with --verify and --starts ------------------------------------------------------------------------
    robust("verify-worst-case", CENTRIFUGE_BARE, 'friction_coefficient = [0.12, 0.18]', None, "--verify"),
    robust("verify-chance", CENTRIFUGE_BARE, 'friction_coefficient = { normal = [0.15, 0.01] }', None, "--verify",
           method="chance=0.999"),
    robust("verify-start-up-limit", MOTOR, 'max_start_time = ["8 s", "12 s"]', None, "--verify", "--json"),
    robust("verify-five-quantities", WEDGE, FIVE, "--verify: simulates a robust design at every corner of its "
                                                  "scatter, up to 4 scattered quantities", "--verify"),
    robust("starts-without-start-up", WEDGE, "friction_coefficient = [0.12, 0.18]",
           "--starts: counts the simulated starts of a [start_up] under scatter", "--starts", "50"),
    robust("starts-and-samples-bad-at-once", WEDGE, "friction_coefficient = [0.12, 0.18]",
           ("--starts: must be a whole number from 10", "--samples: must be a whole number"), "--starts", "5",
           "--samples", "5"),
    case("verify-nominal-with-scatter", scattered(WEDGE, "friction_coefficient = [0.12, 0.18]"), None, "--verify"),
    case("pareto-robust-json", scattered(CENTRIFUGE_BARE, "friction_coefficient = [0.12, 0.18]"), None,
         "--robust", "worst-case", *QUICK, "--points", "3", "--json", command="pareto"),
    case("compare-starts-without-start-up", scattered(WEDGE, "friction_coefficient = [0.12, 0.18]"),
         "--starts: counts the simulated starts", "--robust", "worst-case", "--starts", "20", command="compare"),
    # --- the run store after robust designs ------------------------------------------------------------------------
    runs("runs-list-robust", "list"),
    runs("runs-list-robust-json", "list", "--json"),
    runs("runs-list-robust-solves-only", "list", "--kind", "solve", "--limit", "2"),
    runs("runs-show-worst-case", "show", "1"),
    runs("runs-export-robust-csv", "export", "-o", "{dir}/runs.csv"),
    runs("runs-export-robust-md", "export", "-o", "{dir}/runs.md"),
    runs("runs-list-older-store", "list", store=OLDER_RUNS),
    runs("runs-export-older-store", "export", "-o", "{dir}/runs.csv", store=OLDER_RUNS),
]


@lru_cache(maxsize=1)
def robust_store(folder: Path) -> Path:
    """A run store of a worst-case and a chance design of the centrifuge, a worst-case start-up design and a
    nominal design, recorded as ``solve`` records them (built once, in ``folder``)."""
    from clutchopt.cases import parse_case, read_toml
    from clutchopt.cli.options import record_solve
    from clutchopt.optimise.design import Robustness, design_case, method_of
    from clutchopt.store import RunStore
    from clutchopt.store_kept import close_kept

    path = folder / "robust.sqlite"
    motor = read_toml(CASES / "wedge_motor_start.toml")
    motor["scatter"] = {"max_start_time": ["8 s", "12 s"]}
    designs = [(parse_case(read_toml(CASES / "wedge_centrifuge.toml"), "wedge_centrifuge.toml"), method)
               for method in (Robustness("worst-case", None, 100), Robustness("chance", 0.999, 100), None)]
    designs.insert(2, (parse_case(motor, "motor.toml"), Robustness("worst-case", None, 100, 10)))
    with RunStore(path) as store:
        for designed_case, method in designs:
            record_solve(store, design_case(designed_case, robust=method)[0], method_of(method))
    close_kept()  # as at the end of a command's process: the write-ahead log folded into the file, then copied
    older = folder / "older.sqlite"
    shutil.copy(path, older)
    with sqlite3.connect(older) as db:
        db.execute("ALTER TABLE runs DROP COLUMN method")
    db.close()
    return path


def written(hostile: Hostile, folder: Path, stores: Path) -> list[str]:
    """:meth:`Hostile.write` with the run stores of robust designs copied in (built once, in ``stores``)."""
    plain = Hostile(hostile.name, hostile.argv, hostile.expect,
                    tuple(f for f in hostile.files if f[1] not in (ROBUST_RUNS, OLDER_RUNS)), hostile.subprocess)
    argv = plain.write(folder)
    for name, content in hostile.files:
        if content in (ROBUST_RUNS, OLDER_RUNS):
            built = robust_store(stores)
            shutil.copy(built if content is ROBUST_RUNS else built.with_name("older.sqlite"), folder / name)
    return argv

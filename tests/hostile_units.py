"""Hostile inputs for what issue 25 found on the new surfaces: a unit of another kind than its quantity's (an angle
for a ratio, an angular speed for a count per time, a torque for a torque per angle) in cases, start-up sections,
scenes and scatters; limits of zero; a start-up motor slower than its duty, in a case, a sweep and a scatter; sweep
points refused before the first solve; a role both named in [library] and chosen; several bad options at once.
Inputs that are fine say so (``expect`` None: exit code 0), so that the rules refuse no more than they should.

The entries reuse tests/hostile.py's :class:`Hostile` and helpers; tests/test_hostile_units.py runs them. Run as a
script, this module writes every input to a folder (``python tests/hostile_units.py /tmp/hostile-units``).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from hostile import CASES, DESIGN, LEVER, WEDGE, Hostile, case, command, edit, write_all

MOTOR = (CASES / "wedge_motor_start.toml").read_text()
CABLE = (CASES / "cable_conveyor.toml").read_text()
NO_MOTOR = WEDGE + '\n[start_up]\neffects = ["slip_friction", "lockup"]\n'
MOTOR_SCENE = edit(edit((CASES / "scenes" / "wedge_motor_springs.toml").read_text(),
                        'case = "../wedge_paper.toml"', 'case = "wedge_paper.toml"'),
                   'design = "../designs/wedge_paper.json"', 'design = "design.json"')
PAPER_SCENE = (CASES / "scenes" / "paper_transient.toml").read_text()
SCATTERED = "\n[scatter]\n"


def motor(name: str, old: str, new: str, expect: str | tuple[str, ...] | None) -> Hostile:
    """The wedge case on its induction motor (cases/wedge_motor_start.toml) with one value replaced."""
    return case(name, edit(MOTOR, old, new), expect)


def slip(name: str, value: str, expect: str | None) -> Hostile:
    return motor(name, "breakdown_slip = 0.2", f"breakdown_slip = {value}", expect)


def starts(name: str, value: str, expect: str | None) -> Hostile:
    return motor(name, 'starts_per_hour = "10 1/hour"', f"starts_per_hour = {value}", expect)


def motor_sweep(name: str, *extra: str, expect: str | tuple[str, ...] | None, text: str = MOTOR) -> Hostile:
    return command(name, ("sweep", "{dir}/case.toml", "--quiet", "--no-store", *extra), expect, ("case.toml", text))


def scene(name: str, text: str, expect: str | None) -> Hostile:
    """A start-up scene of the paper's design on an induction motor, the case and design beside it."""
    return Hostile(name, ("simulate", "{dir}/scene.toml", "--no-store"), expect,
                   (("scene.toml", text), ("wedge_paper.toml", WEDGE), ("design.json", json.dumps(DESIGN))))


def paper_solve(name: str, *extra: str, expect: str | tuple[str, ...] | None,
                path: str = "wedge_paper.toml") -> Hostile:
    return command(name, ("solve", str(CASES / path), "--no-store", *extra), expect)


SLOW_MOTOR = "start_up.driver.synchronous_speed: 500 rpm is below duty.speed 1000 rpm: an induction motor runs below"
COUNT = "start_up.limits.starts_per_hour: expected a count per time (e.g. in 1/hour), got"
RATIO = "start_up.driver.breakdown_slip: expected a ratio (a bare number or %), got"

HOSTILE: list[Hostile] = [
    # --- a count per time: counts per time, never an angle per time ---------------------------------------------
    starts("starts-in-rpm", '"10 rpm"', f"{COUNT} '10 rpm', which is an angular speed"),
    starts("starts-in-rev-per-hour", '"10 rev/hour"', f"{COUNT} '10 rev/hour', which is an angular speed"),
    starts("starts-in-rad-per-s", '"0.01 rad/s"', "which is an angular speed"),
    starts("starts-in-deg-per-min", '"60 deg/min"', "which is an angular speed"),
    starts("starts-in-degrees", '"10 deg"', f"{COUNT} '10 deg', which is an angle"),
    starts("starts-as-a-ratio", '"10 %"', f"{COUNT} '10 %', which is a ratio"),
    starts("starts-600-per-h", '"600 1/h"', None),
    starts("starts-per-minute", '"0.1667 1/min"', None),
    starts("starts-in-hz", '"0.002778 Hz"', None),
    # --- a ratio: a bare number or %, never an angle -------------------------------------------------------------
    slip("slip-in-degrees", '"11.46 deg"', f"{RATIO} '11.46 deg', which is an angle"),
    slip("slip-in-radians", '"0.2 rad"', f"{RATIO} '0.2 rad', which is an angle"),
    slip("slip-in-revolutions", '"0.0318 rev"', "which is an angle"),
    slip("slip-in-percent", '"20 %"', None),
    slip("slip-as-text", '"0.2"', None),
    case("friction-in-degrees", edit(WEDGE, "friction_coefficient = 0.15", 'friction_coefficient = "8.53 deg"'),
         "material.friction_coefficient: expected a ratio (a bare number or %), got '8.53 deg', which is an angle"),
    case("radius-ratio-in-radians", edit(WEDGE, "radius_ratio = 1.2", 'radius_ratio = "1.2 rad"'),
         "geometry.radius_ratio: expected a ratio"),
    case("friction-in-percent", edit(WEDGE, "friction_coefficient = 0.15", 'friction_coefficient = "15 %"'), None),
    case("cable-area-ratio-in-radians", edit(CABLE, "area_ratio = 0.5", 'area_ratio = "0.5 rad"'),
         "cables.area_ratio: expected a ratio"),
    # --- an angle takes any angle; a torque per angle is no torque -----------------------------------------------
    case("flank-angle-in-revolutions", edit(WEDGE, 'flank_angle = "15 deg"', 'flank_angle = "0.041667 rev"'), None),
    case("cable-stiffness-as-a-torque", edit(CABLE, '"28 N*m/rad"', '"28 N*m"'),
         "cables.torsional_stiffness: expected a torque per angle (e.g. in N*m/rad), got '28 N*m', which is a torque"),
    case("cable-stiffness-per-degree", edit(CABLE, '"28 N*m/rad"', '"0.48869 N*m/deg"'), None),
    # --- scenes, scatters and load profiles read values by the same rule -----------------------------------------
    scene("scene-slip-in-degrees", edit(MOTOR_SCENE, "breakdown_slip = 0.2", 'breakdown_slip = "11.46 deg"'),
          "driver.breakdown_slip: expected a ratio"),
    scene("scene-slip-in-percent", edit(MOTOR_SCENE, "breakdown_slip = 0.2", 'breakdown_slip = "20 %"'), None),
    Hostile("scene-slip-scale-in-seconds", ("simulate", "{dir}/scene.toml", "--no-store"),
            "coupling.a: expected a time per angle (e.g. in s/rad), got '-0.01 s', which is a time",
            (("scene.toml", edit(PAPER_SCENE, '"-0.01 s/rad"', '"-0.01 s"')),)),
    case("scatter-slip-in-degrees", MOTOR + SCATTERED + 'breakdown_slip = ["10 deg", "13 deg"]\n',
         "scatter.breakdown_slip: expected a ratio"),
    case("scatter-starts-in-rpm", MOTOR + SCATTERED + 'starts_per_hour = ["8 rpm", "12 rpm"]\n',
         "scatter.starts_per_hour: expected a count per time"),
    case("profile-speed-in-hz", edit(MOTOR, "[start_up.heat]", '[start_up.driven.load_profile]\nover = "speed"\n'
                                                               'points = ["0 Hz", "16 Hz"]\ntorque = ["2 N*m", "5 N*m"]'
                                                               '\n\n[start_up.heat]'),
         "start_up.driven.load_profile.points[0]: '0 Hz' is ambiguous"),
    # --- limits of zero: refused where they mean nothing, else a margin that is defined --------------------------
    motor("engagement-at-least-zero", 'min_engagement_speed = "350 rpm"', 'min_engagement_speed = "0 rpm"',
          "start_up.limits.min_engagement_speed: must be > 0 rpm, got 0 rpm"),
    motor("motor-without-load", 'resisting_torque = "5 N*m"', 'resisting_torque = "0 N*m"', None),
    case("no-motor-no-load", edit(NO_MOTOR, 'resisting_torque = "5 N*m"', 'resisting_torque = "0 N*m"'), None),
    case("cable-hub-pushes-nothing", edit(edit(CABLE, '"20000 N/m"', '"0 N/m"'), '"30 N/mm"', '"0 N/mm"'),
         "cables.transverse_stiffness: is 0, and so is spring.spring_stiffness: the hub thread pushes nothing"),
    motor_sweep("sweep-engagement-to-zero", "--vary", "min_engagement_speed=350,0",
                expect="--vary (point 1): start_up.limits.min_engagement_speed: must be > 0 rpm"),
    case("scatter-engagement-from-zero", MOTOR + SCATTERED + 'min_engagement_speed = ["0 rpm", "400 rpm"]\n',
         "scatter.min_engagement_speed: must be > 0 rpm"),
    # --- a motor slower than its duty: in the case, a sweep and a scatter -----------------------------------------
    motor("motor-slower-than-duty", 'synchronous_speed = "1000 rpm"', 'synchronous_speed = "500 rpm"', SLOW_MOTOR),
    motor("duty-faster-than-motor", 'speed = "1000 rpm"', 'speed = "1200 rpm"',
          "start_up.driver.synchronous_speed: 1000 rpm is below duty.speed 1200 rpm"),
    motor("lock-up-beyond-motor", "[start_up.limits]", '[start_up.limits]\nmin_lock_up_speed = "1100 rpm"',
          "start_up.limits.min_lock_up_speed: 1100 rpm is not below start_up.driver.synchronous_speed 1000 rpm"),
    motor("motor-faster-than-duty", 'synchronous_speed = "1000 rpm"', 'synchronous_speed = "1050 rpm"', None),
    motor_sweep("sweep-duty-past-motor", "--vary", "speed=900,1100",
                expect="--vary (point 1): start_up.driver.synchronous_speed: 1000 rpm is below duty.speed 1100 rpm"),
    motor_sweep("sweep-motor-below-duty", "--vary", "synchronous_speed=1000,500",
                expect=f"--vary (point 1): {SLOW_MOTOR}"),
    motor_sweep("sweep-motor-below-everything", "--vary", "synchronous_speed=1000,300",
                expect=("--vary (point 1): start_up.driver.synchronous_speed: 300 rpm is below duty.speed",
                        "--vary (point 1): start_up.limits.min_engagement_speed: 350 rpm is not below")),
    motor_sweep("sweep-grid-crosses", "--vary", "speed=900,1000", "--vary", "synchronous_speed=950,1100",
                expect="--vary (point 2): start_up.driver.synchronous_speed: 950 rpm is below duty.speed 1000 rpm"),
    motor_sweep("sweep-zipped-crosses", "--zip", "--vary", "speed=900,1000", "--vary", "synchronous_speed=1000,950",
                expect="--vary (point 1): start_up.driver.synchronous_speed: 950 rpm is below"),
    case("scatter-motor-below-duty", MOTOR + SCATTERED + 'synchronous_speed = ["900 rpm", "1100 rpm"]\n',
         "scatter (at synchronous_speed = 900 rpm): start_up.driver.synchronous_speed: 900 rpm is below duty.speed"),
    case("scatter-duty-past-motor", MOTOR + SCATTERED + 'speed = ["950 rpm", "1050 rpm"]\n',
         "scatter (at speed = 1050 rpm): start_up.driver.synchronous_speed: 1000 rpm is below duty.speed 1050 rpm"),
    motor_sweep("robust-sweep-corner-past-motor", "--vary", "speed=1000,1050", "--robust", "worst-case",
                text=edit(MOTOR, 'synchronous_speed = "1000 rpm"', 'synchronous_speed = "1100 rpm"')
                + SCATTERED + 'synchronous_speed = ["1000 rpm", "1200 rpm"]\n',
                expect="--vary (point 1): scatter (at synchronous_speed = 1000 rpm): start_up.driver.synchronous_"),
    # --- every sweep point checked before the first is solved ----------------------------------------------------
    motor_sweep("sweep-motor-beyond-simulator", "--vary", "synchronous_speed=1000,1e9",
                expect="--vary (point 1): start_up.driver.synchronous_speed: must be from 0.001 to 100000 rad/s"),
    motor_sweep("sweep-late-point-refused", "--vary", "speed=900:1100:201",
                expect="--vary (point 101): start_up.driver.synchronous_speed: 1000 rpm is below duty.speed 1001 rpm"),
    motor_sweep("sweep-window-closes", "--vary", "min_engagement_speed=350,700",
                expect="--vary (point 1): start_up.limits.min_engagement_speed: must be below max_engagement_speed"),
    command("sweep-shell-fills-housing", ("sweep", str(CASES / "wedge_paper.toml"), "--quiet", "--no-store",
                                          "--vary", "shell_thickness=10,100"),
            "--vary (point 1): limits.outer_diameter_max: leaves no room inside the shell"),
    # --- a role named in [library] and chosen in options.choose ---------------------------------------------------
    case("choose-and-library", LEVER + '\n[library]\nmaterial = "C45_QT"\n[options]\n'
                                       'choose = {material = ["C45_QT", "42CrMo4_QT"]}\n',
         "library.material: names 'C45_QT', and options.choose.material lists the entries to choose from"),
    case("choose-and-library-other-entry", LEVER + '\n[library]\nmaterial = "S235JR"\n[options]\n'
                                                   'choose = {material = ["C45_QT", "42CrMo4_QT"]}\n',
         "library.material: names 'S235JR'"),
    # --- every bad option in one run ------------------------------------------------------------------------------
    paper_solve("options-tol-and-samples", "--tol", "5", "--samples", "1.5",
                expect=("argument --tol: must be between", "argument --samples: not a whole number: '1.5'")),
    paper_solve("options-tol-mode-objective-starts", "--tol", "0", "--mode", "", "--objective", " ", "--starts", "x",
                expect=("argument --tol", "argument --mode", "argument --objective", "argument --starts")),
    paper_solve("options-tol-and-robust-counts", "--tol", "nan", "--robust", "worst-case", "--samples", "50",
                "--starts", "5", path="wedge_motor_start_scatter.toml",
                expect=("argument --tol", "--samples: must be a whole number from 100",
                        "--starts: must be a whole number from 10")),
    command("options-sweep-jobs-and-tol", ("sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=900",
                                           "--jobs", "0", "--tol", "1"),
            ("argument --jobs: must be from 1", "argument --tol: must be between")),
    command("options-pareto-points-and-tol", ("pareto", str(CASES / "wedge_paper.toml"), "--points", "1",
                                              "--tol", "inf"),
            ("argument --points: must be from 2", "argument --tol")),
    command("options-runs-limit-and-sweep", ("runs", "list", "--limit", "x", "--sweep", "0"),
            ("argument --limit: not a whole number", "argument --sweep: must be from 1")),
]



if __name__ == "__main__":
    write_all(Path(sys.argv[1] if len(sys.argv) > 1 else "hostile-unit-inputs"), HOSTILE)

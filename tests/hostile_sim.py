"""Hostile inputs for the start-up and its simulation (issue 25, "Hangs and unbounded work"): inertias, times, heat
and motors at the ends of their accepted ranges and just beyond, load profiles of 2 to 1000 points in odd shapes,
scenes with extreme values, start-up sweeps across such values. Each input within the ranges must end, within the
time limit of tests/test_hostile.py, in a result (exit code 0: a design, or a verdict such as ``infeasible``) or in
``error:`` lines naming the field (exit code 2); never exit code 3, never a run without end.

``tests/test_hostile_sim.py`` runs them all in process; as a script, this module writes every input to a folder and
prints its command line, as tests/hostile.py does::

    python tests/hostile_sim.py /tmp/hostile-sim
"""

from __future__ import annotations

import sys
from pathlib import Path

from hostile import CASES, Hostile, case, command, edit, scene, write_all

MOTOR = (CASES / "wedge_motor_start.toml").read_text()
CABLE = (CASES / "cable_motor_start.toml").read_text()
SCENES = CASES / "scenes"
ABSOLUTE = {'"../wedge_paper.toml"': f'"{CASES / "wedge_paper.toml"}"',
            '"../designs/wedge_paper.json"': f'"{CASES / "designs" / "wedge_paper.json"}"',
            '"../wedge_fan.toml"': f'"{CASES / "wedge_fan.toml"}"'}
RPM = 1000.0  # the synchronous speed of wedge_motor_start


def _scene_text(name: str) -> str:
    """A committed scene with its case and design named by absolute paths (it is written to another folder)."""
    text = (SCENES / name).read_text()
    for relative, absolute in ABSOLUTE.items():
        text = text.replace(relative, absolute)
    return text


SPRINGS, FAN, PAPER = (_scene_text(name) for name in ("wedge_motor_springs.toml", "wedge_fan_load.toml",
                                                      "paper_transient.toml"))


def motor(name: str, old: str, new: str, expect, *extra: str, command_name: str = "solve") -> Hostile:
    """wedge_motor_start with one text replaced."""
    return case(name, edit(MOTOR, old, new), expect, *extra, command=command_name)


def motor_inertia(name: str, value: str, expect) -> Hostile:
    return motor(name, 'inertia = "0.012 kg*m^2"', f'inertia = "{value}"', expect)


def limits(name: str, lines: str, expect, *extra: str, command_name: str = "solve") -> Hostile:
    """wedge_motor_start with lines added to [start_up.limits]."""
    return motor(name, "[start_up.limits]\n", f"[start_up.limits]\n{lines}\n", expect, *extra,
                 command_name=command_name)


def driven(name: str, lines: str, expect, *extra: str, command_name: str = "solve") -> Hostile:
    """wedge_motor_start with a [start_up.driven] section."""
    return motor(name, "[start_up.driver]\n", f"[start_up.driven]\n{lines}\n\n[start_up.driver]\n", expect, *extra,
                 command_name=command_name)


def profile(name: str, over: str, points, torques, expect, unit: str = "rpm") -> Hostile:
    """wedge_motor_start against a load profile (points in ``unit``, torques in N*m)."""
    quoted = ", ".join(f'"{point:.9g} {unit}"' for point in points)
    return driven(name, f'[start_up.driven.load_profile]\nover = "{over}"\npoints = [{quoted}]\n'
                        f'torque = [{", ".join(f"{torque:.9g}" for torque in torques)}]', expect)


def spread(count: int, top: float = 1.1 * RPM) -> list[float]:
    return [top * i / (count - 1) for i in range(count)]


def springs(name: str, old: str, new: str, expect) -> Hostile:
    """The committed solved wedge design on its motor with springs (cases/scenes/wedge_motor_springs.toml)."""
    return scene(name, edit(SPRINGS, old, new), expect)


def sweep(name: str, *vary: str, expect=None) -> Hostile:
    """A start-up sweep of wedge_motor_start (its table not stored)."""
    return command(name, ("sweep", "{dir}/case.toml", "--quiet", "--no-store", *vary), expect, ("case.toml", MOTOR))


HOSTILE: list[Hostile] = [
    # --- inertias at and beyond the ends of their ranges --------------------------------------------------------
    motor_inertia("motor-inertia-at-low-end", "1e-9 kg*m^2", None),  # a motor time constant of 3e-10 s
    motor_inertia("motor-inertia-below-range", "1e-10 kg*m^2", "start_up.driver.inertia: must be from 1e-09"),
    motor_inertia("motor-inertia-of-a-flywheel", "1000 kg*m^2", None),  # 2,800 s to run up: proven infeasible
    driven("driven-inertia-huge", 'inertia = "1e6 kg*m^2"', None),
    driven("driven-inertia-at-high-end", 'inertia = "1e9 kg*m^2"', None),
    driven("driven-inertia-at-low-end", 'inertia = "1e-9 kg*m^2"', None),
    driven("driven-inertia-above-range", 'inertia = "2e9 kg*m^2"', "start_up.driven.inertia: must be from"),
    # --- times ---------------------------------------------------------------------------------------------------
    limits("start-time-1e8-s", 'max_start_time = "1e8 s"', None),
    limits("start-time-at-high-end", 'max_start_time = "1e9 s"', None),
    limits("start-time-a-nanosecond", 'max_start_time = "1e-9 s"', None),  # proven infeasible
    limits("start-time-beyond-range", 'max_start_time = "1e10 s"', "start_up.limits.max_start_time: must be from"),
    limits("start-time-in-years", 'max_start_time = "3 year"', None),
    # --- heat ------------------------------------------------------------------------------------------------------
    motor("heat-capacity-at-low-end", 'capacity = "1400 J/K"', 'capacity = "1e-6 J/K"', None),
    motor("heat-capacity-at-high-end", 'capacity = "1400 J/K"', 'capacity = "1e12 J/K"', None),
    motor("heat-conductance-at-high-end", 'conductance = "4 W/K"', 'conductance = "1e12 W/K"', None),
    motor("heat-conductance-zero", 'conductance = "4 W/K"', 'conductance = "0 W/K"',
          "start_up.heat.conductance: 0 W/K with starts_per_hour: give the housing's conductance above 0 W/K"),
    # --- the motor -----------------------------------------------------------------------------------------------
    motor("breakdown-slip-tiny", "breakdown_slip = 0.2", "breakdown_slip = 1e-6", None),
    motor("breakdown-slip-at-high-end", "breakdown_slip = 0.2", "breakdown_slip = 0.99", None),
    motor("breakdown-torque-at-high-end", 'breakdown_torque = "37 N*m"', 'breakdown_torque = "1e9 N*m"', None),
    motor("synchronous-speed-below-the-duty", 'synchronous_speed = "1000 rpm"', 'synchronous_speed = "100 rpm"',
          "start_up.driver.synchronous_speed: 100 rpm is below duty.speed 1000 rpm"),
    # --- loads and load profiles -------------------------------------------------------------------------------
    driven("load-zero", 'resisting_torque = "0 N*m"', None),
    driven("load-at-high-end", 'resisting_torque = "1e9 N*m"', None),  # beyond the motor: infeasible, proven
    profile("profile-two-points", "speed", [0.0, RPM], [0.0, 5.0], None),
    profile("profile-1000-points-fan-law", "speed", spread(1000), [5.0 * (x / RPM) ** 2 for x in spread(1000)],
            None),
    profile("profile-1000-points-over-time", "time", spread(1000, 20.0), [5.0 + x / 20.0 for x in spread(1000, 20.0)],
            None, unit="s"),
    profile("profile-100-point-sawtooth", "speed", spread(100), [5.0 + 0.5 * (i % 2) for i in range(100)], None),
    profile("profile-1000-point-noise", "speed", spread(1000), [5.0 + 0.1 * (i % 7) for i in range(1000)], None),
    profile("profile-step-in-time", "time", [0.0, 4.999, 5.0, 60.0], [2.0, 2.0, 8.0, 8.0], None, unit="s"),
    profile("profile-zero-everywhere", "speed", spread(50), [0.0] * 50, None),
    profile("profile-spike", "speed", [0.0, 499.0, 500.0, 501.0, RPM], [1.0, 1.0, 30.0, 1.0, 1.0], None),
    profile("profile-beyond-the-motor", "speed", [0.0, RPM], [5.0, 40.0], None),
    profile("profile-1001-points", "speed", spread(1001), [5.0] * 1001, "(2 to 1000)"),
    profile("profile-points-repeated", "speed", [0.0, 500.0, 500.0, RPM], [5.0] * 4,
            "start_up.driven.load_profile.points: must increase strictly"),
    # --- other commands on such cases -----------------------------------------------------------------------------
    motor("compare-motor-inertia-at-low-end", 'inertia = "0.012 kg*m^2"', 'inertia = "1e-9 kg*m^2"', None,
          command_name="compare"),
    case("cable-motor-inertia-at-low-end", edit(CABLE, 'inertia = "0.09 kg*m^2"', 'inertia = "1e-9 kg*m^2"'), None),
    sweep("sweep-motor-inertia-across-the-range", "--vary", "motor_inertia=1e-9,0.012,1000"),
    sweep("sweep-start-time-to-1e8-s", "--vary", "max_start_time=10,1e8"),
    sweep("sweep-driven-inertia-to-1e6", "--vary", "driven_inertia=0.5,1e6"),
    # --- scenes ----------------------------------------------------------------------------------------------------
    springs("scene-motor-inertia-at-low-end", 'inertia = "0.012 kg*m^2"', 'inertia = "1e-9 kg*m^2"', None),
    springs("scene-end-time-at-high-end", 'end_time = "40 s"', 'end_time = "1e9 s"', None),
    springs("scene-driven-inertia-at-high-end", "[driver]\n", '[driven]\ninertia = "1e9 kg*m^2"\n\n[driver]\n', None),
    springs("scene-breakdown-slip-tiny", "breakdown_slip = 0.2", "breakdown_slip = 1e-6", None),
    scene("scene-paper-conductance-at-high-end", edit(PAPER, 'capacity = "2300 J/K"',
                                                      'capacity = "2300 J/K"\nconductance = "1e12 W/K"'), None),
    scene("scene-paper-end-time-at-high-end", 'end_time = "1e9 s"\n' + PAPER, None),
    scene("scene-fan-1000-points", edit(FAN, FAN[FAN.index("points ="):], "points = [{}]\ntorque = [{}]\n".format(
        ", ".join(f'"{x:.9g} rpm"' for x in spread(1000, 980.0)),
        ", ".join(f'"{150.0 * (x / 980.0) ** 2:.9g} N*m"' for x in spread(1000, 980.0)))), None),
    scene("scene-chatter", 'title = "A clutch the load breaks loose again and again"\n'
                           'effects = ["slip_friction", "lockup"]\nend_time = "100 s"\n[coupling]\nlaw = "constant"\n'
                           'torque = "10 N*m"\n[driven]\ninertia = "1 kg*m^2"\n[driven.load_profile]\nover = "time"\n'
                           f'points = [{", ".join(str(0.5 * i) for i in range(200))}]\n'
                           f'torque = [{", ".join("15" if i % 2 else "2" for i in range(200))}]\n'
                           '[driver]\nspeed = "100 rpm"\n', None),
]



if __name__ == "__main__":
    write_all(Path(sys.argv[1] if len(sys.argv) > 1 else "hostile-sim-inputs"), HOSTILE)

"""Hostile inputs on the surfaces of the last sessions (issue 29): the neutral case of ``choose-coupling`` and its
``[couplings.NAME]`` tables, the lining's temperatures and life in ``[start_up]``, the distributions of ``[scatter]``.
What each found, in the form of ``tests/hostile.py`` (``expect``: text of the ``error:`` lines, exit code 2; None:
the input is fine, exit code 0); ``tests/test_hostile_surfaces.py`` runs them in process.

Run as a script, this module writes every input to a folder (``python tests/hostile_surfaces.py /tmp/h3``).
"""

from __future__ import annotations

import sys
from pathlib import Path

from hostile import CASES, WEDGE, Hostile, case, edit, write_all

NEUTRAL = (CASES / "conveyor_drive.toml").read_text()  # coupling = "any": a belt conveyor on a 15 kW motor
LINING = (CASES / "lever_motor_start.toml").read_text()  # organic lining: its temperature limits from the library
MOTOR = (CASES / "wedge_motor_start.toml").read_text()
CABLE = (CASES / "cable_motor_start.toml").read_text()  # an elastic link on its induction motor


def neutral(name: str, old: str, new: str, expect, *extra: str) -> Hostile:
    """``choose-coupling`` of the conveyor's neutral case with one edit."""
    return case(name, edit(NEUTRAL, old, new), expect, *extra, command="choose-coupling")


def override(name: str, table: str, expect, *extra: str) -> Hostile:
    """The neutral case with a ``[couplings.NAME...]`` table before its ``[start_up]``."""
    return neutral(name, "[start_up]\n", f"{table}\n\n[start_up]\n", expect, *extra)


def scattered(name: str, table: str, expect, *extra: str) -> Hostile:
    return case(name, f"{WEDGE}\n[scatter]\n{table}\n", expect, "--no-store", *extra)


def lining_scatter(name: str, table: str, expect) -> Hostile:
    """``solve`` (nominal: the scatter read, not designed for) of the lever on its motor with a [scatter]."""
    return case(name, edit(LINING, "[bounds]", f"[scatter]\n{table}\n\n[bounds]"), expect, "--no-store")


def heat(name: str, text: str, old: str, new: str, expect) -> Hostile:
    return case(name, edit(text, old, new), expect, "--no-store")


HOSTILE: list[Hostile] = [
    # --- a lognormal's sd far above its mean: 1e300 overflowed ln(1 + (s/m)^2), exit code 3 ------------------------
    scattered("lognormal-sd-1e300", 'allowable_pressure = { lognormal = ["4 MPa", "1e300 Pa"] }',
              "scatter.allowable_pressure.lognormal: the standard deviation 1e+294 MPa against the mean 4 MPa"),
    scattered("lognormal-sd-1e8-means", 'allowable_pressure = { lognormal = ["4 MPa", "4e8 MPa"] }',
              "scatter.allowable_pressure.lognormal: the standard deviation 4e+08 MPa against the mean 4 MPa"),
    # --- an sd below float64's resolution of the mean: torque "0 (exact: independent of the scatter)" of f ----------
    scattered("normal-sd-subnormal", "friction_coefficient = { normal = [0.15, 1e-320] }",
              "scatter.friction_coefficient.normal: the standard deviation 9.99989e-321 does not move the mean 0.15 in "
              "float64"),
    scattered("cut-normal-sd-subnormal", "friction_coefficient = { normal = [0.15, 1e-320], within = [0.14, 0.16] }",
              "scatter.friction_coefficient.normal: the standard deviation 9.99989e-321 does not move the mean"),
    scattered("normal-sd-a-millionth", "friction_coefficient = { normal = [0.15, 1.5e-7] }", None),
    scattered("lognormal-sd-ten-means", 'allowable_pressure = { lognormal = ["4 MPa", "40 MPa"] }', None),
    # --- a temperature's scatter: an sd in degC was 278.15 K wide; a band of 20 % of the kelvin ----------------------
    lining_scatter("temperature-sd-in-degc", 'ambient_temperature = { normal = ["40 degC", "5 degC"] }',
                   "scatter.ambient_temperature.normal: '5 degC' is a temperature on a scale with an offset; write a "
                   "temperature difference in K (or delta_degC)"),
    lining_scatter("temperature-sd-in-kelvin", 'ambient_temperature = { normal = ["40 degC", "5 K"] }', None),
    lining_scatter("temperature-sd-in-delta-degc", 'ambient_temperature = { normal = ["40 degC", "5 delta_degC"] }',
                   None),
    lining_scatter("temperature-cut-normal-sd-in-degc",
                   'ambient_temperature = { normal = ["40 degC", "5 degC"], within = ["30 degC", "50 degC"] }',
                   "scatter.ambient_temperature.normal: '5 degC' is a temperature on a scale with an offset"),
    lining_scatter("temperature-lognormal-sd-in-degc", 'ambient_temperature = { lognormal = ["40 degC", "5 degC"] }',
                   "scatter.ambient_temperature.lognormal: '5 degC' is a temperature on a scale with an offset"),
    lining_scatter("temperature-band", 'ambient_temperature = "+-20 %"',
                   "scatter.ambient_temperature: a relative band of an absolute temperature depends on its scale"),
    lining_scatter("temperature-range", 'ambient_temperature = ["30 degC", "50 degC"]', None),
    scattered("band-of-a-pressure", 'allowable_pressure = "+-5 %"', None),
    # --- a correlation a hair below 1: "no joint distribution has them (e.g. a with b and b with c ...)" of two -------
    scattered("correlation-nearly-one", 'friction_coefficient = [0.12, 0.18]\nallowable_bending_stress = "+-5 %"\n'
              "[scatter.correlation]\nfriction_coefficient.allowable_bending_stress = 0.9999999999999",
              "scatter.correlation: the correlations of friction_coefficient, allowable_bending_stress are nearly "
              "singular (smallest eigenvalue 1e-13, below 1e-12"),
    scattered("correlation-not-positive-definite",
              'friction_coefficient = [0.12, 0.18]\nallowable_bending_stress = "+-5 %"\nspeed = "+-5 %"\n'
              "[scatter.correlation]\nfriction_coefficient.allowable_bending_stress = 0.9\n"
              "friction_coefficient.speed = 0.9\nallowable_bending_stress.speed = -0.9",
              "scatter.correlation: the correlations of friction_coefficient, allowable_bending_stress, speed are not "
              "positive definite (no joint distribution has them"),
    # --- choose-coupling's [couplings.NAME]: the user's own override is the case's error, not a coupling's loss ------
    override("override-mode-list", '[couplings.wedge.options]\nmode = ["geometry"]',
             "couplings.wedge.options.mode: must be a mode of the wedge coupling (paper, geometry), got ['geometry']"),
    override("override-mode-unknown", '[couplings.wedge.options]\nmode = "fancy"',
             "couplings.wedge.options.mode: must be a mode of the wedge coupling (paper, geometry), got 'fancy'"),
    override("override-coupling-swapped", '[couplings.wedge]\ncoupling = "lever"',
             "couplings.wedge.coupling: not a section of a wedge case"),
    override("override-duty", '[couplings.wedge.duty]\ninertia = "0.4 kg*m^2"',
             "couplings.wedge.duty: the duty and the drive are one for every coupling"),
    override("override-driven", '[couplings.lever.start_up.driven]\ninertia = "0.4 kg*m^2"',
             "couplings.lever.start_up.driven: the duty and the drive are one for every coupling"),
    override("override-start-time", '[couplings.ball.start_up.limits]\nmax_start_time = "20 s"',
             "couplings.ball.start_up.limits.max_start_time: the duty and the drive are one for every coupling"),
    # --- the machine's starts per hour and the air around it, one coupling's own: it was ranked at 1 start an hour or
    #     30 degC against the others at 12 and 40 degC, "like for like", exit 0 without a word ----------------------
    override("override-starts-per-hour", '[couplings.ball.start_up.limits]\nstarts_per_hour = "1 1/hour"',
             "couplings.ball.start_up.limits.starts_per_hour: the duty and the drive are one for every coupling"),
    override("override-ambient", '[couplings.lever.start_up.heat]\nambient = "30 degC"',
             "couplings.lever.start_up.heat.ambient: the air around the coupling is one for every coupling"),
    override("override-housing", '[couplings.lever.start_up.heat]\nconductance = "8 W/K"', None),
    override("override-title", '[couplings.ball]\ntitle = "mine"', "couplings.ball.title: not a section of a ball case"),
    override("override-bad-value", '[couplings.wedge.geometry]\nflank_angle = "95 deg"',
             "couplings.wedge.geometry.flank_angle: "),
    override("override-unknown-key", '[couplings.wedge.geometry]\nflank_angel = "15 deg"',
             "couplings.wedge.geometry.flank_angel: unknown key (did you mean 'flank_angle'?)"),
    override("override-section-not-a-table", '[couplings.wedge]\ngeometry = 5', "couplings.wedge.geometry: must be"),
    override("override-scatter", '[couplings.wedge.scatter]\nfriction_coefficient = "+-20 %"',
             "couplings.wedge.scatter: choose-coupling designs every coupling at its nominal values"),
    override("override-objective", '[couplings.wedge.options]\nobjective = "cost"',
             "couplings.wedge.options.objective: choose-coupling designs every coupling for least like-for-like mass"),
    override("override-choose", '[couplings.wedge.options]\nchoose = {friction_pair = ["organic_dry", "cermet_dry"]}',
             "couplings.wedge.options.choose: choose-coupling designs one entry of each role"),
    neutral("rated-power-twice", 'power = "15 kW"', 'power = "30 kW"',
            "duty.power: 30 kW is not the rated_power of the nameplate motor in [start_up.driver], 15 kW"),
    neutral("rated-torque-twice", 'power = "15 kW"', 'torque = "150 N*m"',
            "duty.torque: 150 N*m is not the rated torque of the nameplate motor in [start_up.driver], 98.1092 N*m"),
    # --- a bad setting of the neutral [start_up]: its field named, not "no coupling can be posed: wedge: ... | ..." --
    neutral("neutral-start-up-unknown-key", "[start_up.driver]", "colour = 1\n\n[start_up.driver]",
            "error: start_up.colour: unknown key; [start_up] takes driven, driver, effects"),
    neutral("neutral-start-up-effect-unknown", '"lockup", "friction_heat"]', '"lockup", "friction_heat", "magic"]',
            "error: start_up.effects: unknown effect 'magic'"),
    neutral("neutral-start-up-intervals", "[start_up.driver]", "intervals = 1000\n\n[start_up.driver]",
            "error: start_up.intervals: must be a whole number from 2 to 128, got 1000"),
    # --- a bad [limits] or [library] of the neutral case: three couplings "not posed", the fourth ranked, exit 0 ------
    neutral("neutral-library-entry-unknown", 'friction_pair = "organic_dry"', 'friction_pair = "organic_dryy"',
            "library.friction_pair: unknown friction pair 'organic_dryy'"),
    neutral("neutral-library-role-unknown", 'friction_pair = "organic_dry"', 'frictionpair = "organic_dry"',
            "library.frictionpair: no coupling has this role (did you mean 'friction_pair'?)"),
    neutral("neutral-limit-wrong-unit", 'outer_diameter_max = "400 mm"', 'outer_diameter_max = "400 kg"',
            "limits.outer_diameter_max: expected a length (e.g. in mm), got '400 kg'"),
    neutral("neutral-limit-negative", 'outer_diameter_max = "400 mm"', 'outer_diameter_max = "-400 mm"',
            "limits.outer_diameter_max: must be > 0"),
    neutral("neutral-limit-unknown", 'outer_diameter_max = "400 mm"', 'outer_diameter_maxx = "400 mm"',
            "limits.outer_diameter_maxx: no coupling declares this limit (did you mean 'outer_diameter_max'?)"),
    neutral("neutral-conductance-zero", 'conductance = "5 W/K"', 'conductance = "0 W/K"',
            "start_up.heat.conductance: 0 W/K with starts_per_hour: give the housing's conductance above 0 W/K"),
    neutral("neutral-lining-limit-below-ambient", 'min_life = "500 h"',
            'min_life = "500 h"\nmax_lining_temperature = "30 degC"',
            "start_up.limits.max_lining_temperature: 30 degC is not above the ambient temperature 40 degC"),
    neutral("neutral-title-escape", 'title = "Belt conveyor', 'title = "\\u001b[2JBelt conveyor',
            "title: contains the control character '\\x1b'"),
    neutral("neutral-title-table", 'title = "Belt conveyor, 15 kW 4-pole motor, 4 kg m^2, 60 N m"', "title = {a = 1}",
            "title: must be text, got dict"),
    neutral("neutral-description-number", 'coupling = "any"', 'coupling = "any"\ndescription = 5',
            "description: must be text, got int"),
    # --- an absolute temperature as a bare number: read as kelvin, 40 became -233 degC -------------------------------
    heat("ambient-bare-number", MOTOR, 'conductance = "4 W/K"', 'conductance = "4 W/K"\nambient = 40',
         "start_up.heat.ambient: a bare number is ambiguous for a temperature: write '40 degC' or '40 K'"),
    heat("lining-limit-bare-number", LINING, 'max_temperature_rise = "30 K"',
         'max_temperature_rise = "30 K"\nmax_lining_temperature = 250',
         "start_up.limits.max_lining_temperature: a bare number is ambiguous for a temperature"),
    # --- a wear allowance thicker than the lining: 100 mm of a 4 mm lining gave 129,239 h of life, exit 0 ----------
    heat("allowance-beyond-the-lining", LINING, 'conductance = "10 W/K"',
         'conductance = "10 W/K"\n[start_up.wear]\nallowance = "100 mm"',
         "start_up.wear.allowance: 100 mm is more than geometry.lining_thickness 4 mm: a lining cannot wear away more"),
    heat("allowance-the-lining", LINING, 'conductance = "10 W/K"',
         'conductance = "10 W/K"\n[start_up.wear]\nallowance = "4 mm"', None),
    case("sweep-lining-below-allowance", edit(LINING, 'conductance = "10 W/K"',
                                              'conductance = "10 W/K"\n[start_up.wear]\nallowance = "3 mm"'),
         "--vary (point 1): start_up.wear.allowance: 3 mm is more than geometry.lining_thickness 2 mm",
         "--vary", "lining_thickness=4,2", "--quiet", "--no-store", command="sweep"),
    # --- an overload friction below the case's own: max(f, f_max) set it aside, exit 0 -------------------------------
    heat("overload-friction-below-nominal", LINING, "check = false", "friction_max = 0.1",
         "start_up.overload.friction_max: 0.1 is below the case's friction_coefficient 0.3"),
    heat("overload-friction-at-nominal", LINING, "check = false", "check = false\nfriction_max = 0.3", None),
    # --- an overload check asked of the cable (an elastic link: none is made), exit 0 without a word ---------------
    heat("overload-check-of-an-elastic-link", CABLE, "[start_up.driver]", "[start_up.overload]\ncheck = true\n\n"
         "[start_up.driver]", "start_up.overload.check: does not apply to the cable coupling: an elastic link"),
    # --- a cable given three fields of a slipping coupling: only the first named, the user fixed them one run at a time
    heat("cable-heat-fields-each-named", CABLE, "[start_up.driver]",
         '[start_up.heat]\ncapacity = "1400 J/K"\nconductance = "4 W/K"\n\n[start_up.driver]',
         ("start_up.heat.capacity: does not apply to the cable coupling",
          "start_up.heat.conductance: does not apply to the cable coupling")),
    heat("overload-check-off-of-an-elastic-link", CABLE, "[start_up.driver]", "[start_up.overload]\ncheck = false\n"
         "\n[start_up.driver]", None),
    # --- a conductance given without friction_heat: not used, exit 0 without a word ---------------------------------
    case("conductance-without-friction-heat",
         edit(edit(edit(MOTOR, '"lockup", "friction_heat"]', '"lockup"]'), 'capacity = "1400 J/K"\n', ""),
              'max_temperature_rise = "4 K"\n', ""),
         "start_up.heat.conductance: given, but effects do not list friction_heat", "--no-store"),
    heat("ambient-in-kelvin", MOTOR, 'conductance = "4 W/K"', 'conductance = "4 W/K"\nambient = "313.15 K"', None),
    heat("ambient-in-fahrenheit", MOTOR, 'conductance = "4 W/K"', 'conductance = "4 W/K"\nambient = "104 degF"', None),
    heat("rise-bare-number", MOTOR, 'max_temperature_rise = "4 K"', "max_temperature_rise = 4", None),
]


if __name__ == "__main__":
    write_all(Path(sys.argv[1] if len(sys.argv) > 1 else "hostile-surfaces"), HOSTILE)

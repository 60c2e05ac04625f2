"""Hostile inputs for every command: generated case files, scenes, design files, sweep tables and command lines.

Each input says what a correct answer is: ``expect`` is text the ``error:`` lines must contain (exit code 2), or
None where the input is in fact fine (exit code 0). ``tests/test_hostile.py`` runs them all through the CLI;
run as a script, this module writes every input to a folder and prints its command line::

    python tests/hostile.py /tmp/hostile        # then e.g. clutchopt solve /tmp/hostile/<name>/case.toml

Classes: numbers and unit strings (beyond float64, giant powers, Unicode minus, control characters, ambiguous
speed units), files (encodings, byte-order marks, NUL bytes, nesting, size, FIFOs, devices, folders), case
structure, scenes and design files at and beyond their ranges, sweep tables, and the command line of every
command (solve, compare, simulate, sweep, pareto, report, runs list/show/export, bench).
"""

from __future__ import annotations

import codecs
import json
import os
import sqlite3
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
WEDGE = (CASES / "wedge_paper.toml").read_text()
LEVER = (CASES / "lever_centrifuge.toml").read_text()
SCENE = (CASES / "scenes" / "paper_transient.toml").read_text()
DESIGN = json.loads((CASES / "designs" / "wedge_paper.json").read_text())
DESIGN["case"] = "wedge_paper.toml"  # the scenes below name the case beside them


class Special:
    """A file that is not a regular file with content: a FIFO, a folder, a symbolic link to itself."""

    def __init__(self, kind: str):
        self.kind = kind


FIFO, FOLDER, LOOP, OTHER_DATABASE = Special("fifo"), Special("folder"), Special("loop"), Special("sqlite")


@dataclass(frozen=True)
class Hostile:
    name: str
    argv: tuple[str, ...]  # "{dir}" stands for the folder the files are written to
    expect: str | tuple[str, ...] | None  # text of the error lines (exit code 2, each text in them), or None:
    #                                        the input is fine (exit code 0)
    files: tuple[tuple[str, object], ...] = ()  # (file name, str | bytes | Special)
    subprocess: bool = False  # run as a user does, in a process of its own

    def write(self, folder: Path) -> list[str]:
        """Write the files into ``folder``; the command line with ``{dir}`` filled in."""
        folder.mkdir(parents=True, exist_ok=True)
        for name, content in self.files:
            path = folder / name
            if content is FIFO:
                os.mkfifo(path)
            elif content is FOLDER:
                path.mkdir()
            elif content is LOOP:
                path.symlink_to(path.name)
            elif content is OTHER_DATABASE:
                with sqlite3.connect(path) as db:
                    db.execute("CREATE TABLE invoices (id INTEGER PRIMARY KEY, amount REAL)")
                db.close()
            elif isinstance(content, bytes):
                path.write_bytes(content)
            else:
                path.write_text(content, encoding="utf-8")
        return [arg.replace("{dir}", str(folder)) for arg in self.argv]


def edit(text: str, old: str, new: str) -> str:
    assert old in text, old  # the edit must change the input, or the test would test nothing
    return text.replace(old, new, 1)


def case(name: str, text: str | bytes | Special, expect: str | None, *extra: str, command: str = "solve",
         subprocess: bool = False) -> Hostile:
    return Hostile(name, (command, "{dir}/case.toml", *extra), expect, (("case.toml", text),), subprocess)


def quantity(name: str, old: str, new: str, expect: str | None) -> Hostile:
    """The wedge case with one value replaced."""
    return case(name, edit(WEDGE, old, new), expect)


def inertia(name: str, value: str, expect: str | None) -> Hostile:
    return quantity(name, 'inertia = "0.5 kg*m^2"', f"inertia = {value}", expect)


def speed(name: str, value: str, expect: str | None) -> Hostile:
    return quantity(name, 'speed = "1000 rpm"', f"speed = {value}", expect)


def scene(name: str, text: str, expect: str | None, *files: tuple[str, object]) -> Hostile:
    return Hostile(name, ("simulate", "{dir}/scene.toml"), expect, (("scene.toml", text), *files))


def scene_value(name: str, old: str, new: str, expect: str | None) -> Hostile:
    return scene(name, edit(SCENE, old, new), expect)


def design(name: str, content: object, expect: str | None) -> Hostile:
    """A centrifugal scene started from a design file (the JSON of clutchopt solve), edited."""
    text = content if isinstance(content, (str, bytes)) else json.dumps(content)
    return scene(name, 'effects = ["slip_friction", "lockup"]\n[coupling]\nlaw = "centrifugal"\n'
                       'case = "wedge_paper.toml"\ndesign = "design.json"\n', expect,
                 ("wedge_paper.toml", WEDGE), ("design.json", text))


def designed(**values) -> dict:
    data = json.loads(json.dumps(DESIGN))
    data["design"].update(values)
    return data


def command(name: str, argv: tuple[str, ...], expect: str | None, *files: tuple[str, object],
            subprocess: bool = False) -> Hostile:
    return Hostile(name, argv, expect, files, subprocess)


def paper(name: str, command_name: str, *extra: str, expect: str | None) -> Hostile:
    """A command on the paper's worked example (cases/wedge_paper.toml)."""
    return command(name, (command_name, str(CASES / "wedge_paper.toml"), *extra), expect)


def sweep(name: str, *extra: str, expect: str | None) -> Hostile:
    return command(name, ("sweep", "{dir}/case.toml", "--quiet", *extra), expect, ("case.toml", WEDGE))


def table(name: str, content: str | bytes | Special, expect: str | None, file: str = "sweep.csv") -> Hostile:
    """``report --sweep`` with a sweep table."""
    return command(name, ("report", "{dir}/case.toml", "-o", "{dir}/review.html", "--sweep", f"{{dir}}/{file}"),
                   expect, ("case.toml", WEDGE), (file, content))


START_UP = """
[start_up]
effects = ["slip_friction", "motor_curve", "lockup", "friction_heat"]
[start_up.driver]
synchronous_speed = "1000 rpm"
breakdown_torque = "37 N*m"
breakdown_slip = 0.2
inertia = "0.012 kg*m^2"
[start_up.heat]
capacity = "1400 J/K"
"""
SWEEP_TABLE = "point,speed [rpm],status,mass [kg],weight_mass [kg]\n0,900,optimal,0.8,0.2\n1,1000,infeasible,,\n"
MISSING_DUTY = edit(edit(edit(edit(WEDGE, 'inertia = "0.5 kg*m^2"\n', ""), 'speed = "1000 rpm"\n', ""),
                         'acceleration_time = "10 s"\n', ""), 'resisting_torque = "5 N*m"\n', "")
TWELVE_PROBLEMS = edit(edit(edit(edit(edit(edit(edit(edit(MISSING_DUTY,
    'friction_coefficient = 0.15', 'friction_coefficient = 1.5'), '"4 MPa"', '"4 kg"'), '"160 MPa"', '"nan MPa"'),
    '"7850 kg/m^3"', "-1"), "radius_ratio = 1.2", "radius_ratio = 0.9"), "weight_count = 4", "weight_count = 2.5"),
    '"15 deg"', '"95 deg"'), '["5 mm", "40 mm"]', '["40 mm", "5 mm"]')
TWELVE_FIELDS = ("duty.inertia", "duty.speed", "duty.acceleration_time", "duty.resisting_torque",
                 "material.friction_coefficient", "material.allowable_pressure", "material.allowable_bending_stress",
                 "material.density", "geometry.radius_ratio", "geometry.weight_count", "geometry.flank_angle",
                 "bounds.weight_width")

HOSTILE: list[Hostile] = [
    # --- numbers and unit strings --------------------------------------------------------------------------------
    inertia("beyond-float64", '"1e400 kg*m^2"', "duty.inertia: must be a finite number"),
    inertia("bare-400-digits", "1" + "0" * 400, "duty.inertia: 401-digit number is beyond the float64 range"),
    inertia("bare-5000-digits", "1" * 5000, "not valid TOML: Exceeds the limit"),
    inertia("text-400-digits", '"1' + "0" * 400 + ' kg*m^2"', "duty.inertia: text of 408 characters is too long"),
    inertia("bare-toml-inf", "inf", "duty.inertia: must be a finite number"),
    inertia("bare-toml-nan", "-nan", "duty.inertia: must be a finite number"),
    inertia("text-nan", '"nan kg*m^2"', "duty.inertia: must be a finite number"),
    inertia("text-minus-inf", '"-inf kg*m^2"', "duty.inertia: must be a finite number"),
    inertia("underflow-to-zero", '"1e-400 kg*m^2"', "duty.inertia: 1e-400 is below the float64 range: it would be "
            "read as 0"),
    inertia("giant-unit-power", '"1 m**99999999"', "unit power 99999999 is out of range"),
    inertia("giant-unit-power-caret", '"1 kg*m^99999"', "unit power 99999 is out of range"),
    inertia("nested-powers", '"1 ((kg*m^2)^2)^0.5"', None),
    inertia("nested-too-deep", '"1 (((kg)))*m^2"', "parentheses nested too deeply"),
    inertia("power-of-a-number", '"2**99999999 kg*m^2"', "a number inside the unit (99999999)"),
    inertia("tower-of-powers", '"10**10**10 kg*m^2"', "a number inside the unit"),
    inertia("parenthesised-power", '"(1 m**99)**99"', "duty.inertia: cannot read"),
    inertia("unit-power-13", '"1 Ym^13"', "unit power 13 is out of range (at most 12)"),
    inertia("nul", '"0.5\\u0000 kg*m^2"', "duty.inertia: contains the control character '\\x00'"),
    inertia("escape-sequence", '"0.5 kg*m^2\\u001b[2J"', "duty.inertia: contains the control character '\\x1b'"),
    inertia("zero-width-space", '"0.5 kg*m^2\\u200b"', "duty.inertia: contains the control character"),
    inertia("fullwidth-digits", '"\uff10.5 kg*m^2"', "duty.inertia: cannot read"),
    inertia("en-dash-in-unit", '"0.5 kg*m\u20132"', "unexpected character '\u2013'"),
    inertia("empty-text", '""', "duty.inertia: cannot read ''"),
    inertia("blank-text", '"   "', "duty.inertia: cannot read"),
    inertia("unit-only", '"kg*m^2"', "duty.inertia: cannot read 'kg*m^2'"),
    inertia("unknown-unit", '"0.5 blorbs*m"', "unknown unit 'blorbs'"),
    inertia("hex-number", '"0x10 kg*m^2"', "duty.inertia: cannot read"),
    inertia("two-numbers", '"0.5 kg*m^2 2"', "a number inside the unit (2)"),
    inertia("python-expression", '"__import__(\'os\') kg"', "duty.inertia: cannot read"),
    inertia("wrong-dimension", '"0.5 MPa"', "duty.inertia: expected a moment of inertia"),
    inertia("boolean", "true", "duty.inertia: expected a quantity in kg*m^2, got a boolean"),
    inertia("date", "1979-05-27", "duty.inertia: expected a quantity in kg*m^2, got date"),
    inertia("table", "{ value = 0.5 }", "duty.inertia: expected a quantity in kg*m^2, got dict"),
    inertia("long-list", "[" + ", ".join(["1"] * 20000) + "]", "duty.inertia: expected a quantity in kg*m^2, got list"),
    inertia("superscripts", '"0.5 kg\u00b7m\u00b2"', None),
    quantity("unicode-minus-read-as-minus", '"10 s"', '"\u221210 s"',
             "duty.acceleration_time: must be > 0 s, got -10 s"),
    speed("speed-in-hz", '"16.6667 Hz"', "duty.speed: '16.6667 Hz' is ambiguous"),
    speed("speed-in-per-second", '"104.7 1/s"', "duty.speed: '104.7 1/s' is ambiguous"),
    speed("speed-in-khz", '"0.0167 kHz"', "is ambiguous"),
    speed("speed-per-minute", '"1000 1/min"', "is ambiguous"),
    speed("speed-in-rps", '"16.6667 rps"', None),
    speed("speed-in-rev-per-min", '"1000 rev/min"', None),
    speed("speed-in-rad-per-s", '"104.72 rad/s"', None),
    speed("speed-in-degrees", '"1000 deg"', "duty.speed: expected an angular speed"),
    quantity("angle-in-percent", '"15 deg"', '"15 %"', "geometry.flank_angle: expected an angle"),
    quantity("count-nearly-whole", "weight_count = 4", "weight_count = 4.0000001",
             "geometry.weight_count: must be a whole number, got 4.0000001"),
    quantity("count-huge", "weight_count = 4", "weight_count = 1e300", "geometry.weight_count: 1e+300 (SI) is"),
    quantity("count-too-many", "weight_count = 4", "weight_count = 1000", "geometry.sector_angle"),
    quantity("ratio-nearly-one", "radius_ratio = 1.2", "radius_ratio = 0.99999999999", "got 0.99999999999"),
    # --- files ---------------------------------------------------------------------------------------------------
    case("utf-16-with-bom", WEDGE.encode("utf-16"), "is UTF-16 text; save it as UTF-8"),
    case("utf-16-big-endian", codecs.BOM_UTF16_BE + WEDGE.encode("utf-16-be"), "is UTF-16 text"),
    case("utf-16-without-bom", WEDGE.encode("utf-16-le"), "contains NUL bytes"),
    case("utf-32", WEDGE.encode("utf-32"), "is UTF-32 text"),
    case("latin-1", ("# r\u00e9sum\u00e9\n" + WEDGE).encode("latin-1"), "is not UTF-8 text (byte 0xe9"),
    case("random-bytes", bytes(range(256)) * 8, "contains NUL bytes"),
    case("random-high-bytes", bytes(range(128, 256)) * 8, "is not UTF-8 text"),
    case("utf-8-bom", codecs.BOM_UTF8 + WEDGE.encode(), None, subprocess=True),
    case("nul-inside", WEDGE.replace("[duty]", "[duty]\x00", 1).encode(), "contains NUL bytes"),
    case("empty-file", "", "coupling: missing"),
    case("comments-only", "# nothing\n# here\n", "coupling: missing"),
    case("deep-arrays", "x = " + "[" * 100000 + "]" * 100000 + "\n", "nested too deeply"),
    case("deep-inline-tables", "x = " + "{a=" * 5000 + "1" + "}" * 5000 + "\n", "nested too deeply"),
    case("deep-dotted-keys", "x" + ".x" * 3000 + " = 1\n" + WEDGE, "x: unknown section or key"),
    case("over-one-mebibyte", WEDGE + "#" + "x" * (1 << 20) + "\n", "too large (at most 1 MiB)"),
    case("fifo", FIFO, "cannot read a FIFO (named pipe); expected a regular file", subprocess=True),
    case("folder", FOLDER, "cannot read a folder"),
    case("symlink-loop", LOOP, "cannot read"),
    command("device-zero", ("solve", "/dev/zero"), "cannot read a character device", subprocess=True),
    command("device-null", ("solve", "/dev/null"), "cannot read a character device"),
    command("no-such-file", ("solve", "{dir}/nowhere.toml"), "nowhere.toml: no such file"),
    command("empty-file-name", ("solve", ""), "'': no such file"),
    # --- case structure ------------------------------------------------------------------------------------------
    case("twelve-problems-at-once", TWELVE_PROBLEMS, tuple(f"error: {name}: " for name in TWELVE_FIELDS)),
    case("free-list-of-lists", WEDGE + '\n[options]\nfree = [["flank_angle"]]\n', "options.free: must be a list"),
    case("free-list-of-tables", WEDGE + '\n[options]\nfree = [{a = 1}]\n', "options.free: must be a list"),
    case("free-text", WEDGE + '\n[options]\nfree = "flank_angle"\n', "options.free: must be a list"),
    case("free-twice", WEDGE + '\n[options]\nfree = ["flank_angle", "flank_angle"]\n', "options.free: lists a "),
    case("free-number", WEDGE + '\n[options]\nfree = 5\n', "options.free: must be a list"),
    case("options-not-a-table", "options = 5\n" + WEDGE, "options: must be a table"),
    case("options-mode-empty", WEDGE + '\n[options]\nmode = ""\n', "options.mode: must be a name"),
    case("options-mode-list", WEDGE + '\n[options]\nmode = ["geometry"]\n', "options.mode: must be a name"),
    case("options-objective-number", WEDGE + '\n[options]\nobjective = 5\n', "options.objective: must be a name"),
    case("options-mode-unknown", WEDGE + '\n[options]\nmode = "fancy"\n', "mode: unknown mode 'fancy'"),
    case("bounds-not-a-table", edit(WEDGE, "[bounds]\nweight_width", "[bounds2]\nweight_width"),
         "bounds2: unknown section or key (did you mean 'bounds'?)"),
    case("bounds-three-values", edit(WEDGE, '["5 mm", "40 mm"]', '["5 mm", "20 mm", "40 mm"]'),
         "bounds.weight_width: must be a pair"),
    case("bounds-nan", edit(WEDGE, '["5 mm", "40 mm"]', '["nan mm", "40 mm"]'),
         "bounds.weight_width: must be a finite"),
    case("bounds-huge", edit(WEDGE, '["5 mm", "40 mm"]', '["1e-300 mm", "1e300 mm"]'),
         "bounds.weight_width: 1e-303 m (SI) is outside the magnitudes clutchopt works with"),
    case("bounds-wide", edit(WEDGE, '["5 mm", "40 mm"]', '["1e-6 mm", "1e6 mm"]'), None),
    speed("speed-beyond-magnitudes", '"1e300 rpm"', "duty.speed: 1.0472e+299 rad/s (SI) is outside the magnitudes"),
    inertia("inertia-beyond-magnitudes", '"1e-300 kg*m^2"', "duty.inertia: 1e-300 kg*m^2 (SI) is outside"),
    quantity("density-at-magnitude-limit", '"7850 kg/m^3"', '"1e18 kg/m^3"', None),
    case("section-not-a-table", edit(WEDGE, "[duty]\n", "duty = 5\n[duty2]\n"), "duty: must be a table [duty]"),
    case("section-misspelt", edit(WEDGE, "[material]", "[materials]"), "(did you mean 'material'?)"),
    case("key-misspelt", edit(WEDGE, "friction_coefficient", "friction_coeficient"),
         "material.friction_coeficient: unknown key (did you mean 'friction_coefficient'?)"),
    case("top-level-key-unknown", edit(WEDGE, 'title = "Amb', 'title2 = "Amb'), "title2: unknown section or key"),
    case("title-not-text", "title = 5\n" + edit(WEDGE, 'title = "', 'subtitle = "'), "title: must be text"),
    case("title-escape-sequence", edit(WEDGE, 'title = "', 'title = "\\u001b[2J'), "title: contains the control"),
    case("title-too-long", edit(WEDGE, 'title = "', 'title = "' + "x" * 5000), "title: text of 5"),
    case("coupling-number", edit(WEDGE, 'coupling = "wedge"', "coupling = 5"), "coupling: unknown coupling 5"),
    case("coupling-empty", edit(WEDGE, 'coupling = "wedge"', 'coupling = ""'), "coupling: unknown coupling ''"),
    case("coupling-list", edit(WEDGE, 'coupling = "wedge"', 'coupling = ["wedge"]'), "coupling: unknown coupling"),
    case("many-unknown-keys", edit(WEDGE, "[duty]\n", "[duty]\n" + "".join(f"k{i} = 1\n" for i in range(2000))),
         "... and 1950 more problems"),
    case("start-up-motor-too-fast", WEDGE + START_UP.replace('"1000 rpm"', '"1e7 rpm"'),
         "start_up.driver.synchronous_speed: must be from 0.001 to 100000 rad/s"),
    case("start-up-no-breakdown-slip", WEDGE + START_UP.replace("breakdown_slip = 0.2", "breakdown_slip = 0"),
         "start_up.driver.breakdown_slip: must be > 0"),
    case("start-up-tiny-heat-capacity", WEDGE + START_UP.replace('"1400 J/K"', '"1e-9 J/K"'),
         "start_up.heat.capacity: must be from 1e-06 to 1e+12 J/K"),
    case("start-up-profile-in-hz", WEDGE + START_UP + '[start_up.driven.load_profile]\nover = "speed"\n'
         'points = ["0 Hz", "10 Hz"]\ntorque = [0, 5]\n', "start_up.driven.load_profile.points[0]: '0 Hz' is"),
    case("start-up-rise-in-celsius", WEDGE + START_UP + '[start_up.limits]\nmax_temperature_rise = "15 degC"\n',
         "start_up.limits.max_temperature_rise: '15 degC' is a temperature on a scale with an offset"),
    case("scatter-triple", WEDGE + "[scatter]\nfriction_coefficient = [0.1, 0.15, 0.2]\n",
         "scatter.friction_coefficient: must be a pair"),
    case("scatter-two-distributions", WEDGE + '[scatter]\nfriction_coefficient = { normal = [0.15, 0.01], '
         'uniform = [0.1, 0.2] }\n', "scatter.friction_coefficient: must be [low, high]"),
    case("scatter-nan", WEDGE + '[scatter]\nfriction_coefficient = ["nan", 0.2]\n',
         "scatter.friction_coefficient: must be a finite number"),
    case("scatter-huge-sd", WEDGE + '[scatter]\ninertia = { normal = ["0.5 kg*m^2", "1e300 kg*m^2"] }\n',
         "scatter.inertia.normal"),
    case("scatter-wrong-dimension", WEDGE + '[scatter]\ninertia = ["1 kg", "2 kg"]\n', "scatter.inertia"),
    case("scatter-unknown", WEDGE + "[scatter]\nfrictoin_coefficient = [0.1, 0.2]\n", "scatter.frictoin_coefficient"),
    case("scatter-too-many", WEDGE + "[scatter]\n" + "".join(f"q{i} = [0, 1]\n" for i in range(13)),
         "scatter: at most 12"),
    case("scatter-excludes-nominal", WEDGE + "[scatter]\nfriction_coefficient = [0.2, 0.3]\n",
         "scatter.friction_coefficient: the case's value 0.15 lies outside"),
    case("robust-empty", WEDGE + "[scatter]\nfriction_coefficient = [0.1, 0.2]\n", "--robust: expected", "--robust", ""),
    case("robust-certain", WEDGE + "[scatter]\nfriction_coefficient = [0.1, 0.2]\n", "--robust: chance=P needs",
         "--robust", "chance=1"),
    case("robust-no-scatter", WEDGE, "--robust: the case has no [scatter] section", "--robust", "worst-case"),
    case("samples-without-robust", WEDGE, "--samples: counts the Monte Carlo samples", "--samples", "100"),
    case("samples-huge", WEDGE + "[scatter]\nfriction_coefficient = [0.1, 0.2]\n", "--samples: must be a whole",
         "--robust", "worst-case", "--samples", str(10**12)),
    case("lever-limit-above-engagement", edit(LEVER, 'engagement_angle = "15 deg"', 'engagement_angle = "2 deg"'),
         "geometry.engagement_angle: must exceed the limit angle"),
    # --- scenes --------------------------------------------------------------------------------------------------
    scene_value("scene-inertia-tiny", '"2 kg*m^2"', '"1e-300 kg*m^2"', "driven.inertia: must be from 1e-09"),
    scene_value("scene-inertia-huge", '"2 kg*m^2"', '"1e300 kg*m^2"', "driven.inertia: must be from 1e-09"),
    scene_value("scene-inertia-at-low-end", '"2 kg*m^2"', '"1e-9 kg*m^2"', None),
    scene_value("scene-inertia-at-high-end", '"2 kg*m^2"', '"1e9 kg*m^2"', None),
    scene_value("scene-k-huge", '"50 N*m"', '"1e308 N*m"', "coupling.k: must be from 1e-09 to 1e+09 N*m"),
    scene_value("scene-k-negative", '"50 N*m"', '"-50 N*m"', "coupling.k: must be from"),
    scene_value("scene-k-zero", '"50 N*m"', "0", "coupling.k: must be from"),
    scene_value("scene-k-at-high-end", '"50 N*m"', '"1e9 N*m"', None),
    scene_value("scene-a-huge", '"-0.01 s/rad"', '"1e300 s/rad"', "coupling.a: must be from -1e+06"),
    scene_value("scene-a-unicode-minus", '"-0.01 s/rad"', '"\u22120.01 s/rad"', None),
    scene_value("scene-speed-huge", '"1500 rpm"', '"1e300 rpm"', "driver.speed: must be from 0.001 to 100000 rad/s"),
    scene_value("scene-speed-tiny", '"1500 rpm"', '"1e-300 rpm"', "driver.speed: must be from"),
    scene_value("scene-speed-in-hz", '"1500 rpm"', '"25 Hz"', "driver.speed: '25 Hz' is ambiguous"),
    scene_value("scene-load-huge", '"20 N*m"', '"1e308 N*m"', "driven.resisting_torque: must be from 0"),
    scene_value("scene-load-negative", '"20 N*m"', '"-20 N*m"', "driven.resisting_torque: must be from 0"),
    scene_value("scene-heat-zero", '"2300 J/K"', "0", "heat.capacity: must be from"),
    scene("scene-end-time-huge", 'end_time = "1e300 s"\n' + SCENE, "end_time: must be from 1e-09 to 1e+09 s"),
    scene("scene-end-time-negative", 'end_time = "-1 s"\n' + SCENE, "end_time: must be from"),
    scene("scene-tolerance-tiny", "tolerance = 1e-300\n" + SCENE, "tolerance: must be from 1e-14"),
    scene("scene-tolerance-loose", "tolerance = 0.5\n" + SCENE, "tolerance: must be from 1e-14 to 0.001"),
    scene("scene-profile-long", edit(SCENE, 'resisting_torque = "20 N*m"', 'load_profile = {over = "time", points = ['
                                     + ", ".join(map(str, range(5000))) + "], torque = [" + ", ".join(["1"] * 5000)
                                     + "]}"), "points and torque must be lists of the same length (2 to 1000)"),
    scene("scene-profile-decreasing", edit(SCENE, 'resisting_torque = "20 N*m"', 'load_profile = {over = "speed", '
                                           'points = [2, 1], torque = [1, 2]}'), "load_profile.points: must increase"),
    scene("scene-profile-huge-torque", edit(SCENE, 'resisting_torque = "20 N*m"', 'load_profile = {over = "speed", '
                                            'points = [0, 1], torque = [0, 1e300]}'),
          "load_profile.torque: must be at"),
    scene("scene-profile-over-what", edit(SCENE, 'resisting_torque = "20 N*m"', 'load_profile = {over = "mood", '
                                          'points = [0, 1], torque = [0, 1]}'), "load_profile.over"),
    scene("scene-effects-nested", edit(SCENE, 'effects = ["slip_friction"', 'effects = [["slip_friction"]'),
          "effects: must be a list of effect names"),
    scene("scene-effects-twice", edit(SCENE, '"lockup"', '"lockup", "lockup"'), "effects: lists an effect twice"),
    scene("scene-effects-unknown", edit(SCENE, '"lockup"', '"warp_drive"'), "unknown effect 'warp_drive'"),
    scene("scene-gravity-on-paper-law", edit(SCENE, '"lockup"', '"gravity"'), "gravity applies to centrifugal"),
    scene("scene-law-unknown", edit(SCENE, 'law = "paper"', 'law = "magic"'), "coupling.law: must be one of"),
    scene("scene-law-number", edit(SCENE, 'law = "paper"', "law = 5"), "coupling.law: must be one of"),
    scene("scene-driven-not-a-table", "driven = 5\n" + edit(SCENE, "[driven]\n", "[driven2]\n"),
          "driven: must be a table"),
    scene("scene-title-list", "\n".join('title = ["a", "b"]' if line.startswith("title =") else line
                                         for line in SCENE.splitlines()), "title: must be text"),
    scene("scene-four-problems", edit(edit(edit(edit(SCENE, '"2 kg*m^2"', "-1"), '"50 N*m"', "0"), '"1500 rpm"',
                                                '"1 Hz"'), '"2300 J/K"', '"5 kg"'),
          ("driven.inertia: must be from 1e-09 to 1e+09 kg*m^2 (the range the simulator is tested over), got -1",
           "coupling.k: must be from", "driver.speed: '1 Hz' is ambiguous", "heat.capacity: expected a heat capacity")),
    scene("scene-motor-slip-zero", edit(edit(SCENE, '"lockup"', '"lockup", "motor_curve"'), 'speed = "1500 rpm"',
                                        'synchronous_speed = "1500 rpm"\nbreakdown_torque = "200 N*m"\n'
                                        'breakdown_slip = 0\ninertia = "0.05 kg*m^2"'),
          "driver.breakdown_slip: must be from 1e-06 to 0.99"),
    scene("scene-motor-tiny", edit(edit(SCENE, '"lockup"', '"lockup", "motor_curve"'), 'speed = "1500 rpm"',
                                   'synchronous_speed = "1500 rpm"\nbreakdown_torque = "1e-300 N*m"\n'
                                   'breakdown_slip = 0.2\ninertia = "1e-300 kg*m^2"'),
          "driver.breakdown_torque: must be from 1e-09 to 1e+09 N*m"),
    scene("scene-case-missing", 'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\n',
          "coupling.case: missing"),
    scene("scene-case-fifo", 'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\ncase = "pipe.toml"\n',
          "cannot read a FIFO", ("pipe.toml", FIFO)),
    scene("scene-case-not-text", 'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\ncase = 5\n',
          "coupling.case: must be a file path"),
    scene("scene-case-with-bad-field", 'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\n'
                                       'case = "bad.toml"\n', "coupling.case (bad.toml): duty.speed",
          ("bad.toml", edit(WEDGE, '"1000 rpm"', '"16.7 Hz"'))),
    scene("scene-utf-16", SCENE.encode("utf-16"), "is UTF-16 text"),
    # --- design files (clutchopt solve --json) -------------------------------------------------------------------
    design("design-as-committed", DESIGN, None),
    design("design-nan", json.dumps(designed(weight_mass=float("nan"))), "NaN is not a number a solved design"),
    design("design-infinity", json.dumps(designed(weight_mass=float("inf"))), "Infinity is not a number"),
    design("design-boolean", designed(weight_mass=True), "design.weight_mass: must be a finite number (SI), got True"),
    design("design-negative", designed(weight_mass=-0.15), "design.weight_mass: must be > 0 kg"),
    design("design-zero-mass", designed(weight_mass=0), "design.weight_mass: must be > 0 kg"),
    design("design-huge", designed(weight_mass=1e308), "design.weight_mass: 1e+308 kg (SI) is outside"),
    design("design-no-usable-law", designed(weight_mass=1e14), "the design gives no usable torque law"),
    design("design-big-integer", designed(weight_mass=10**400), "design.weight_mass: must be a finite number"),
    design("design-text-value", designed(finger_diameter="5 mm"), "design.finger_diameter: must be a finite number"),
    design("design-missing-value", {**DESIGN, "design": {}}, "design.weight_mass: missing: `clutchopt solve --json`"),
    design("design-not-optimal", {**DESIGN, "status": "infeasible"}, "the design's status is 'infeasible'"),
    design("design-other-coupling", {**DESIGN, "coupling": "lever"}, "is not a solved wedge design"),
    design("design-other-case", {**DESIGN, "case": "wedge_fan.toml"}, "was solved for 'wedge_fan.toml'"),
    design("design-list", "[1, 2]", "is not a solved wedge design"),
    design("design-deep", "[" * 100000 + "]" * 100000, "JSON nested too deeply"),
    design("design-broken", '{"coupling": "wedge", ', "cannot read"),
    design("design-utf-16", json.dumps(DESIGN).encode("utf-16"), "is UTF-16 text"),
    # --- command lines: solve, compare -----------------------------------------------------------------------------
    paper("solve-mode-empty", "solve", "--mode", "", expect="argument --mode"),
    paper("solve-mode-blank", "solve", "--mode", " ", expect="argument --mode"),
    paper("solve-mode-unknown", "solve", "--mode", "fancy", expect="mode: unknown mode 'fancy'"),
    paper("solve-objective-empty", "solve", "--objective", "", expect="argument --objective"),
    paper("solve-objective-unknown", "solve", "--objective", "beauty", expect="objective: unknown objective 'beauty'"),
    paper("solve-tol-inf", "solve", "--tol", "inf", expect="argument --tol: must be"),
    paper("solve-tol-nan", "solve", "--tol", "nan", expect="argument --tol: must be"),
    paper("solve-tol-zero", "solve", "--tol", "0", expect="argument --tol: must be"),
    paper("solve-tol-tiny", "solve", "--tol", "1e-300", expect="argument --tol"),
    paper("solve-tol-one", "solve", "--tol", "1", expect="argument --tol"),
    paper("solve-tol-word", "solve", "--tol", "tight", expect="not a number: 'tight'"),
    paper("solve-unknown-flag", "solve", "--fast", expect="unrecognized arguments"),
    command("solve-no-case", ("solve",), "the following arguments are required: case"),
    paper("solve-store-is-a-folder", "solve", "--store", "{dir}", expect=None),
    paper("compare-tol-inf", "compare", "--tol", "inf", expect="argument --tol"),
    command("compare-folder", ("compare", "{dir}"), "cannot read a folder"),
    # --- simulate ------------------------------------------------------------------------------------------------
    command("simulate-plot-missing-folder", ("simulate", str(CASES / "scenes" / "paper_transient.toml"), "--plot",
                                             "{dir}/no/such/folder/plot.png"), "the folder"),
    command("simulate-plot-unknown-suffix", ("simulate", str(CASES / "scenes" / "paper_transient.toml"), "--plot",
                                             "{dir}/plot.xyz"), "--plot: write .png, .svg or .pdf"),
    command("simulate-plot-into-folder", ("simulate", str(CASES / "scenes" / "paper_transient.toml"), "--plot",
                                          "{dir}/plot.png"), "it is a folder", ("plot.png", FOLDER)),
    command("simulate-plot-into-fifo", ("simulate", str(CASES / "scenes" / "paper_transient.toml"), "--plot",
                                        "{dir}/plot.png"), "it is a FIFO", ("plot.png", FIFO)),
    # --- sweep ---------------------------------------------------------------------------------------------------
    sweep("sweep-grid-1e12", "--vary", "speed=500:3000:1000000", "--vary", "inertia=0.1:1:1000000",
          expect="--vary inertia=0.1:1:1000000: 1000000 values; a sweep has at most 100,000 points"),
    sweep("sweep-grid-product", "--vary", "speed=500:3000:1000", "--vary", "inertia=0.1:1:1000",
          expect="--vary: the grid has 1,000,000 points"),
    sweep("sweep-count-1e300", "--vary", "speed=1:2:1e300", expect="a sweep has at most 100,000 points"),
    sweep("sweep-count-zero", "--vary", "speed=1:2:0", expect="a range is start:stop:count with a whole count"),
    sweep("sweep-count-fraction", "--vary", "speed=1:2:2.5", expect="a whole count"),
    sweep("sweep-count-negative", "--vary", "speed=1:2:-3", expect="a whole count"),
    sweep("sweep-vary-twice", "--vary", "speed=800,900", "--vary", "speed=1000",
          expect="--vary: speed varied twice"),
    sweep("sweep-vary-unknown", "--vary", "colour=1,2", expect="unknown quantity 'colour'"),
    sweep("sweep-vary-no-values", "--vary", "speed=", expect="expected name=start:stop:count"),
    sweep("sweep-vary-no-name", "--vary", "=1,2", expect="unknown quantity ''"),
    sweep("sweep-vary-no-equals", "--vary", "speed", expect="expected name=start:stop:count"),
    sweep("sweep-vary-two-parts", "--vary", "speed=1:2", expect="a range is start:stop:count"),
    sweep("sweep-vary-four-parts", "--vary", "speed=1:2:3:4", expect="a range is start:stop:count"),
    sweep("sweep-vary-nan", "--vary", "speed=nan", expect="values must be finite"),
    sweep("sweep-vary-beyond-float64", "--vary", "speed=1e400", expect="values must be finite"),
    sweep("sweep-vary-si-overflow", "--vary", "allowable_pressure=1e308", expect="beyond the float64 range once"),
    sweep("sweep-vary-empty-item", "--vary", "speed=1,,2", expect="not a number"),
    sweep("sweep-vary-out-of-range", "--vary", "inertia=-1", expect="--vary (point 0): duty.inertia: must be > 0"),
    sweep("sweep-vary-three-problems", "--vary", "colour=1", "--vary", "speed=x", "--vary", "inertia=nan",
          expect=("unknown quantity 'colour'", "--vary speed=x: not a number", "--vary inertia=nan: values must")),
    sweep("sweep-zip-unequal", "--vary", "speed=800,900", "--vary", "inertia=1,2,3", "--zip", expect="equally many"),
    sweep("sweep-jobs-zero", "--vary", "speed=800,900", "--jobs", "0", expect="argument --jobs: must be from 1"),
    sweep("sweep-jobs-million", "--vary", "speed=800,900", "--jobs", "1000000", expect="argument --jobs: must be"),
    sweep("sweep-jobs-word", "--vary", "speed=800,900", "--jobs", "two", expect="argument --jobs: not a whole number"),
    sweep("sweep-dask-not-an-address", "--vary", "speed=800", "--dask", "localhost", expect="--dask: expected an"),
    sweep("sweep-dask-port-out-of-range", "--vary", "speed=800", "--dask", "tcp://127.0.0.1:99999",
          expect="port 99999 is out of range"),
    sweep("sweep-dask-nobody-listens", "--vary", "speed=800", "--dask", "tcp://127.0.0.1:9",
          expect="cannot reach a Dask scheduler at tcp://127.0.0.1:9"),
    sweep("sweep-resume-without-store", "--vary", "speed=800", "--resume", "--no-store",
          expect="--resume: continues a sweep from the run store"),
    sweep("sweep-out-unknown-suffix", "--vary", "speed=800", "--out", "{dir}/table.xlsx",
          expect="--out: write .csv, .parquet or .md"),
    sweep("sweep-out-missing-folder", "--vary", "speed=800", "--out", "{dir}/no/table.csv", expect="does not exist"),
    sweep("sweep-mode-empty", "--vary", "speed=800", "--mode", "", expect="argument --mode"),
    sweep("sweep-two-points", "--vary", "speed=800,1200", expect=None),
    # --- pareto --------------------------------------------------------------------------------------------------
    paper("pareto-one-point", "pareto", "--points", "1", expect="argument --points"),
    paper("pareto-negative-points", "pareto", "--points", "-5", expect="argument --points"),
    paper("pareto-1e11-points", "pareto", "--points", "100000000000",
          expect="argument --points: must be from 2 to 1000"),
    paper("pareto-plot-missing-folder", "pareto", "--plot", "{dir}/no/front.png", expect="--plot: cannot write"),
    paper("pareto-plot-unknown-suffix", "pareto", "--plot", "{dir}/front.bmpx",
          expect="--plot: write .png, .svg or .pdf"),
    paper("pareto-out-unknown-suffix", "pareto", "--out", "{dir}/front.txt",
          expect="--out: write .csv, .parquet or .md"),
    # --- report and its sweep table ------------------------------------------------------------------------------
    paper("report-out-missing-folder", "report", "-o", "{dir}/no/review.html", expect="--out: cannot write"),
    paper("report-out-not-a-page", "report", "-o", "{dir}/review.docx", expect="--out: write .html, .htm or .pdf"),
    table("table-as-written", SWEEP_TABLE, None),
    table("table-identified-other-coupling", '# clutchopt_sweep {"coupling": "lever", "case": "lever.toml", '
          '"values": {}, "mode": "paper", "objective": "mass", "robust": "", "varies": ["speed [rpm]"]}\n' + SWEEP_TABLE,
          ("sweep.csv: not a sweep of", "case.toml: coupling 'lever', not 'wedge'")),
    table("table-identification-damaged", '# clutchopt_sweep {"coupling": "wedge"\n' + SWEEP_TABLE,
          "its identification (the case it was swept from) is damaged"),
    table("table-identification-nested-deep", "# clutchopt_sweep " + "[" * 100_000 + "\n" + SWEEP_TABLE,
          "its identification (the case it was swept from) is damaged"),
    table("table-empty", "", "cannot read a sweep table"),
    table("table-header-only", "point,speed [rpm],status,mass [kg]\n", "a sweep table has 1 to 100,000 rows"),
    table("table-no-input", "point,status,mass [kg]\n0,optimal,1\n", "no varied input before status"),
    table("table-no-status", "point,speed [rpm],mass [kg]\n0,900,1\n", "not a sweep table"),
    table("table-point-first-missing", "speed [rpm],point,status,mass [kg]\n900,0,optimal,1\n", "not a sweep table"),
    table("table-words-for-numbers", "point,speed [rpm],status,mass [kg]\nx,fast,optimal,heavy\n",
          "column 'point': must hold numbers"),
    table("table-status-unknown", "point,speed [rpm],status,mass [kg]\n0,900,great,1\n",
          "column 'status': must be one of"),
    table("table-infinite-input", "point,speed [rpm],status,mass [kg]\n0,inf,optimal,1\n",
          "column 'speed [rpm]': must hold finite numbers"),
    table("table-random-bytes", bytes(range(256)), "cannot read a sweep table"),
    table("table-markdown", "| point |\n", "a sweep table is read from .csv or .parquet", file="sweep.md"),
    table("table-parquet-garbage", b"PAR1 not really", "cannot read a sweep table", file="sweep.parquet"),
    table("table-fifo", FIFO, "cannot read a FIFO"),
    table("table-folder", FOLDER, "cannot read a folder"),
    # --- runs ----------------------------------------------------------------------------------------------------
    command("runs-limit-negative", ("runs", "list", "--limit", "-5"), "argument --limit: must be from 0"),
    command("runs-limit-word", ("runs", "list", "--limit", "all"), "argument --limit: not a whole number"),
    command("runs-sweep-zero", ("runs", "list", "--sweep", "0"), "argument --sweep: must be from 1"),
    command("runs-sweep-beyond-sqlite", ("runs", "list", "--sweep", str(2**63)), "argument --sweep: must be from 1"),
    command("runs-show-zero", ("runs", "show", "0"), "argument id: must be from 1"),
    command("runs-show-negative", ("runs", "show", "-5"), "argument id"),
    command("runs-show-beyond-sqlite", ("runs", "show", "9" * 30), "argument id: must be from 1"),
    command("runs-show-5000-digits", ("runs", "show", "9" * 5000), "argument id: not a whole number"),
    command("runs-show-no-store", ("runs", "show", "1", "--store", "{dir}/none.sqlite"), "no such run store"),
    command("runs-list-text-file", ("runs", "list", "--store", str(CASES / "wedge_paper.toml")),
            "is not an SQLite database"),
    command("runs-list-folder", ("runs", "list", "--store", "{dir}"), "is not a regular file"),
    command("runs-list-other-database", ("runs", "list", "--store", "{dir}/other.sqlite"),
            "is an SQLite database but not a clutchopt run store", ("other.sqlite", OTHER_DATABASE)),
    command("runs-kind-unknown", ("runs", "list", "--kind", "magic"), "argument --kind: invalid choice"),
    command("runs-export-unknown-suffix", ("runs", "export", "-o", "{dir}/runs.xls"), "--out: write .csv, .parquet"),
    command("runs-export-missing-folder", ("runs", "export", "-o", "{dir}/no/runs.csv"), "--out: cannot write"),
    command("runs-without-action", ("runs",), "the following arguments are required: ACTION"),
    # --- file names the system refuses ---------------------------------------------------------------------------
    command("case-name-too-long", ("solve", "{dir}/" + "c" * 5000 + ".toml"), "cannot read (File name too long)"),
    paper("out-name-too-long", "sweep", "--vary", "speed=900", "--out", "{dir}/" + "t" * 5000 + ".csv",
          expect="--out: cannot use"),
    paper("plot-name-too-long", "pareto", "--plot", "{dir}/" + "p" * 5000 + ".png", expect="--plot: cannot use"),
    command("store-name-too-long", ("runs", "list", "--store", "{dir}/" + "s" * 5000), "--store: "),
    paper("solve-with-store-name-too-long", "solve", "--store", "{dir}/" + "s" * 5000, expect=None),
    # --- init, couplings, materials ------------------------------------------------------------------------------
    command("init-unknown-coupling", ("init", "clutch"), "argument COUPLING: invalid choice: 'clutch'"),
    command("init-mode-empty", ("init", "wedge", "--mode", ""), "argument --mode"),
    command("init-mode-unknown", ("init", "wedge", "--mode", "fancy"), "unknown mode 'fancy'"),
    command("init-out-not-toml", ("init", "wedge", "-o", "{dir}/case.txt"), "--out: write .toml"),
    command("init-out-missing-folder", ("init", "wedge", "-o", "{dir}/no/case.toml"), "does not exist"),
    command("init-out-fifo", ("init", "wedge", "-o", "{dir}/case.toml", "--force"), "it is a FIFO",
            ("case.toml", FIFO)),
    command("init-out-exists", ("init", "wedge", "-o", "{dir}/case.toml"), "exists; give another name",
            ("case.toml", WEDGE)),
    command("init-out-name-too-long", ("init", "wedge", "-o", "{dir}/" + "i" * 5000 + ".toml"), "--out: cannot use"),
    command("init-as-written", ("init", "lever", "-o", "{dir}/mine.toml"), None),
    command("couplings-extra-argument", ("couplings", "wedge"), "unrecognized arguments: wedge"),
    command("materials-unknown-flag", ("materials", "--all"), "unrecognized arguments: --all"),
    case("library-unknown-entry", LEVER + '\n[library]\nmaterial = "unobtainium"\n',
         "library.material: unknown material 'unobtainium'"),
    case("library-not-a-table", "library = 5\n" + LEVER, "library: must be a table of names"),
    case("choose-list-of-lists", LEVER + '\n[options]\nchoose = {material = [["C45_QT"]]}\n',
         "options.choose.material: unknown material"),
    case("choose-twice", LEVER + '\n[options]\nchoose = {material = ["C45_QT", "C45_QT"]}\n',
         "options.choose.material: must be a list of different names"),
    # --- bench and the top level ---------------------------------------------------------------------------------
    command("bench-unknown-flag", ("bench", "--quick", "--repeats", "3"), "unrecognized arguments: --repeats"),
    command("no-command", (), "the following arguments are required: COMMAND", subprocess=True),
    command("unknown-command", ("benchmark",), "invalid choice: 'benchmark'"),
    command("hint-names-the-command", ("runs", "list", "--limit", "x"), "(see clutchopt runs list --help)"),
]


def write_all(folder: Path, inputs: list[Hostile] | None = None) -> None:
    """Every hostile input (of ``inputs``, else of this module) in a folder of its own under ``folder``, with its
    command line; the generated suites beside this one write theirs by it too."""
    for hostile in HOSTILE if inputs is None else inputs:
        argv = hostile.write(folder / hostile.name)
        print(f"{hostile.name}: clutchopt {' '.join(argv)}")


if __name__ == "__main__":
    write_all(Path(sys.argv[1] if len(sys.argv) > 1 else "hostile-inputs"))

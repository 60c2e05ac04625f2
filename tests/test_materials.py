"""The material library: each entry sourced and consistent with the rules it states; cases take its values where
they give none; options.choose solves every choice, best first; bad names are refused naming the field."""

import json
import math
import os
import shutil
import subprocess
import sys
import tomllib

import pytest

from clutchopt.cases import parse_case, read_toml
from clutchopt.errors import InputError
from clutchopt.formulations import MODULES, get_coupling
from clutchopt.materials import FIELDS, MAX_CHOICES, library
from clutchopt.optimise.design import design_case
from clutchopt.template import case_template
from clutchopt.units import ureg
from tests.conftest import CASES, ROOT, choosing
from tests.test_json_units import assert_units, run

STEELS_AND_IRONS = list(library()["materials"].values())


def test_every_entry_names_its_source_and_describes_itself():
    assert {kind: len(entries) for kind, entries in library().items()} == {
        "materials": 9, "friction_pairs": 7, "thread_pairs": 3}
    for entries in library().values():
        for entry in entries.values():
            assert len(entry.source) > 20 and entry.description, entry.name


@pytest.mark.parametrize("entry", STEELS_AND_IRONS, ids=lambda e: e.name)
def test_allowable_stresses_follow_the_stated_rules(entry):
    """materials.toml: [sigma_b] = [sigma] = R_e / 2.5 (grey iron R_m / 4), [tau] = [sigma] / sqrt(3), to 1 MPa."""
    v = entry.values
    if "allowable_normal" not in v:  # hardened steels: contact only
        assert "allowable_contact" in v and "yield_strength" not in v
        return
    expected = v["yield_strength"] / 2.5 if "yield_strength" in v else v["tensile_strength"] / 4
    assert v["allowable_bending"] == v["allowable_normal"] == pytest.approx(expected, abs=1e6)
    assert v["allowable_shear"] == pytest.approx(v["allowable_normal"] / math.sqrt(3), abs=1e6)
    assert v["allowable_contact"] < 1.3e9  # S_c / 1.3 <= 1240 MPa / 1.3 (hardened surfaces) plus rounding


@pytest.mark.parametrize("kind", ["friction_pairs", "thread_pairs"])
def test_nominal_friction_lies_in_its_scatter_range(kind):
    for entry in library()[kind].values():
        v = entry.values
        assert v["friction_min"] <= v["friction_coefficient"] <= v["friction_max"], entry.name


@pytest.mark.parametrize("coupling", MODULES)
def test_each_role_maps_library_fields_onto_quantities_of_the_same_dimension(coupling):
    c = get_coupling(coupling)
    quantities = {q.name: q for q in c.quantities}
    assert c.materials
    for role in c.materials:
        fields = {q.name: q for q in FIELDS[role.kind]}
        for field, quantity in role.fills.items():
            assert ureg.Quantity(1, fields[field].unit).dimensionality == \
                ureg.Quantity(1, quantities[quantity].unit).dimensionality, (role.key, field)


LEVER = read_toml(CASES / "lever_centrifuge.toml")


def lever(**changes):
    data = {**LEVER, "material": dict(LEVER["material"])}
    for section, values in changes.items():
        data[section] = {**data.get(section, {}), **values}
    return data


def test_the_library_fills_what_the_case_leaves_out_and_explicit_values_win():
    data = lever(library={"friction_pair": "sintered_bronze_dry", "material": "41Cr4_QT"})
    del data["material"]["friction_coefficient"], data["material"]["allowable_link_stress"]
    case = parse_case(data)
    v = case.values
    assert v["friction_coefficient"] == 0.3 and v["lining_density"] == 5500 and v["lining_price"] == 800  # EUR/m^2
    assert v["allowable_link_stress"] == 264e6 and v["elastic_modulus"] == 210e9
    assert v["allowable_pressure"] == 0.25e6 and v["allowable_pin_shear"] == 80e6  # the case's own, not 0.3, 152
    assert case.filled["friction_coefficient"] == ("friction_pair", "sintered_bronze_dry")
    assert "allowable_pressure" not in case.filled and "allowable_pin_shear" not in case.filled


@pytest.mark.parametrize(("changes", "message"), [
    ({"library": {"friction_pair": "sintered_brnze"}},
     "library.friction_pair: unknown friction pair 'sintered_brnze'; known: organic_dry, organic_oiled, "),
    ({"library": {"material": "C45"}}, "library.material: unknown material 'C45'; known: S235JR, C45_N, C45_QT"),
    ({"library": {"thread_pair": "steel_bronze_greased"}}, "library.thread_pair: unknown key; [library] takes "
                                                           "material, friction_pair for this coupling"),
    ({"options": {"choose": {"friction_pair": []}}}, "options.choose.friction_pair: must be a list of different"),
    ({"options": {"choose": {"friction_pair": ["organic_dry", "organic_dry"]}}}, "options.choose.friction_pair"),
    ({"options": {"choose": {"friction_pair": ["organic_dry", "felt"]}}},
     "options.choose.friction_pair: unknown friction pair 'felt'"),
    ({"options": {"choose": {"lining": ["organic_dry"]}}}, "options.choose.lining: unknown role"),
    ({"options": {"choose": "organic_dry"}}, "options.choose: must be a table of lists"),
    ({"library": {"friction_pair": "organic_dry"}, "options": {"choose": {"friction_pair": ["cermet_dry"]}}},
     "library.friction_pair: names 'organic_dry', and options.choose.friction_pair lists the entries to choose from: "
     "name one entry in [library] or several in options.choose, not both"),
])
def test_bad_library_names_are_refused_naming_the_field(changes, message):
    with pytest.raises(InputError) as error:
        parse_case(lever(**changes))
    assert message in str(error.value)


def test_every_choice_is_checked_when_the_case_is_read():
    """The pin's shear allowable comes from the library here; hardened 100Cr6 has none (contact only)."""
    data = lever(options={"choose": {"material": ["C45_QT", "100Cr6_hardened"]}})
    del data["material"]["allowable_pin_shear"]
    with pytest.raises(InputError, match=r"options\.choose\.material: 100Cr6_hardened has no allowable_shear, "
                                         r"which material\.allowable_pin_shear takes from the library"):
        parse_case(data)
    with pytest.raises(InputError, match=r'library: must be a table of names, e\.g\. \[library\] friction_pair = '
                                         r'"organic_dry"'):
        parse_case({**LEVER, "library": 5})


def test_a_missing_field_the_library_could_fill_says_so():
    data = lever()
    del data["material"]["friction_coefficient"]
    with pytest.raises(InputError, match=r"material\.friction_coefficient: missing .*; or name a friction_pair"):
        parse_case(data)


def test_choose_solves_every_pair_and_ranks_them_by_the_closed_form():
    """Wedge, paper mode: m_r = 2 T_max sin(alpha) / (f z (r1 + r2) w^2 r_c) (eq. 27, consistent), so the weight
    mass goes as 1/f and the finger, sized by F_fr = T_max / (z (r1 + r2)/2), not at all: the steel pair
    (f = 0.18) needs 0.07 / 0.18 of the weight the oiled bronze (f = 0.07) needs, and comes first. That holds while
    the finger fits its weight: with the template's finger_fit_ratio 0.5 the steel weight that carries the torque is
    too narrow for its finger (d_n <= 0.5 b(m_r)), so its mass is the finger's fit's (still lighter, still first);
    with a ratio of 1 the torque sizes both."""
    data = tomllib.loads(case_template("wedge"))  # the paper's duty on 70 mm flanks (steel: q within 0.25 MPa)
    del data["library"]["friction_pair"]
    data["options"] = {"choose": {"friction_pair": ["sintered_bronze_oiled", "steel_steel_dry"]}}
    fitted = design_case(parse_case(data))
    assert [d.choice["friction_pair"] for d in fitted] == ["steel_steel_dry", "sintered_bronze_oiled"]
    assert [sorted(c.name for c in d.solution.constraints if c.active) for d in fitted] == [
        ["finger_bending", "finger_fits_width"], ["finger_bending", "torque"]]
    data.setdefault("limits", {})["finger_fit_ratio"] = 1.0
    ranked = design_case(parse_case(data))
    assert [d.choice["friction_pair"] for d in ranked] == ["steel_steel_dry", "sintered_bronze_oiled"]
    steel, bronze = (d.solution for d in ranked)
    assert steel.status == bronze.status == "optimal"
    assert steel.outputs["weight_mass"].value / bronze.outputs["weight_mass"].value == pytest.approx(0.07 / 0.18,
                                                                                                     rel=1e-8)
    assert steel.design["finger_diameter"] == pytest.approx(bronze.design["finger_diameter"], rel=1e-8)


def test_solve_reports_the_choices_and_the_library_in_text_and_json(tmp_path):
    path = tmp_path / "choose.toml"
    path.write_text(choosing("lever"))
    text = run("solve", path, "--no-store")
    assert text.startswith("Choices of options.choose, best first\n")
    header, first = text.splitlines()[1:3]  # (the rank as text, right-aligned to its name: h17 dropped pandas from
    assert header.split()[:3] == ["rank", "friction_pair", "status"] and header.startswith("rank ")  # the text
    assert first.split()[:3] == ["1", "organic_dry", "optimal"] and first.startswith("   1 ")  # tables)
    assert "From the material library (values the case gives itself win):" in text
    assert "friction_pair = organic_dry: friction_coefficient 0.3 (scatter 0.25 to 0.45)" in text
    data = json.loads(run("solve", path, "--json", "--no-store"))
    assert [c["choice"]["friction_pair"] for c in data["choices"]] == ["organic_dry", "cermet_dry",
                                                                       "sintered_bronze_dry"]
    masses = [c["objective"]["value"] for c in data["choices"]]
    assert masses == sorted(masses) and data["objective"]["value"] == masses[0]
    assert data["library"]["friction_pair"]["values"]["allowable_pressure"] == {
        "value": 250000.0, "unit": "Pa", "display_unit": "MPa"}
    assert_units(data)


def test_materials_lists_every_entry_in_text_and_si_json():
    text = run("materials")
    for entries in library().values():
        for name in entries:
            assert f"\n  {name}: " in text
    data = json.loads(run("materials", "--json"))
    assert len(assert_units(data)) > 100
    c45 = next(e for e in data["materials"] if e["name"] == "C45_QT")
    assert c45["values"]["allowable_bending"] == {"value": 172e6, "unit": "Pa", "display_unit": "MPa"}
    organic = next(e for e in data["friction_pairs"] if e["name"] == "organic_dry")
    assert organic["values"]["max_temperature"]["value"] == pytest.approx(523.15)  # 250 degC in kelvin
    assert organic["values"]["price"] == {"value": 200.0, "unit": "EUR/m^2", "display_unit": "EUR/cm^2"}


def test_a_build_ships_the_library(tmp_path):
    """A non-editable install has the data files: build the package from the tracked files (setuptools'
    build_py, the step a wheel is made of) and look for them."""
    source, built = tmp_path / "src", tmp_path / "lib"
    tracked = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True).stdout.split()
    if not tracked:
        pytest.skip("not a git checkout")
    for name in tracked + [str(p.relative_to(ROOT)) for p in (ROOT / "clutchopt" / "data").iterdir()]:
        if (ROOT / name).is_file():
            (source / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(ROOT / name, source / name)
    result = subprocess.run([sys.executable, "-c", "from setuptools import setup; setup()", "-q", "build_py",
                             "--build-lib", str(built)], cwd=source, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr[-2000:]
    assert (built / "clutchopt" / "data" / "materials.toml").is_file()
    assert (built / "clutchopt" / "data" / "starting_values.toml").is_file()


def test_every_command_designs_every_choice_and_says_which_it_keeps(tmp_path):
    """compare and report take the best choice as solve ranks them; sweep keeps the best at each point (its
    column choice), pareto draws a front per choice."""
    path = tmp_path / "choose.toml"
    path.write_text(choosing("cable"))
    solved = json.loads(run("solve", path, "--json"))
    best = ", ".join(f"{key} = {name}" for key, name in solved["choices"][0]["choice"].items())
    assert len(solved["choices"]) >= 2
    text = run("compare", path)
    assert text.startswith(f"options.choose: compared for the best of {len(solved['choices'])} choices, {best} "
                           "(clutchopt solve lists them)\n")
    swept = run("sweep", path, "--vary", "torque=200,240", "--quiet")
    assert swept.startswith("options.choose: every choice designed at every point, the best kept (column choice)\n")
    case = parse_case(read_toml(path))
    points = json.loads(run("sweep", path, "--vary", "torque=200,240", "--json", "--quiet"))["points"]
    for point in points:
        assert point["choice"] == design_case(case.with_values(torque=point["values"]["torque"]))[0].choice
    fronts = json.loads(run("pareto", path, "--points", "2", "--json"))["fronts"]
    listed = case.options["choose"]["thread_pair"]
    assert [front["choice"] for front in fronts] == [{"thread_pair": name} for name in listed]


def test_choose_is_capped_before_any_solve():
    data = tomllib.loads(case_template("lever"))
    data["options"] = {"choose": {"material": list(library()["materials"]), "friction_pair": list(
        library()["friction_pairs"])}}
    with pytest.raises(InputError, match=rf"options\.choose: 63 combinations \(9 material x 7 friction_pair\); at most "
                                         rf"{MAX_CHOICES} are designed in one run: list fewer names"):
        parse_case(data)


def _on_a_terminal(*argv: str) -> str:
    """What a command writes to stderr when that is a terminal (100 columns): its progress bars."""
    import fcntl
    import pty
    import struct
    import termios

    leader, follower = pty.openpty()
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 100, 0, 0))
    process = subprocess.Popen([sys.executable, "-m", "clutchopt", *argv], stdout=subprocess.DEVNULL,
                               stderr=follower, cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
    os.close(follower)
    written = b""
    while chunk := _read(leader):
        written += chunk
    os.close(leader)
    assert process.wait(timeout=120) == 0, written
    return written.decode()


def _read(descriptor: int) -> bytes:
    try:
        return os.read(descriptor, 4096)
    except OSError:  # the terminal closed with the process
        return b""


def test_a_progress_bar_moves_as_the_choices_are_designed_on_a_terminal_only(tmp_path, capsys):
    path = tmp_path / "choose.toml"
    path.write_text(choosing("lever"))
    assert "choices:   0%| " in _on_a_terminal("solve", str(path), "--no-store")  # then cleared: the lever is fast
    assert _on_a_terminal("solve", str(path), "--no-store", "--quiet") == ""
    assert run("solve", path, "--no-store") and "choices" not in capsys.readouterr().err  # not a terminal

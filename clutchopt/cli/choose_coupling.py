"""``clutchopt choose-coupling CASE``: one duty, drive and limits for every coupling; the verified optima ranked by
like-for-like mass, cost and outer diameter, with what sizes each and why the others lose (docs/envelope.md)."""

from __future__ import annotations

from clutchopt.cli.options import add_case_argument, add_json_option, add_parser, add_tolerance_option


def add_command(commands) -> None:
    choose = add_parser(
        commands, "choose-coupling",
        "which coupling suits a drive: every coupling designed for one duty, ranked by mass, cost and diameter",
        "The case has coupling = \"any\": [duty] (power or torque, speed, inertia, acceleration_time,\n"
        "resisting_torque), [library], [limits], [start_up] as in any case. Each coupling is posed from its\n"
        "starting values (clutchopt init) with that duty, designed for least mass and verified in float64; the\n"
        "optima are ranked by the like-for-like mass of docs/envelope.md (halves and housing, moving parts,\n"
        "springs, linings). A coupling that cannot meet the duty is listed with its verdict and the reason.",
        ("clutchopt choose-coupling cases/conveyor_drive.toml",
         "clutchopt choose-coupling cases/conveyor_drive.toml --json > choice.json"))
    add_case_argument(choose)
    add_tolerance_option(choose)
    add_json_option(choose)
    choose.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.choose import choice_json, choice_units, choose_coupling
    from clutchopt.output import choice_text, to_json, with_units

    choice = choose_coupling(args.case, SolverOptions(tol=args.tol))
    if args.json:
        return to_json(with_units(choice_json(choice), choice_units()))
    return choice_text(choice_json(choice))

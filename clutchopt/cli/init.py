"""``clutchopt init COUPLING [--mode M] [-o case.toml]``: a new case to start from, complete and commented."""

from __future__ import annotations

from clutchopt.cli.options import COUPLING_MODES, MODE_HELP, Checked, add_parser, name, path
from clutchopt.errors import InputError


def add_command(commands) -> None:
    init = add_parser(
        commands, "init",
        "write a new case to start from: every field with its unit, meaning, typical range and source",
        "The case solves as written. Edit the numbers of your duty, pick materials by name in [library]\n"
        "(clutchopt materials lists them), then solve it. Without -o the case is printed.",
        ("clutchopt init lever -o mine.toml              then: clutchopt solve mine.toml",
         "clutchopt init wedge --mode geometry -o w.toml  free geometry, not the paper's",
         "clutchopt init ball | less                      read it first"))
    init.add_argument("coupling", choices=tuple(COUPLING_MODES), metavar="COUPLING",
                      help=f"which coupling: {', '.join(COUPLING_MODES)} (clutchopt couplings describes them)")
    init.add_argument("--mode", metavar="MODE", action=Checked, check=name,
                      help=MODE_HELP.replace("Default: the case's [options] mode, then",
                                             "Written into [options]; default:"))
    init.add_argument("-o", "--out", action=Checked, check=path, metavar="FILE",
                      help="write the case to FILE (default: print it)")
    init.add_argument("--force", action="store_true", help="overwrite FILE if it exists")
    init.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.files import check_output, status, write_whole
    from clutchopt.template import case_template

    text = case_template(args.coupling, args.mode)
    if not args.out:
        return text.rstrip("\n")
    path = args.out
    check_output("--out", path, (".toml",))
    if status(path, "--out") is not None and not args.force:
        raise InputError("--out", f"{path} exists; give another name, or --force to overwrite it")

    def write(target: str) -> None:
        with open(target, "w", encoding="utf-8") as handle:
            handle.write(text)

    write_whole("--out", path, write)
    return f"wrote {path}: a new {args.coupling} case; solve it with: clutchopt solve {path}"

"""The ``mechcli`` command line: a lazy click group and ONE error boundary.

Exit codes (:class:`ExitStatus`): 0 ok, 1 internal error, 2 bad spec or usage,
3 the problem has no solution, 4 ``mechcli check``: an expected value is not met,
130 interrupted.  Subcommand modules are imported only when the subcommand runs,
so ``mechcli --version`` never imports numpy (the library versions are read from
their installed metadata, :mod:`mechcli._versions`).
"""

from __future__ import annotations

import enum
import importlib
import sys

import click

from mechcli import __version__

#: subcommand -> (module, attribute, one-line help).  Register only what works.
COMMANDS = {
    "kin": ("mechcli.commands.kin", "kin", "Kinematics of a planar linkage (chapter 1)."),
    "force": ("mechcli.commands.force", "force",
              "Kinetostatics: pair reactions and balancing torque (chapter 2)."),
    "gear": ("mechcli.commands.gear", "gear",
             "Involute gears: function, geometry, pairs, generation (chapter 5)."),
    "grashof": ("mechcli.commands.grashof", "grashof",
                "Linkage type, crank conditions, K, transmission angle, mobility (ch. 3 §1)."),
    "cam": ("mechcli.commands.cam", "cam",
            "Disc cams: motion laws, profiles, pressure angle, sizing (chapter 4)."),
    "synth": ("mechcli.commands.synth", "synth",
              "Linkage synthesis: guidance, function generation, design from K (ch. 3)."),
    "flywheel": ("mechcli.commands.flywheel", "flywheel",
                 "Machine dynamics: Je, Me, equation of motion, steady state, flywheel (ch. 6)."),
    "optimize": ("mechcli.commands.optimize", "optimize",
                 "Optimization of linkages: function/path generation, any kin/force result "
                 "(ch. 7)."),
    "check": ("mechcli.commands.check", "check",
              "Run specs and compare every [expected] value (batches, CI, JUnit)."),
    "new": ("mechcli.commands.new", "new", "Write a commented starter spec for a command."),
    "schema": ("mechcli.commands.schema", "schema",
               "Print the JSON Schema of a command's spec (for editors)."),
}


#: commands that never repeat large numpy temporaries: no allocator setting for them
#: (``mechcli._alloc``; it costs the ``ctypes`` import, ~1.5 ms of a ~90 ms start-up)
_LIGHT_COMMANDS = frozenset({"grashof", "new", "schema"})


#: subcommand -> the example its ``--help`` ends with (a shipped example, so that it runs
#: anywhere mechcli is installed: ``mechcli new CMD --from EXAMPLE`` writes the spec)
EXAMPLES = {
    "kin": ("mechcli new kin --from ex1-1 -o ex1-1.toml",
            "mechcli kin ex1-1.toml --lang zh --columns theta3,omega3"),
    "force": ("mechcli new force --from ex2-1 -o ex2-1.toml",
              "mechcli force ex2-1.toml --json --no-plot"),
    "grashof": ("mechcli grashof --lengths 40,90,70,100",
                "mechcli new grashof --from ex3-1 -o ex3-1.toml && mechcli grashof ex3-1.toml"),
    "cam": ("mechcli new cam --from ex4-1 -o ex4-1.toml", "mechcli cam ex4-1.toml --animate"),
    "gear": ("mechcli new gear --from ex5-4 -o ex5-4.toml", "mechcli gear ex5-4.toml"),
    "synth": ("mechcli new synth --from ex3-8 -o ex3-8.toml", "mechcli synth ex3-8.toml"),
    "flywheel": ("mechcli new flywheel --from ex6-4 -o ex6-4.toml",
                 "mechcli flywheel ex6-4.toml"),
    "optimize": ("mechcli new optimize --from ex7-1 -o ex7-1.toml",
                 "mechcli optimize ex7-1.toml --json"),
    "check": ("mechcli check configs/ -j 2 --junit check.xml",),
}

#: the exit codes, as every ``--help`` lists them
EXIT_CODES = ("Exit codes: 0 ok; 1 a bug (rerun with --traceback and report it); "
              "2 bad spec, option or --out; 3 the problem has no solution (cannot "
              "assemble, no crank, no convergence, undercut when forbidden); 4 mechcli "
              "check: an expected value is not met; 130 interrupted.")


def _epilog(name):
    """The end of a subcommand's ``--help``: its examples and the exit codes."""
    lines = ["\b", "Examples:"] + [f"  {ex}" for ex in EXAMPLES.get(name, ())]
    return ("\n".join(lines) + "\n\n" if name in EXAMPLES else "") + EXIT_CODES


class ExitStatus(enum.IntEnum):
    OK = 0
    INTERNAL = 1
    BAD_SPEC = 2
    UNSOLVABLE = 3
    CHECK_FAILED = 4   # mechcli check: an expected value is not met


class LazyGroup(click.Group):
    """A click group whose subcommands are imported on first use."""

    def list_commands(self, ctx):
        return sorted(COMMANDS)

    def get_command(self, ctx, name):
        if name not in COMMANDS:
            return None
        module, attr, _ = COMMANDS[name]
        cmd = getattr(importlib.import_module(module), attr)
        if cmd.epilog is None:   # examples and exit codes, once per process
            cmd.epilog = _epilog(name)
        return cmd

    def format_commands(self, ctx, formatter):
        rows = [(name, COMMANDS[name][2]) for name in self.list_commands(ctx)]
        with formatter.section("Commands"):
            formatter.write_dl(rows)

    def resolve_command(self, ctx, args):
        try:
            return super().resolve_command(ctx, args)
        except click.UsageError as exc:
            import difflib
            if args and args[0] not in COMMANDS:
                near = difflib.get_close_matches(args[0], list(COMMANDS), n=1)
                if near:
                    raise click.UsageError(f"{exc.message} (did you mean '{near[0]}'?)",
                                           ctx) from None
            raise


def versions():
    """``[(name, version)]`` of mechcli, Python, numpy, scipy and matplotlib, read
    from their installed metadata (never imported: ``--version`` stays fast);
    ``"not installed"`` for a missing library."""
    from mechcli._versions import python_version, version

    out = [("python", python_version())]
    for lib in ("numpy", "scipy", "matplotlib"):
        out.append((lib, version(lib) or "not installed"))
    return out


def _print_version(ctx, _param, value):
    if not value or ctx.resilient_parsing:
        return
    click.echo(f"mechcli, version {__version__}")
    click.echo(", ".join(f"{name} {v}" for name, v in versions()))
    ctx.exit()


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]},
             epilog=("\b\nExamples:\n"
                     "  mechcli new kin --from ex1-1 -o ex1-1.toml   # a book example as a spec\n"
                     "  mechcli kin ex1-1.toml                       # table, kin.csv, plots in "
                     "out/ex1-1/\n"
                     "  mechcli kin ex1-1.toml --lang zh --animate -o hw1\n"
                     "  mechcli grashof --lengths 40,90,70,100       # no file needed\n"
                     "  mechcli COMMAND --help                       # the options of a command"
                     "\n\n" + EXIT_CODES))
@click.option("--version", is_flag=True, expose_value=False, is_eager=True,
              callback=_print_version,
              help="Show the versions of mechcli, Python, numpy, scipy, matplotlib and exit.")
def cli():
    """mechcli: theory of machines (机械原理) from TOML problem files.

    Each command reads SPEC.toml, prints the result table in the book's
    format and writes CSV, PNG plots and GIF animations into --out
    (-o; default out/<spec stem>/).
    """


def _unknown_first(args, exc):
    """The first unknown key of the spec the failing command read (:mod:`mechcli.spec.
    unknown`), when the error is about that spec; None otherwise."""
    if not args or args[0] not in COMMANDS or not str(exc.file).lower().endswith(".toml"):
        return None
    sets = [args[i + 1] for i, a in enumerate(args[:-1]) if a == "--set"]
    sets += [a.split("=", 1)[1] for a in args if a.startswith("--set=")]
    from mechcli.spec.unknown import first_unknown_key
    try:
        found = first_unknown_key(args[0], exc.file, sets)
    except Exception:   # noqa: BLE001 -- a second opinion never hides the first error
        return None
    # the error already names that key: keep its own words
    return None if found is None or found.key == exc.key else found


def _err(message):
    click.echo(f"mechcli: error: {message}", err=True)


def _json_error(args, message, code):
    """With --json, also put the error on stdout as a JSON document for scripts."""
    if "--json" in args:
        import json
        command = next((a for a in args if a in COMMANDS), None)
        click.echo(json.dumps({"command": command, "error": message, "exit_code": int(code)},
                              ensure_ascii=False))


def _traceback(show):
    if show:
        import traceback
        traceback.print_exc()


def main(argv=None):
    """Entry point: run the CLI and turn every exception into an exit code."""
    from mechcli.core.errors import ConvergenceError, UnsolvableError
    from mechcli.report.files import OutputPathError
    from mechcli.spec.errors import SpecError

    args = list(sys.argv[1:] if argv is None else argv)
    show_tb = "--traceback" in args
    from mechcli._signals import sigterm_as_exit
    restore = sigterm_as_exit()
    try:
        if args and args[0] in COMMANDS and args[0] not in _LIGHT_COMMANDS:
            from mechcli._alloc import keep_heap_warm
            keep_heap_warm()
        # with standalone_mode=False click returns (not raises) the code of an Exit
        rv = cli.main(args=args, prog_name="mechcli", standalone_mode=False)
    except (SpecError, OutputPathError) as exc:
        # a bad spec, or an --out that cannot take the files (unsafe name, OS error);
        # a key no table knows is named first, before what it made go wrong
        if isinstance(exc, SpecError):
            exc = _unknown_first(args, exc) or exc
        _traceback(show_tb)
        _err(exc.format())
        _json_error(args, exc.format(), ExitStatus.BAD_SPEC)
        code = ExitStatus.BAD_SPEC
    except (UnsolvableError, ConvergenceError) as exc:
        _traceback(show_tb)
        spec = next((a for a in args if a.lower().endswith(".toml")), None)
        message = f"{spec}: {exc}" if spec else str(exc)
        _err(message)
        _json_error(args, message, ExitStatus.UNSOLVABLE)
        code = ExitStatus.UNSOLVABLE
    except click.exceptions.Exit as exc:
        code = exc.exit_code
    except click.Abort as exc:
        # click turns Ctrl-C (KeyboardInterrupt) into Abort
        interrupted = isinstance(exc.__cause__ or exc.__context__, KeyboardInterrupt)
        _err("interrupted" if interrupted else "aborted")
        code = 130 if interrupted else ExitStatus.INTERNAL
    except click.ClickException as exc:
        no_args = getattr(click.exceptions, "NoArgsIsHelpError", None)
        if no_args is not None and isinstance(exc, no_args):
            # bare `mechcli` (click >= 8.2 raises this): the help, on stdout, exit 0
            click.echo(exc.ctx.get_help())
            sys.exit(int(ExitStatus.OK))
        # a usage error: one line, like every other error (and the JSON object with --json);
        # click's own may span lines ("Choose from:" and one choice a line)
        message = " ".join(exc.format_message().split())
        ctx = getattr(exc, "ctx", None)
        if ctx is not None and ctx.command_path and ctx.command_path != "mechcli":
            message = f"{ctx.command_path}: {message}"
        _err(message)
        _json_error(args, message, ExitStatus.BAD_SPEC)
        code = ExitStatus.BAD_SPEC
    except KeyboardInterrupt:
        _err("interrupted")
        code = 130
    except BrokenPipeError:
        code = ExitStatus.OK
    except Exception as exc:  # the one boundary for internal errors
        _traceback(show_tb)
        _err(f"internal error: {type(exc).__name__}: {exc} "
             "(this is a bug; rerun with --traceback and report it)")
        code = ExitStatus.INTERNAL
    else:
        code = rv if isinstance(rv, int) and not isinstance(rv, bool) else ExitStatus.OK
    finally:
        restore()
        # a run that did not commit its outputs leaves --out as the earlier run left it
        files = sys.modules.get("mechcli.report.files")
        if files is not None:
            files.abandon_staged()
    sys.exit(int(code))

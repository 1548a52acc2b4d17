"""The ``mechcli`` command line: a lazy click group and ONE error boundary.

Exit codes (:class:`ExitStatus`): 0 ok, 1 internal error, 2 bad spec or usage,
3 the problem has no solution, 4 ``mechcli check``: an expected value is not met.  Subcommand modules are imported only when the
subcommand runs, so ``mechcli --version`` never imports numpy.
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
                 "Optimization of linkages: function/path generation, any kin/force result (ch. 7)."),
    "check": ("mechcli.commands.check", "check",
              "Run specs and compare every [expected] value (batches, CI, JUnit)."),
    "new": ("mechcli.commands.new", "new", "Write a commented starter spec for a command."),
    "schema": ("mechcli.commands.schema", "schema",
               "Print the JSON Schema of a command's spec (for editors)."),
}


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
        return getattr(importlib.import_module(module), attr)

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


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="mechcli")
def cli():
    """mechcli: theory of machines (机械原理) from TOML problem files.

    Each command reads SPEC.toml, prints the result table in the book's
    format and writes CSV, PNG plots and GIF animations into --out.
    """


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
    if not any(a in ("--version", "--help", "-h") for a in args[:1]):
        from mechcli._alloc import keep_heap_warm
        keep_heap_warm()
    try:
        # with standalone_mode=False click returns (not raises) the code of an Exit
        rv = cli.main(args=args, prog_name="mechcli", standalone_mode=False)
    except (SpecError, OutputPathError) as exc:
        # a bad spec, or an --out that cannot take the files (unsafe name, OS error)
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
        # a usage error: one line, like every other error (and the JSON object with --json)
        message = exc.format_message()
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
    sys.exit(int(code))

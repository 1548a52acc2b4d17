"""``mechcli new``: write a commented starter spec for a command.

The templates are package data: ``mechcli/templates/<command>.toml`` for the command's
main problem type and ``mechcli/templates/<command>.<type>.toml`` for each other type
(``mechcli new kin --type slider_crank``).  Each is a runnable problem with no
``[expected]`` values (a comment shows how to add one's own), and every key carries its
meaning, unit and default as a comment, written from the catalogue that also describes
the keys in ``mechcli schema`` (:mod:`mechcli.spec.keydocs`).  The test suite runs every
template through its command and ``mechcli check``, so they cannot rot.
``--from NAME`` starts instead from one of the book's worked examples shipped in
``mechcli/templates/examples/<NAME>.toml``.
"""

from __future__ import annotations

import click

#: commands that have a starter template
TEMPLATE_COMMANDS = ("kin", "force", "grashof", "cam", "gear", "synth", "flywheel", "optimize")

_LINKAGES = ("four_bar", "slider_crank", "guide_bar", "shaper", "general", "joints")
#: the problem types of each command, the default first: the mechanism types of a linkage
#: (``[mechanism] type``), gear's and grashof's problem tables, cam's followers
#: (``motion`` and ``contact``), synth's ``[synthesis] kind``, flywheel's forms (``[motion]
#: kind``, a linkage's Je and Me, an energy swing), optimize's ``[objective] kind``
TYPES = {
    "kin": _LINKAGES,
    "force": _LINKAGES,
    "grashof": ("fourbar", "slider_crank", "guide_bar", "fivebar", "rrrrp", "mobility"),
    "cam": ("translating_roller", "translating_knife", "translating_flat",
            "oscillating_roller", "oscillating_knife"),
    "gear": ("spur", "involute", "inverse_involute", "pair", "generation", "helical", "worm",
             "bevel"),
    "synth": ("three_positions", "two_positions", "moving_pivots", "coupler_poses",
              "burmester", "function", "slider_function", "rocker_slider", "quick_return",
              "atlas_page", "type_chart", "atlas_build", "path"),
    "flywheel": ("steady", "start", "linkage", "energy"),
    "optimize": ("function", "path", "result", "pressure_angle"),
}


def _templates():
    from importlib.resources import files
    return files("mechcli") / "templates"


def template_name(command, kind=None):
    """The file name of *command*'s template of type *kind* (None: the default type)."""
    if kind is None or kind == TYPES[command][0]:
        return f"{command}.toml"
    return f"{command}.{kind}.toml"


def template_text(command, kind=None):
    """The starter spec of *command* (a name in :data:`TEMPLATE_COMMANDS`) for the
    problem type *kind* (a name in ``TYPES[command]``; None: the default one)."""
    return (_templates() / template_name(command, kind)).read_text(encoding="utf-8")


def _check_type(command, kind):
    import difflib
    known = TYPES[command]
    if kind not in known:
        near = difflib.get_close_matches(kind, known, n=1)
        hint = f" (did you mean '{near[0]}'?)" if near else ""
        raise click.BadParameter(f"no type '{kind}' for {command}{hint}; types: "
                                 + ", ".join(known), param_hint="'--type'")


def examples():
    """``{name: (command, text)}`` of the shipped examples, sorted by name."""
    import re
    out = {}
    for entry in sorted(_templates().joinpath("examples").iterdir(), key=lambda e: e.name):
        if not entry.name.endswith(".toml"):
            continue
        text = entry.read_text(encoding="utf-8")
        m = re.search(r'^command\s*=\s*"([a-z]+)"', text, re.M)
        out[entry.name[:-5]] = (m.group(1) if m else None, text)
    return out


def _example_text(command, name):
    import difflib
    known = examples()
    mine = [n for n, (c, _) in known.items() if c == command]
    if name.endswith(".toml"):
        name = name[:-5]
    if name not in known:
        near = difflib.get_close_matches(name, list(known), n=1)
        hint = f" (did you mean '{near[0]}'?)" if near else ""
        raise click.BadParameter(f"no example '{name}'{hint}; examples for {command}: "
                                 + ", ".join(mine), param_hint="'--from'")
    other, text = known[name]
    if other != command:
        raise click.BadParameter(f"example '{name}' is a `mechcli {other}` spec, not {command}; "
                                 f"examples for {command}: " + ", ".join(mine),
                                 param_hint="'--from'")
    head = (f"# Started from the shipped example {name} (`mechcli new {command} --from {name}`).\n"
            f"# Every key of `mechcli {command}` with its meaning, unit and default: "
            f"`mechcli new {command}`.\n\n")
    return head + text


def _help():
    lines = ["Write a commented starter spec for COMMAND (" + ", ".join(TEMPLATE_COMMANDS)
             + ").", "",
             "The spec runs as written; every key has its meaning, unit and default beside "
             "it. --type picks the problem type (the first listed is the default):", "",
             "\b"]
    import textwrap
    width = max(map(len, TEMPLATE_COMMANDS))
    for c in TEMPLATE_COMMANDS:
        lines += textwrap.wrap(" ".join(TYPES[c]), 76, initial_indent=f"  {c.ljust(width)}  ",
                               subsequent_indent=" " * (width + 4), break_on_hyphens=False)
    lines += ["", "\b", "  mechcli new kin -o linkage.toml && mechcli kin linkage.toml",
              "  mechcli new kin --type slider_crank -o engine.toml",
              "  mechcli new gear --from ex5-4 > pair.toml"]
    return "\n".join(lines)


@click.command("new", help=_help())
@click.argument("command", type=click.Choice(TEMPLATE_COMMANDS), metavar="COMMAND")
@click.option("--type", "kind", metavar="TYPE",
              help="The problem type (e.g. slider_crank for kin): see the list above.")
@click.option("--from", "example", metavar="EXAMPLE",
              help="Start from a shipped example (e.g. ex1-4) instead of the template.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None, metavar="FILE",
              help="Write to FILE instead of stdout.")
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
@click.option("--list", "list_", is_flag=True, help="List the examples of COMMAND and exit.")
def new(command, kind, example, output, force, list_):
    if list_:
        for name, (cmd, _) in examples().items():
            if cmd == command:
                click.echo(name)
        return
    if kind is not None and example is not None:
        raise click.UsageError("--type and --from: give one (a type's template, or an example)")
    if kind is not None:
        _check_type(command, kind)
    text = template_text(command, kind) if example is None else _example_text(command, example)
    if output is None:
        click.echo(text, nl=False)
        return
    from pathlib import Path

    from mechcli.report.files import write_text
    path = Path(output)
    if path.exists() and not force:
        raise click.UsageError(f"{path} exists; add --force to overwrite it")
    try:
        write_text(path, text)
    except OSError as exc:
        raise click.UsageError(f"cannot write {path}: {exc.strerror or exc}") from None
    click.echo(f"wrote {path}; run it with: mechcli {command} {path}", err=True)

"""``mechcli new``: write a commented starter spec for a command.

The templates are package data, ``mechcli/templates/<command>.toml``: every key of the
command's main problem with its meaning, unit and default as TOML comments, around a
runnable minimal problem (the test suite runs each one, so they cannot rot).
``--from NAME`` starts instead from one of the book's worked examples shipped in
``mechcli/templates/examples/<NAME>.toml``.
"""

from __future__ import annotations

import click

#: commands that have a starter template
TEMPLATE_COMMANDS = ("kin", "force", "grashof", "cam", "gear", "synth", "flywheel", "optimize")


def _templates():
    from importlib.resources import files
    return files("mechcli") / "templates"


def template_text(command):
    """The starter spec of *command* (a name in :data:`TEMPLATE_COMMANDS`)."""
    return (_templates() / f"{command}.toml").read_text(encoding="utf-8")


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


@click.command("new")
@click.argument("command", type=click.Choice(TEMPLATE_COMMANDS), metavar="COMMAND")
@click.option("--from", "example", metavar="EXAMPLE",
              help="Start from a shipped example (e.g. ex1-4) instead of the template.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None, metavar="FILE",
              help="Write to FILE instead of stdout.")
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
@click.option("--list", "list_", is_flag=True, help="List the examples of COMMAND and exit.")
def new(command, example, output, force, list_):
    """Write a commented starter spec for COMMAND (kin, force, grashof, cam, gear, synth, flywheel).

    \b
      mechcli new kin -o linkage.toml && mechcli kin linkage.toml
      mechcli new gear --from ex5-4 > pair.toml
    """
    if list_:
        for name, (cmd, _) in examples().items():
            if cmd == command:
                click.echo(name)
        return
    text = template_text(command) if example is None else _example_text(command, example)
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

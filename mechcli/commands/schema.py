"""``mechcli schema COMMAND``: the JSON Schema of a command's spec, for editors.

The schema is learnt from the command's own spec reader
(:mod:`mechcli.spec.schema`), so it cannot drift from what the reader accepts; each
key's description comes from the catalogue that also writes the comments of
``mechcli new``'s templates (:mod:`mechcli.spec.keydocs`).
"""

from __future__ import annotations

import click


@click.command("schema")
@click.argument("command", metavar="COMMAND")
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False), default=None,
              help="Write the schema to this file instead of printing it.")
@click.option("--learn", is_flag=True,
              help="Learn the schema afresh from the spec reader (development: the shipped "
                   "schemas are learnt this way with the checkout's configs/).")
def schema(command, output, learn):
    """Print the JSON Schema (draft-07) of COMMAND's spec (kin, force, grashof,
    cam, gear, synth, flywheel, optimize), for editors that check TOML against a
    schema (Taplo, tombi): every key with its type, bounds, default and description.

    \b
      mechcli schema kin -o kin.schema.json
    """
    import difflib
    import os
    import tempfile

    from mechcli.spec.schema import COMMANDS, command_schema, schema_text, shipped_schema_text

    if command not in COMMANDS:
        near = difflib.get_close_matches(command, COMMANDS, n=1)
        raise click.UsageError(
            f"no spec schema for '{command}': expected one of {', '.join(COMMANDS)}"
            + (f" (did you mean '{near[0]}'?)" if near else ""))
    text = schema_text(command_schema(command)) if learn else shipped_schema_text(command)
    if output is None:
        click.echo(text, nl=False)
        return
    folder = os.path.dirname(os.path.abspath(output))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".schema-", suffix=".tmp", dir=folder)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)   # mkstemp makes 0600; a written schema is a normal file
        os.replace(tmp, output)
    except OSError as exc:
        raise click.UsageError(f"-o {output}: cannot write ({exc.strerror or exc})") from None
    click.echo(f"wrote {output}", err=True)

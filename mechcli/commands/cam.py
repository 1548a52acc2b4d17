"""``mechcli cam``: follower motion, disc-cam profile, pressure angle, curvature, sizing."""

from __future__ import annotations

from pathlib import Path

import click

from mechcli.options import RunOptions, common_options, export_option


class FiniteFloat(click.FloatRange):
    """A float option within [min, max] that is also finite: click's FloatRange lets NaN
    through (every comparison with NaN is false).  A bad value is a usage error (exit 2)
    naming the option.  Shared by the commands' numeric options (``grashof --offset``)."""

    name = "finite float"

    def convert(self, value, param, ctx):
        rv = click.FLOAT.convert(value, param, ctx)
        if rv != rv or rv in (float("inf"), float("-inf")):
            self.fail(f"{value!r} is not a finite number.", param, ctx)
        return super().convert(rv, param, ctx)


@click.command("cam")
@click.argument("spec", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--step", type=FiniteFloat(1e-4, 10.0), default=None, metavar="DEG",
              help="Profile sampling step in degrees [default: spec, else 0.1].")
@click.option("--points", type=click.IntRange(36, 3_600_000), default=None,
              help="Profile points per revolution (instead of --step).")
@export_option
@common_options
def cam(spec, step, points, **opts):
    """Design and check a disc cam from SPEC.toml (chapter 4, 例 7-2)."""
    run = RunOptions.from_click(spec, opts)
    from mechcli.report.cam import cam_report
    from mechcli.spec.cam import read_cam_spec
    from mechcli.spec.reader import load_spec

    cs = read_cam_spec(load_spec(spec, run.sets), step, points)
    design = design_of(cs)
    cam_report(run, cs, design, extra=lambda out: export(run, cs, design, out))


def export(run, cs, design, outputs):
    """``--export``: cam.dxf / cam.svg, the profile as profile.png draws it (report.cad)."""
    if not run.export:
        return
    from mechcli.core.cam.geometry import working_outline
    from mechcli.report import cad
    outline = working_outline(design.follower, design.program, design.profile,
                              design.checks.corners)
    cad.write(outputs, "cam", cad.cam_sketch(cs, design, outline), run.export)


def design_of(cs):
    """The cam of a read spec (also ``optimize``'s cam problems); a core error
    worded in the spec's units and keys."""
    from mechcli.core.cam.design import design_cam
    from mechcli.core.cam.geometry import CamError
    from mechcli.report.cam import error_message
    sz = cs.sizing
    try:
        return design_cam(
            cs.motion, cs.contact, cs.r0, cs.follower_args, cs.segments, cs.stroke,
            angular=cs.angular, step=cs.step, alpha_rise=cs.limits.alpha_rise,
            alpha_return=cs.limits.alpha_return, size_base_radius=bool(sz and sz.base_radius),
            limit_return=bool(sz and sz.limit_return), rho_min=sz.rho_min if sz else 0.0,
            round_up=sz.round_up if sz else 0.0, forbid_undercut=cs.limits.forbid_undercut)
    except CamError as exc:  # worded in the spec's units and keys
        raise type(exc)(error_message(exc, cs), exc.reason, **exc.values) from exc

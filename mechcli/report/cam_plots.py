"""Pictures of ``mechcli cam`` (imports matplotlib: import only to write a PNG/GIF)."""

from mechcli.report.plotting import setup  # noqa: F401


def plot_all(cs, design, out, lang):
    pass


def animate(cs, design, out, lang):
    pass

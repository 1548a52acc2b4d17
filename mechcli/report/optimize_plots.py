"""Pictures of ``mechcli optimize`` (placeholder until the plots land)."""


def write(spec, problem, result, details, outputs, lang, plots=True, animate=False):
    return []

"""The wording catalogue's ``flywheel_plots`` section: the labels of mechcli/report/flywheel_plots.py's
figures (see the package docstring)."""

WORDS = {
    'je': {'en': 'Equivalent inertia', 'zh': '等效转动惯量'},
    'me': {'en': 'Equivalent moment and work', 'zh': '等效力矩与盈亏功'},
    'w': {'en': 'Speed of the equivalent link', 'zh': '等效构件角速度'},
    'phi': {'en': 'φ / °', 'zh': '转角 φ / °'},
    't': {'en': 't / s', 'zh': '时间 t / s'},
    'iter': {'en': 'period-map evaluation', 'zh': '迭代次数'},
    'conv': {'en': 'Convergence of the steady state', 'zh': '稳定运转的收敛'},
}

"""The wording catalogue's ``kin_plots`` section: the labels of mechcli/report/kin_plots.py's
figures (see the package docstring)."""

WORDS = {
    'disp': {'en': 'Displacement', 'zh': '位移线图'},
    'vel': {'en': 'Velocity', 'zh': '速度线图'},
    'acc': {'en': 'Acceleration', 'zh': '加速度线图'},
    'mech': {'en': 'Mechanism at', 'zh': '机构位置'},
    'input': {'en': 'crank angle {sym} / °', 'zh': '曲柄转角 {sym} / °'},
    'curve': {'en': 'Path of point', 'zh': '轨迹 点'},
    'anim': {'en': 'Motion', 'zh': '运动仿真'},
    'path': {'en': 'path of {name}', 'zh': '{name} 点轨迹'},
    'const': {'en': '{sym} ≡ {v:.4g} {u}', 'zh': '{sym} ≡ {v:.4g} {u}'},
}

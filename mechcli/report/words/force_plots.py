"""The wording catalogue's ``force_plots`` section: the labels of mechcli/report/force_plots.py's
figures (see the package docstring)."""

WORDS = {
    'pair': {'en': 'Reaction F_R{lab}', 'zh': '运动副反力 F_R{lab} 曲线图'},
    'Mb': {'en': 'Balancing torque {sym}', 'zh': '平衡力矩 {sym} 曲线图'},
    'Fb': {'en': 'Balancing force {sym}', 'zh': '平衡力 {sym} 曲线图'},
    'hodo': {'en': 'Hodograph of F_R{lab}', 'zh': 'F_R{lab} 矢端曲线'},
    'crank': {'en': 'crank angle θ{n} / °', 'zh': '曲柄转角 θ{n} / °'},
    'slide': {'en': 'slide s{n} / {u}', 'zh': '滑块位移 s{n} / {u}'},
    'shake_f': {'en': 'Shaking force (force on the frame)', 'zh': '机架总反力 (摆动力) 曲线图'},
    'shake_m': {'en': 'Shaking moment Msh (about the origin)', 'zh': '机架总力矩 (摆动力矩) Msh 曲线图'},
    'power': {'en': 'Input power P', 'zh': '输入功率 P 曲线图'},
    'active': {'en': "load '{name}' acts", 'zh': '载荷 {name} 作用区间'},
    'anim': {'en': 'Pair reactions', 'zh': '运动副反力'},
    'at': {'en': 'θ{n} = {v:.0f}°', 'zh': 'θ{n} = {v:.0f}°'},
    'at_s': {'en': 's{n} = {v:.4g} {u}', 'zh': 's{n} = {v:.4g} {u}'},
    'piston': {'en': 'Forces on the piston (toward the crank +)', 'zh': '活塞上的力 (指向曲柄为正)'},
    'rod': {'en': 'Rod force, wall thrust and crank effort', 'zh': '连杆力、侧压力与曲柄切向力'},
    'torque': {'en': 'Turning moment diagram T (mean {m:.4g} N·m)', 'zh': '曲轴转矩图 T (平均 {m:.4g} N·m)'},
    'start': {'en': 'start', 'zh': '起点'},
    'origin': {'en': 'origin', 'zh': '原点'},
}

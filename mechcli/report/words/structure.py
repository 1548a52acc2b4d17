"""The wording catalogue's ``structure`` section (see the package docstring)."""

WORDS = {
    # The structural analysis (杆组分解) block: mechcli/report/structure.py.
    'driver': {'en': 'driver {link} with the frame {frame}', 'zh': '原动件 {link} 与机架 {frame}'},
    'dyad': {'en': 'dyad {type}', 'zh': '{type} 型 II 级杆组'},
    'triad': {'en': 'triad', 'zh': '三级杆组'},
    'group': {'en': 'group', 'zh': '杆组'},
    'higher_group': {'en': '{kind} (class {klass})', 'zh': '{klass} 级{kind}'},
    'title': {'en': 'Structural analysis: a class {klass} mechanism (groups in solving order)', 'zh': '杆组分解: {klass} 级机构 (按求解顺序)'},
    'links': {'en': 'links', 'zh': '构件'},
    'pairs': {'en': 'pairs', 'zh': '运动副'},
    'class': {'en': 'class', 'zh': '级别'},
}

"""The wording catalogue's ``optimize_plots`` section: the labels of mechcli/report/optimize_plots.py's
figures (see the package docstring)."""

WORDS = {
    'conv': {'en': 'Convergence', 'zh': '收敛过程'},
    'iter': {'en': 'iteration', 'zh': '迭代次数'},
    'record': {'en': 'record', 'zh': '记录'},
    'f': {'en': 'objective f', 'zh': '目标函数 f'},
    'viol': {'en': 'constraint violation', 'zh': '约束违反量'},
    'all_feasible': {'en': 'every iterate is feasible', 'zh': '每次迭代都可行'},
    'tol': {'en': 'feasibility tolerance', 'zh': '可行容差'},
    'surf': {'en': 'Objective surface', 'zh': '目标函数等值线'},
    'infeasible': {'en': 'infeasible', 'zh': '不可行域'},
    'start': {'en': 'start x0', 'zh': '初始点 x0'},
    'opt': {'en': 'optimum x*', 'zh': '最优点 x*'},
    'path': {'en': 'iterates', 'zh': '迭代路径'},
    'target': {'en': 'Target and achieved', 'zh': '预期与实际'},
    'tgt_fn': {'en': 'target', 'zh': '预期'},
    'got_fn': {'en': 'achieved', 'zh': '实际'},
    'dev': {'en': 'deviation', 'zh': '偏差'},
    'input': {'en': 'input φ / °', 'zh': '输入角 φ / °'},
    'input_s': {'en': 'input s', 'zh': '输入位移 s'},
    'output': {'en': 'output ψ / °', 'zh': '输出角 ψ / °'},
    'output_s': {'en': 'output s', 'zh': '输出位移 s'},
    'points': {'en': 'target points', 'zh': '给定点'},
    'curve': {'en': 'path of', 'zh': '轨迹'},
    'at': {'en': 'at the prescribed inputs', 'zh': '给定输入角处'},
    'best': {'en': 'f* (best)', 'zh': '最优值 f*'},
}

"""The wording catalogue's ``optimize`` section: mechcli/report/optimize.py's tables (see the
package docstring)."""

WORDS = {
    'variables': {'en': 'Design variables', 'zh': '设计变量'},
    'variable': {'en': 'variable', 'zh': '变量'},
    'start': {'en': 'start x0', 'zh': '初值 x0'},
    'lower': {'en': 'lower bound', 'zh': '下界'},
    'upper': {'en': 'upper bound', 'zh': '上界'},
    'active': {'en': 'active', 'zh': '起作用'},
    'constraints': {'en': 'Constraints g(x) ≤ 0', 'zh': '约束 g(x) ≤ 0'},
    'constraint': {'en': 'constraint', 'zh': '约束'},
    'objective': {'en': 'objective f(x*)', 'zh': '目标函数 f(x*)'},
    'method': {'en': 'method', 'zh': '方法'},
    'iterations': {'en': 'iterations', 'zh': '迭代次数'},
    'evaluations': {'en': 'evaluations', 'zh': '函数计算次数'},
    'time': {'en': 'time t/(s)', 'zh': '时间 t/(s)'},
    'converged': {'en': 'converged', 'zh': '收敛'},
    'deviation_max': {'en': 'largest deviation/(°)', 'zh': '最大偏差/(°)'},
    'phi0': {'en': 'φ0/(°)', 'zh': 'φ0/(°)'},
    'alpha_exact': {'en': 'exact largest pressure angle α/(°) at δ/(°)', 'zh': '精确最大压力角 α/(°) 及转角 δ/(°)'},
    'delta_error': {'en': 'error of the cam angle δ/(°)', 'zh': '转角误差 δ/(°)'},
    'optimum': {'en': 'Optimum', 'zh': '优化结果'},
    'yes': {'en': 'yes', 'zh': '是'},
    'no': {'en': 'no', 'zh': '否'},
    'distance_max': {'en': 'largest distance/({u})', 'zh': '最大距离/({u})'},
}

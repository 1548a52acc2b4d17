"""The wording catalogue's ``force`` section (see the package docstring)."""

WORDS = {
    # mechcli force's report: mechcli/report/force.py.  head_* are the Chinese names before a
    # header's symbol (English shows the symbol alone).
    'head_Mb': {'en': '', 'zh': '平衡力矩'},
    'head_Fb': {'en': '', 'zh': '平衡力'},
    'head_Fsh': {'en': '', 'zh': '机架总反力'},
    'head_Msh': {'en': '', 'zh': '机架总力矩'},
    'head_FL': {'en': '', 'zh': '活塞上的气体力'},
    'head_FI': {'en': '', 'zh': '往复质量惯性力'},
    'head_FP': {'en': '', 'zh': '活塞推力'},
    'head_FQ': {'en': '', 'zh': '连杆力'},
    'head_FN': {'en': '', 'zh': '气缸壁侧压力'},
    'head_FT': {'en': '', 'zh': '曲柄销切向力'},
    'head_Frad': {'en': '', 'zh': '曲柄径向力'},
    'head_T': {'en': '', 'zh': '曲轴转矩'},
    'reactions': {'en': 'Pair reactions and balancing {what} (every {step}{unit}; F_Rij = force of link i on link j)', 'zh': '运动副反力与平衡{what} (每 {step}{unit} 一行; F_Rij 为构件 i 对构件 j 的作用力)'},
    'balancing_torque': {'en': 'torque', 'zh': '力矩'},
    'balancing_force': {'en': 'force', 'zh': '力'},
    'extremes': {'en': 'Extremes (refined by golden-section search, input located to ±{tol}{unit})', 'zh': '极值 (位置精确到 ±{tol}{unit})'},
    'mean': {'en': 'mean {sym}', 'zh': '平均 {sym}'},
    'rms': {'en': 'RMS {sym}', 'zh': '均方根 {sym}'},
    'power_residual': {'en': 'power balance residual (relative)', 'zh': '功率平衡残差 (相对)'},
    'largest_cond': {'en': 'largest condition number', 'zh': '最大条件数'},
    'never': {'en': 'never', 'zh': '从不'},
    'always': {'en': 'always', 'zh': '全程'},
    'loads': {'en': 'Loads and where they act', 'zh': '外载荷作用区间'},
    'engine_forces': {'en': 'Engine forces (FL gas force, FI = m·a of the reciprocating mass, FP piston effort, FQ along the rod, FN on the cylinder wall, FT crank effort, Frad radial, T turning moment)', 'zh': '活塞与曲柄上的力 (F_L 气体力, F_I = m·a, F_P 活塞推力, F_Q 连杆力, F_N 侧压力, F_T 切向力, T 转矩)'},
    'engine_extremes_located': {'en': 'Engine forces: extremes (input located to ±{tol}{unit})', 'zh': '活塞力极值 (位置精确到 ±{tol}{unit})'},
    'engine_extremes': {'en': 'Engine forces: extremes', 'zh': '活塞力极值'},
    # the Chinese note leaves out the crank end ({crank:.0} prints nothing), as it always did
    'piston': {'en': 'piston {link}: stroke {stroke} {unit}, head-end dead centre at {head}°, crank end at {crank}°; the signs: see docs/force.md', 'zh': '活塞 {link}: 行程 {stroke} {unit}, 外止点 θ = {head}°{crank:.0}'},
    'values_at': {'en': 'Values at {sym} = {x}{unit}', 'zh': '{sym} = {x}{unit} 时的值'},
    'approx_arm': {'en': "model: approximate (the piston's inertia force and the moment arm of T and FT, r (sin θ + sin 2θ / 2n), from the series in 1/n, the rest exact); largest differences to the exact model, relative to its peak: {diffs}", 'zh': '模型: 近似 (活塞惯性力与 T、FT 的力臂 r(sin θ + sin 2θ/2n) 按 1/n 级数), 与精确模型的最大相对差: {diffs}'},
    'approx': {'en': "model: approximate (the piston's inertia force from the series in 1/n, the rest exact); largest differences to the exact model, relative to its peak: {diffs}", 'zh': '模型: 近似 (活塞惯性力按 1/n 级数), 与精确模型的最大相对差: {diffs}'},
}

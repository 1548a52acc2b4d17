"""The wording catalogue's ``synth_plots`` section: the labels of mechcli/report/synth_plots.py's
figures (see the package docstring)."""

WORDS = {
    'pos': {'en': 'Design in its prescribed positions', 'zh': '预定位置'},
    'err': {'en': 'Structural error', 'zh': '结构误差'},
    'x': {'en': 'x', 'zh': 'x'},
    'ey': {'en': 'error in y', 'zh': 'y 的误差'},
    'ephi': {'en': 'error of the output angle / °', 'zh': '输出角误差 / °'},
    'burm': {'en': 'Burmester curves', 'zh': 'Burmester 曲线'},
    'centre': {'en': 'centre-point curve', 'zh': '圆心点曲线'},
    'circle': {'en': 'circle-point curve', 'zh': '圆点曲线'},
    'poses': {'en': 'poses', 'zh': '位置'},
    'bpts': {'en': 'Burmester points (centre ▲, circle ●)', 'zh': 'Burmester 点 (圆心点 ▲, 圆点 ●)'},
    'lim': {'en': 'Design at its two limit positions', 'zh': '极限位置'},
}

"""The wording catalogue's ``run`` section (see the package docstring)."""

WORDS = {
    # The end of every command (report.txt's "Given" block): mechcli/report/run.py.
    'given': {'en': 'Given ({items})', 'zh': '已知条件 ({items})'},
    'spec': {'en': 'spec {path}', 'zh': '题目文件 {path}'},
    'units': {'en': 'lengths in {unit}, angles in °, the rest in SI units', 'zh': '长度单位 {unit}, 角的单位 °, 其余为国际单位'},
}

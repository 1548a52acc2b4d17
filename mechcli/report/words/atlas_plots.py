"""The wording catalogue's ``atlas_plots`` section: the labels of mechcli/report/atlas_plots.py's
figures (see the package docstring)."""

WORDS = {
    'page': {'en': 'Atlas page: A = {A:g}, B = {B:g}, C = {C:g} (crank = 1; one dash per {s:g}°)', 'zh': '图谱页: A = {A:g}, B = {B:g}, C = {C:g} (曲柄 = 1; 每段短线 {s:g}°)'},
    'chart': {'en': 'Type chart (图 7)', 'zh': '机构类型图 (图 7)'},
    'B': {'en': 'B (follower / crank)', 'zh': 'B (摇杆 / 曲柄)'},
    'C': {'en': 'C (frame / crank)', 'zh': 'C (机架 / 曲柄)'},
    'path': {'en': 'Path synthesis by atlas search', 'zh': '图谱检索轨迹综合'},
    'x': {'en': 'x / {u}', 'zh': 'x / {u}'},
    'y': {'en': 'y / {u}', 'zh': 'y / {u}'},
    'targets': {'en': 'targets', 'zh': '给定点'},
    'regions_0': {'en': 'crank-rocker', 'zh': '曲柄摇杆'},
    'regions_1': {'en': 'double-crank', 'zh': '双曲柄'},
    'regions_2': {'en': 'double-rocker', 'zh': '双摇杆'},
    'regions_3': {'en': 'change point', 'zh': '变点'},
    'none': {'en': 'no curve: {why}', 'zh': '无曲线: {why}'},
}

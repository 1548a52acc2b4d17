"""The wording catalogue's ``atlas`` section (see the package docstring)."""

WORDS = {
    # The atlas kinds of mechcli synth (atlas_page, type_chart, atlas_build, path): mechcli/report/atlas.py.
    "type": {"en": "type", "zh": "类型"},
    "curves_drawn": {"en": "curves drawn", "zh": "连杆曲线数"},
    "dashes_per_curve": {"en": "dashes per curve", "zh": "每条曲线短线数"},
    "not_drawn": {"en": "not drawn", "zh": "未绘制"},
    "page": {"en": "Atlas page (crank = 1)", "zh": "图谱页 (曲柄 = 1)"},
    "marked_point": {"en": "marked point B, C", "zh": "标记点 B, C"},
    "may_vary": {"en": "{k} may vary within", "zh": "{k} 的变化范围"},
    "type_chart": {"en": "Type chart (图 7)", "zh": "机构类型图 (图 7)"},
    "curves_kept": {"en": "curves kept", "zh": "曲线数"},
    "designs_swept": {"en": "designs swept", "zh": "扫描设计数"},
    "chunks": {"en": "chunks", "zh": "数据块"},
    "complete": {"en": "complete", "zh": "完成"},
    "time": {"en": "time [s]", "zh": "时间/s"},
    "directory": {"en": "directory", "zh": "目录"},
    "build": {"en": "Atlas build", "zh": "图谱生成"},
    "path": {"en": "Path synthesis by atlas search, refined", "zh": "图谱检索轨迹综合 (优化后)"},
    "timing": {"en": "Timing", "zh": "时序"},
    "crank_at_target_1": {"en": "crank angle at target 1 (candidate {i}) [°]", "zh": "第 1 点曲柄转角 (方案 {i})/(°)"},
    "cost": {"en": "Cost", "zh": "耗时"},
    "curves_searched": {"en": "atlas curves searched", "zh": "检索曲线数"},
    "search": {"en": "search [s]", "zh": "检索/s"},
    "refinement": {"en": "refinement [s]", "zh": "优化/s"},
}

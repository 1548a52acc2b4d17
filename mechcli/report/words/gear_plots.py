"""The wording catalogue's ``gear_plots`` section: the labels of mechcli/report/gear_plots.py's
figures (see the package docstring)."""

WORDS = {
    'involute': {'en': 'involute', 'zh': '渐开线'},
    'base': {'en': 'base circle', 'zh': '基圆'},
    'involute_curve': {'en': 'Involute curve', 'zh': '渐开线曲线'},
    'gear': {'en': 'Spur gear m = {m:g}, z = {z}, x = {x:g}', 'zh': '渐开线直齿圆柱齿轮 m = {m:g}, z = {z}, x = {x:g}'},
    'tooth': {'en': 'one tooth; involute from r = {r:.3f} {u} (magenta)', 'zh': '单齿; 渐开线起始圆 r = {r:.3f} {u} (品红)'},
    'pitch_w': {'en': 'operating pitch circles', 'zh': '节圆'},
    'bases': {'en': 'base circles', 'zh': '基圆'},
    'line': {'en': 'line of action N1N2', 'zh': '理论啮合线 N1N2'},
    'contact': {'en': 'points of contact', 'zh': '啮合点'},
    'form': {'en': 'involute starts here (sharp cutter)', 'zh': '渐开线起始圆 (尖角刀具)'},
    'generation': {'en': 'Generation of an involute gear by a rack cutter', 'zh': '渐开线齿轮范成的动态模拟'},
    'tip': {'en': 'tip circle', 'zh': '齿顶圆'},
    'reference': {'en': 'reference circle', 'zh': '分度圆'},
    'root': {'en': 'root circle', 'zh': '齿根圆'},
    'pair': {'en': "z1 = {z1}, z2 = {z2}, a' = {a:g} {u}, εα = {eps:.3f}", 'zh': "z1 = {z1}, z2 = {z2}, a' = {a:g} {u}, 重合度 εα = {eps:.3f}"},
    'pair_internal': {'en': "z1 = {z1}, z2 = {z2} (internal), a' = {a:g} {u}, εα = {eps:.3f}", 'zh': "z1 = {z1}, z2 = {z2} (内齿轮), a' = {a:g} {u}, 重合度 εα = {eps:.3f}"},
    'in_contact': {'en': 'εα = {eps:.3f}: {n} pair(s) in contact', 'zh': '重合度 εα = {eps:.3f}: {n} 对齿啮合'},
    'no_contact': {'en': ' — NO CONTACT', 'zh': ' — 无啮合!'},
    'cut': {'en': 'm = {m:g}, z = {z}, α = {alpha:g}°, x = {x:g}:', 'zh': 'm = {m:g}, z = {z}, α = {alpha:g}°, x = {x:g}:'},
    'undercut': {'en': 'undercut (x < xmin)', 'zh': '根切 (x < xmin)'},
    'no_undercut': {'en': 'no undercut (x ≥ xmin)', 'zh': '无根切 (x ≥ xmin)'},
    'cuts': {'en': ', this sharp cutter cuts {pct:.1f}% of the involute', 'zh': ', 尖角刀具切去渐开线 {pct:.1f}%'},
}

"""The wording catalogue's ``common`` section (see the package docstring)."""

WORDS = {
    # Words many report sections share. Entry: key = { en = "…", zh = "…" }; {fields} are filled by
    # the caller (str.format) and must be the same in both languages.
    'quantity': {'en': 'quantity', 'zh': '量'},
    'value': {'en': 'value', 'zh': '值'},
    'max': {'en': 'max', 'zh': '最大值'},
    'min': {'en': 'min', 'zh': '最小值'},
    'at': {'en': 'at', 'zh': '位置'},
    'constant': {'en': 'constant', 'zh': '常量'},
    'summary': {'en': 'Summary', 'zh': '汇总'},
    'positions': {'en': '{n} positions analysed', 'zh': '共 {n} 个位置'},
    'yes': {'en': 'yes', 'zh': '是'},
    'no': {'en': 'no', 'zh': '否'},
}

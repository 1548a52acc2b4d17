"""docs/exercises.md, the book as an index (issue 29, item 2), is generated from
docs/book-index.toml and configs/ by docs/make_exercises.py: it must be current, list
every 【例】 and 习题 of the book once, and say where every config's values come from."""


from tests.conftest import ROOT, load_module


def _generator():
    return load_module(ROOT / "docs" / "make_exercises.py")


def test_exercises_md_is_current():
    gen = _generator()
    assert (ROOT / "docs" / "exercises.md").read_text(encoding="utf-8") == gen.render(), (
        "docs/exercises.md is stale: run python docs/make_exercises.py")


def test_the_index_lists_the_books_63_exercises_and_30_examples_once():
    # the book's chapters 1-7 (OCR text): 习题 1-1 ... 1-15, 2-1 ... 2-8, 3-1 ... 3-16,
    # 4-1 ... 4-7, 5-1 ... 5-9, 6-1 ... 6-4, 7-1 ... 7-4; 【例】 1-1 ... 1-4, 2-1 ... 2-4,
    # 3-1 ... 3-8, 4-1 ... 4-3, 5-1 ... 5-4, 6-1 ... 6-5, 7-1, 7-2
    gen = _generator()
    items = [i["label"] for i in gen.tomllib.loads(gen.INDEX.read_text(encoding="utf-8"))["item"]]
    assert len(items) == len(set(items))
    counts = {"习题": (15, 8, 16, 7, 9, 4, 4), "例": (4, 4, 8, 3, 4, 5, 2)}
    for kind, per_chapter in counts.items():
        want = [f"{kind} {c}-{m}" for c, n in enumerate(per_chapter, 1) for m in range(1, n + 1)]
        assert sorted(i for i in items if i.startswith(kind + " ")) == sorted(want)


def test_every_config_of_the_book_says_where_its_values_come_from():
    gen = _generator()
    unstated = [row["path"] for rows in gen.configs_by_label().values() for row in rows
                if row["source"] == "not stated"]
    assert unstated == []

"""Report layer: book-format tables, CSV, JSON, PNG plots and GIF animations.

matplotlib is imported only by the plotting modules, and only when a picture
is written.
"""

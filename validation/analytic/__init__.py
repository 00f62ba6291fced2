"""Independent analytic references (pure numpy/scipy) for validating ``fem`` and ``discrete``.

Formulas follow Vulfson, *Short course of the theory of mechanical vibrations* (2017),
chapters 2-5, as transcribed in ``shared/reference/textbook_ch2-5.md``; equation numbers
in the docstrings are the book's.  Nothing here imports ``fem`` or ``discrete``.
"""

"""Model-file fuzzer for the ``drivefem`` command line (issue 11, item 6).

Deterministic mutations of every example model file (:mod:`tests.fuzzing.mutate`) are run
through the CLI commands in subprocesses with a CPU-time limit and a wall-clock ceiling (:mod:`tests.fuzzing.execute`),
each outcome is classified (:mod:`tests.fuzzing.classify`: OK, TRACEBACK, HANG, NONFINITE,
BADEXIT, BADJSON, BADMESSAGE) and summarised (:mod:`tests.fuzzing.summary`).
:mod:`tests.fuzzing.run` ties them together and is the command line::

    python -m tests.fuzzing.run --n 3000 --out DIR [--jobs 2] [--limit 60] [--root SRC]

The file names do not start with ``test_``, so pytest does not collect them; the tests live in
``tests/test_fuzz_models.py``.
"""

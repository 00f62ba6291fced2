"""The exit codes of ``drivefem`` that the code names (docs/cli.md, exit codes)."""

EXIT_INTERNAL = 70      # a bug of drivefem, or a package that does not import (tests and fuzzers see it)
EXIT_INTERRUPTED = 130  # Ctrl-C: what was computed is written

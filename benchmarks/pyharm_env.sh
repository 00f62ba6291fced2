#!/usr/bin/env bash
# Create the benchmark's own virtualenv with pyHarm (PyPI: pyharm-os 1.2.2) for benchmarks/pyharm.py.
#
#   bash benchmarks/pyharm_env.sh             # -> $PYHARM_ENV (default /work/pyharm-env: shared by worktrees)
#   PYHARM_ENV=/some/dir bash benchmarks/pyharm_env.sh
#
# pyHarm is NOT a dependency of drivefem: it lives in this separate environment (about 110 packages,
# ~1.3 GB: jax, pandas, numba) and the benchmark runs it in a subprocess.  The version is pinned to the
# one of ../shared/reference/pyharm_comparison.md.
set -euo pipefail
cd "${TMPDIR:-/tmp}"      # importing pyHarm writes .pyHarm/context.json into the working directory
env_dir="${PYHARM_ENV:-/work/pyharm-env}"
python="${PYTHON:-python3}"
version="${PYHARM_VERSION:-1.2.2}"
if [ -x "$env_dir/bin/python" ] && "$env_dir/bin/python" -c "import pyHarm.Maestro" 2>/dev/null; then
    echo "pyHarm environment ready: $env_dir"
    exit 0
fi
"$python" -m venv "$env_dir"
"$env_dir/bin/python" -m pip install --quiet --upgrade pip
"$env_dir/bin/python" -m pip install --quiet "pyharm-os==$version"
"$env_dir/bin/python" -c "import pyHarm, numpy, scipy; from importlib.metadata import version as v; print('pyHarm', v('pyharm-os'), 'numpy', numpy.__version__, 'scipy', scipy.__version__)"
echo "pyHarm environment ready: $env_dir"

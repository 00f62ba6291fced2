#!/usr/bin/env bash
# Create the benchmark's own virtualenv with ROSS (ross-rotordynamics) for benchmarks/rotor.py.
#
#   bash benchmarks/ross_env.sh            # -> benchmarks/ross-env/ (about 70 packages, ~1.2 GB)
#   ROSS_ENV=/some/dir bash benchmarks/ross_env.sh
#
# ROSS is NOT a dependency of drivefem: it lives in this separate environment and the benchmark
# runs it in a subprocess.  ROSS is pinned (ROSS_VERSION, default 2.3.0: the version of the stored
# references in validation/data/ross/ and of examples/ross_compressor.toml).  plotly is pinned below 7: `import ross` fails with plotly 7.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
env_dir="${ROSS_ENV:-$here/ross-env}"
python="${PYTHON:-python3}"
ross_version="${ROSS_VERSION:-2.3.0}"       # the version the stored references were made with
if [ -x "$env_dir/bin/python" ] && "$env_dir/bin/python" -c "import ross, sys; sys.exit(ross.__version__ != '$ross_version')" 2>/dev/null; then
    echo "ROSS environment ready: $env_dir"
    exit 0
fi
"$python" -m venv "$env_dir"
"$env_dir/bin/python" -m pip install --quiet --upgrade pip
"$env_dir/bin/python" -m pip install --quiet "ross-rotordynamics==$ross_version" "plotly<7"
"$env_dir/bin/python" -c "import ross, numpy, scipy; print('ROSS', ross.__version__, 'numpy', numpy.__version__, 'scipy', scipy.__version__)"
echo "ROSS environment ready: $env_dir"

"""Natural frequencies of the Set C drive (clamped-free, k = 300 rad/s) discretised with n = 1..40
mechanisms, with the pass and stop bands of the regular structure and the pseudo-medium limit
(docs/drives.md figure):

    python examples/drive_spectrum.py [OUT.png]
"""
from __future__ import annotations

import sys

from fem.drives import DriveModel, LumpedShaft, Mechanism, spectrum_sweep
from fem.output.figures import plot_spectrum_vs_n

SET_C = DriveModel(n=6, shaft=LumpedShaft(c0=6.0e4, J0=0.02 / 6),
                   mechanism=Mechanism(m=10 / 6, c=10 / 6 * 300.0**2, ratio=0.05), continuum_length=2.0 / 6)


def main(out: str = "docs/img/drive_spectrum.png"):
    sweep = spectrum_sweep(SET_C, range(1, 41))
    return sweep, plot_spectrum_vs_n(sweep, out, "Set C drive (clamped-free): lumped shaft + n mechanisms, k = 300 rad/s")


if __name__ == "__main__":
    print(main(*sys.argv[1:2])[1])

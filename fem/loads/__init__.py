"""Loads and named outputs of lumped and hybrid model files: the drive's load map
(:mod:`discrete.loads`) built from the file's tables with the file's names (:mod:`.lumped`,
:mod:`.hybrid`), the ``[[output]]`` selection (:mod:`.select`), and the outputs of each analysis
(:mod:`.analyses`: time histories, load shapes of modes, complex amplitudes of a forced response).
docs/outputs.md describes them."""

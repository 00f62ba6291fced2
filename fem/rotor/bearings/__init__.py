"""Bearings computed from their geometry: plain journal bearings (:mod:`.journal`, films in
:mod:`.reynolds` and :mod:`.short_film`), rolling-element bearings (:mod:`.rolling`, contacts in
:mod:`.hertz`) and squeeze-film dampers (:mod:`.squeeze_film`); docs/bearings.md."""

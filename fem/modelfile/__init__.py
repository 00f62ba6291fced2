"""The model-file layer: one declared schema for every table of every kind of model file
(:mod:`.schema`), one reader (:func:`load`: the file is read once and its kind decided once) and
one builder per kind.  Nothing downstream reads or parses TOML.  See design.md §4 and §9."""
from .deprecation import ModelDeprecationWarning
from .load import load, parse, schema_json

__all__ = ["load", "parse", "schema_json", "ModelDeprecationWarning"]

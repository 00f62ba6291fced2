"""Everything the package writes: one JSON serialiser (schema name + version, one complex encoding,
no non-finite number), one CSV writer, the text tables, all matplotlib figures and the mesh files."""
from .contract import SCHEMA_VERSION, payload
from .jsonio import check_finite, encode, write_json
from .paths import check_output_path
from .tablefile import write_csv

__all__ = ["SCHEMA_VERSION", "payload", "check_finite", "encode", "write_json", "check_output_path", "write_csv"]

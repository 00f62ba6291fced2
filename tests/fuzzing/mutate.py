"""Deterministic mutations of the example model files.

Every generator is a pure function of the example (no clock, no global random state): the same
example gives the same mutations with the same ids in the same order.  A :class:`Mutation` is a
model file (its bytes, or a directory / missing path / FIFO in its place) plus, for output-path
mutations, a change of the command line.  Categories:

``control``      the example as shipped and its cheap base (must run cleanly)
``number``       a number -> 0, negative, NaN, +-inf, +-1e300, 1e-300; integers -> 2.7, 1e9, 1e20
``count``        a count (elements, points, harmonics, drive n, modes, samples, ...) -> 1e9 / 1e9 as float
``type``         any value -> string, bool, list, table (strings -> number)
``enum``         a string -> an unknown word, empty, other case
``structure``    table <-> array of tables, empty table / array, scalar lists emptied or nested
``duplicate``    an array-of-tables element repeated (valid TOML); a table or key declared twice (invalid)
``unknown_key``  a typo of a real key (replacing it, or beside it) at every level; an unknown key in every table
``delete``       each key and each array element at every level
``semantic``     every number of one table (or of all elements of an array of tables) set to 0
``units``        a number -> a quantity string: of a wrong dimension, with a garbage unit, a huge exponent
                 ("1e400 mm", "1e300 GPa"), "nan m", an offset unit ("20 degC"), or the same value in a
                 valid non-SI unit (tests/unit_strings.py); and the whole file in valid non-SI units
``broken_toml``  truncation, unbalanced brackets, unterminated string, missing value, bad escape, lone CR
``encoding``     binary, non-UTF-8, UTF-16, BOM, NUL bytes, empty, whitespace- or comment-only files
``filesystem``   a directory, a missing file, a FIFO, a dangling symlink instead of the model file
``nesting``      deeply nested arrays / inline tables / table headers
``output``       --json (--csv, --plot, --render, --vtu, --h5, --out) into a path under a regular file, an existing
                 directory (or file), a read-only directory, /dev/full, an empty path, a 300-character
                 name, a suffix the writer does not produce, or the path of another output option
``extreme``      schema-valid but physically extreme: one stiffness or inertia scaled by 1e10 or 1e-10 (a
                 contrast with the rest of the model), every damping set to 0, the forcing frequency at an
                 undamped resonance or at 0, time constants (a motor's T, omega0, nu) far below the step
``cli``          command-line options out of range: --modes, --mode 0 / -1 / 1e9, --workers -1 / 1e5,
                 an unreachable or malformed --scheduler, --resume of a missing directory or of a file
"""
from __future__ import annotations

import hashlib
import math
import random
from dataclasses import dataclass, field
from typing import Callable, Iterator

import tomli_w

from .examples import Example

COUNT_KEYS = {"elements", "points", "harmonics", "n", "modes", "samples", "periods", "order", "mode"}
FILE_TOKENS = ("TOML", "UTF", "model file", "file", "encoding", "decode", "line", "directory", "path")

OUTPUT_KINDS = {
    "under_file": "a path under a regular file",
    "occupied": "a path taken by an existing directory (a file option) or regular file (a directory option)",
    "readonly_dir": "a read-only directory",
    "dev_full": "/dev/full (no space left on device)",
    "empty": "an empty path ''",
    "long_name": "a file name of 300 characters",
    "bad_suffix": "a file name whose suffix the writer does not produce (.xyz)",
    "same_path": "the path another output option of the same run writes to",
}
#: Output options besides --json, per command: (option, what it names).
SECONDARY_OUTPUTS = {
    "modal": (("--plot", "file"), ("--vtu", "file"), ("--render", "dir"), ("--csv", "file")),
    "forced": (("--csv", "file"), ("--plot", "file")),
    "simulate": (("--csv", "file"), ("--plot", "dir"), ("--h5", "file")),
    "sweep": (("--out", "dir"),),
    "render": (("--render", "dir"),),
    "campbell": (("--plot", "file"), ("--csv", "file")),
    "parametric": (("--plot", "file"), ("--csv", "file")),
}
#: The suffix a file output is named with (the figure options write PNG).
FILE_SUFFIX = {"--json": ".json", "--csv": ".csv", "--plot": ".png", "--vtu": ".vtu", "--png": ".png", "--h5": ".h5",
               "--html": ".html"}
#: Integer and other options of each command with values out of range (``cli`` mutations).
CLI_ATTACKS = {
    "modal": (("--modes", "0"), ("--modes", "-1"), ("--modes", "1000000000")),
    "campbell": (("--modes", "0"), ("--modes", "-3"), ("--modes", "1000000000")),
    "render": (("--modes", "0"), ("--mode", "0"), ("--mode", "-1"), ("--mode", "1000000000")),
    "sweep": (("--workers", "-1"), ("--workers", "100000"), ("--scheduler", "tcp://127.0.0.1:9"),
              ("--scheduler", "not an address"), ("--resume", "no/such/dir"), ("--resume", "model.toml")),
}
#: Keys of stiffnesses and inertias (scaled by 1e+-10 in ``extreme``), of damping (set to 0) and of time scales.
STIFFNESS_KEYS = {"k", "E", "G", "GI", "stiffness", "kyy", "kzz", "kyz", "kzy", "c0", "k3", "cubic"}
INERTIA_KEYS = {"inertia", "mass", "m", "rho", "J", "J0", "Id", "Ip"}
DAMPING_KEYS = {"c", "cyy", "czz", "psi", "damping", "zeta", "alpha", "beta", "delta", "viscous", "quadratic"}
TIME_CONSTANT_KEYS = {"T": 1e-12, "omega0": 1e-9, "nu": 1e-12}


@dataclass(frozen=True)
class Mutation:
    """One mutated model file (or file-system object), with a stable id and a one-line description.

    ``artifact`` is ``"file"`` (``content`` gives its bytes: ``data``, or built by ``make``), ``"directory"``, ``"missing"``,
    ``"fifo"`` or ``"dangling_symlink"``.  ``output`` = ``(option, kind)`` replaces the output path
    of ``option`` by a bad path of ``kind`` (see :data:`OUTPUT_KINDS`); ``commands`` then limits the
    commands it applies to; ``options``: more command-line arguments (after the run's own, so they win).  ``names``: words of which an exit-2 message should name at least one.
    ``target``: the key path mutated (for grouping), ``""`` for whole-file mutations."""

    id: str
    example: str
    category: str
    description: str
    data: bytes = b""
    artifact: str = "file"
    output: tuple[str, str] | None = None
    commands: tuple[str, ...] | None = None
    options: tuple[str, ...] = ()
    names: tuple[str, ...] = ()
    target: str = ""
    make: Callable[[], bytes] | None = field(default=None, compare=False, repr=False)

    @property
    def content(self) -> bytes:
        """The model file's bytes (built on demand for document mutations)."""
        return self.make() if self.make is not None else self.data


# ----------------------------------------------------------------------------- document helpers
Path_ = tuple  # a key path: str keys and int indices


def fmt_path(path: Path_) -> str:
    """``("segment", 0, "section", "d")`` -> ``segment[0].section.d``."""
    s = ""
    for p in path:
        s += f"[{p}]" if isinstance(p, int) else (f".{p}" if s else str(p))
    return s


def get_at(doc, path: Path_):
    for p in path:
        doc = doc[p]
    return doc


def set_at(doc, path: Path_, value):
    get_at(doc, path[:-1])[path[-1]] = value


def del_at(doc, path: Path_):
    del get_at(doc, path[:-1])[path[-1]]


def walk(node, path: Path_ = ()) -> Iterator[tuple[Path_, object]]:
    """Every (path, value) below ``node`` in document order, containers before their contents."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield path + (k,), v
            yield from walk(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield path + (i,), v
            yield from walk(v, path + (i,))


def is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def label(path: Path_) -> str:
    """A readable location: ``[[segment]] #1 section.d``, ``[material] E``, ``title``."""
    if len(path) == 1:
        return str(path[0])
    head, rest = path[0], path[1:]
    if isinstance(rest[0], int):
        where = f"[[{head}]] #{rest[0] + 1}"
        rest = rest[1:]
    else:
        where = f"[{head}]"
    return f"{where} {fmt_path(rest)}".rstrip() if rest else where


def names_for(path: Path_) -> tuple[str, ...]:
    """Words an error about ``path`` should contain: the key and the table it sits in."""
    keys = [p for p in path if isinstance(p, str)]
    return tuple(dict.fromkeys(reversed(keys[-2:])))


def dump(doc: dict, header: str) -> bytes:
    return (f"# fuzz: {header}\n" + tomli_w.dumps(doc)).encode("utf-8")


def _short(v) -> str:
    r = repr(v)
    return r if len(r) <= 40 else r[:37] + "..."


def _rng(*parts) -> random.Random:
    return random.Random(hashlib.sha256("/".join(map(str, parts)).encode()).hexdigest())


# ----------------------------------------------------------------------------- generators
class _Builder:
    """Collects the mutations of one example, keeping ids unique.  Document mutations are lazy: an
    *edit* (a function changing a copy of the cheap base in place) is applied when the bytes are needed."""

    def __init__(self, ex: Example):
        self.ex, self.out, self.seen = ex, [], set()

    def add(self, category: str, target: str, variant: str, description: str, **kw):
        mid = f"{self.ex.name}/{category}/{target or '-'}/{variant}"
        base, k = mid, 2
        while mid in self.seen:
            mid, k = f"{base}~{k}", k + 1
        self.seen.add(mid)
        self.out.append(Mutation(mid, self.ex.name, category, description, target=target, **kw))

    def doc(self, category: str, path: Path_, variant: str, description: str, edit, names=None):
        target = fmt_path(path)
        header = f"{self.ex.name}/{category}/{target}/{variant}: {description}"
        self.add(category, target, variant, description, make=_DocEdit(self.ex.cheap, edit, header),
                 names=names if names is not None else names_for(path))

    def set(self, category: str, path: Path_, variant: str, description: str, value, names=None):
        self.doc(category, path, variant, description, _Set(path, value), names)


def copy_doc(node):
    """A copy of a parsed TOML document (dicts, lists and immutable scalars only)."""
    if isinstance(node, dict):
        return {k: copy_doc(v) for k, v in node.items()}
    if isinstance(node, list):
        return [copy_doc(v) for v in node]
    return node


@dataclass(frozen=True)
class _Set:
    path: Path_
    value: object

    def __call__(self, d):
        set_at(d, self.path, copy_doc(self.value))


@dataclass(frozen=True)
class _DocEdit:
    """The bytes of ``base`` after ``edit``, with a ``# fuzz:`` comment line naming the mutation."""
    base: dict
    edit: object
    header: str

    def __call__(self) -> bytes:
        d = copy_doc(self.base)
        self.edit(d)
        return dump(d, self.header)


def _number_variants(key, v) -> list[tuple[str, object]]:
    out = [("zero", 0 if isinstance(v, int) else 0.0), ("negative", -v if v else -1),
           ("nan", math.nan), ("inf", math.inf), ("-inf", -math.inf),
           ("1e300", 1e300), ("-1e300", -1e300), ("1e-300", 1e-300)]
    if isinstance(v, int):
        out += [("fraction", v + 0.7), ("int_1e9", 10**9), ("int_1e20", 10**20)]
    return out


def gen_values(b: _Builder, doc: dict):
    """number, count, type and enum mutations of every value (list elements: first and last)."""
    for path, v in list(walk(doc)):
        if isinstance(path[-1], int) and not isinstance(v, (dict, list)):
            n = len(get_at(doc, path[:-1]))
            if path[-1] not in (0, n - 1):
                continue
        key = next((p for p in reversed(path) if isinstance(p, str)), "")
        where = label(path)
        if is_number(v):
            for variant, new in _number_variants(key, v):
                b.set("number", path, variant, f"{where} = {_short(new)} (was {_short(v)})", new)
            if key in COUNT_KEYS:
                for variant, new in (("count_1e9", 10**9), ("count_1e9_float", 1e9)):
                    b.set("count", path, variant, f"{where} = {_short(new)} (a huge count, was {_short(v)})", new)
        if isinstance(v, str):
            variants = [("unknown_word", "bogus_value"), ("empty", "")]
            if v.swapcase() != v:
                variants.append(("case", v.upper() if v != v.upper() else v.lower()))
            for variant, new in variants:
                b.set("enum", path, variant, f"{where} = {new!r} (was {_short(v)})", new)
        types = [("string", "abc"), ("bool", True), ("list", [1, 2]), ("table", {"x": 1})]
        if isinstance(v, str):
            types[0] = ("number", 1)
        for variant, new in types:
            if type(new) is type(v) or (isinstance(new, list) and isinstance(v, list)) \
                    or (isinstance(new, dict) and isinstance(v, dict)):
                continue
            b.set("type", path, variant, f"{where} = {_short(new)} (a {variant} instead of {type(v).__name__})", new)


UNIT_VARIANTS = (("unit_wrong_dimension", "{v!r} m^5"), ("unit_garbage", "{v!r} zorkmids"),
                 ("unit_huge_exponent", "1e400 mm"), ("unit_overflow", "1e300 GPa"), ("unit_nan", "nan m"),
                 ("unit_offset", "20 degC"), ("unit_comma", "5,5 mm"), ("unit_power_tower", "2**2**40 m"))
"""Bad quantity strings put in place of every number (``{v!r}``: the number it replaces)."""


def _unit_strings(doc: dict) -> dict | None:
    """The document with every declared number as a valid non-SI quantity string (None if the package
    does not load it: then there is nothing valid to convert)."""
    from tests.unit_strings import rewrite

    try:
        return rewrite(doc)[0]
    except Exception:                                  # noqa: BLE001 -- a base the package refuses
        return None


def gen_units(b: _Builder, doc: dict):
    """units mutations: bad quantity strings for every number, its valid non-SI spelling, the whole
    file in non-SI units."""
    valid = _unit_strings(doc)
    if valid is not None:
        b.doc("units", (), "unit_all", "every number as a quantity string in a non-SI unit",
              _Replace(valid), names=())
    for path, v in list(walk(doc)):
        if not is_number(v):
            continue
        if isinstance(path[-1], int) and path[-1] not in (0, len(get_at(doc, path[:-1])) - 1):
            continue
        where = label(path)
        for variant, text in UNIT_VARIANTS:
            new = text.format(v=v)
            b.set("units", path, variant, f"{where} = {new!r} (was {_short(v)})", new)
        try:
            good = get_at(valid, path) if valid is not None else None
        except (KeyError, IndexError, TypeError):
            good = None
        if isinstance(good, str):
            b.set("units", path, "unit_valid", f"{where} = {good!r} (the same value, was {_short(v)})", good)


@dataclass(frozen=True)
class _Replace:
    doc: dict

    def __call__(self, d):
        d.clear()
        d.update(copy_doc(self.doc))


def _append_copy_of_first(path):
    def edit(d):
        arr = get_at(d, path)
        arr.append(copy_doc(arr[0]))
    return edit


def gen_structure(b: _Builder, doc: dict):
    """Tables <-> arrays of tables, emptied containers, repeated array-of-tables elements."""
    for path, v in list(walk(doc)):
        where = label(path)
        if isinstance(v, dict):
            b.set("structure", path, "to_array_of_tables", f"{where} is an array of tables", [v])
            b.set("structure", path, "empty_table", f"{where} is an empty table", {})
        elif isinstance(v, list) and v and all(isinstance(e, dict) for e in v):
            b.set("structure", path, "to_table", f"{where} is a single table (its first element), not an array", v[0])
            b.set("structure", path, "empty_array", f"{where} is an empty array", [])
            b.doc("duplicate", path, "repeat_element", f"{where}: its first element is given twice",
                  _append_copy_of_first(path))
        elif isinstance(v, list):
            b.set("structure", path, "empty_list", f"{where} = [] (was {_short(v)})", [])
            b.set("structure", path, "nested_list", f"{where} = [{_short(v)}] (a list in a list)", [v])


def _typos(key: str) -> list[str]:
    """Deterministic typos of ``key``: transposition, a doubled last letter, last letter -> z, case."""
    out = []
    if len(key) >= 2:
        i = max(0, len(key) // 2 - 1)
        t = key[:i] + key[i + 1] + key[i] + key[i + 2:]
        if t != key:
            out.append(t)
    out.append(key + key[-1])
    out.append(key[:-1] + ("z" if key[-1] != "z" else "x"))
    if key.swapcase() != key:
        out.append(key.swapcase())
    return list(dict.fromkeys(out))


def _rename(path, key, new):
    def edit(d):
        tab = get_at(d, path)
        items = [(new if k == key else k, v) for k, v in tab.items()]
        tab.clear()
        tab.update(items)
    return edit


def _add_key(path, key, value):
    def edit(d):
        get_at(d, path)[key] = copy_doc(value)
    return edit


def _delete(path):
    def edit(d):
        del_at(d, path)
    return edit


def gen_keys(b: _Builder, doc: dict):
    """Unknown keys (typos and a made-up key at every level) and deleted keys / elements."""
    tables = [((), doc)] + [(p, v) for p, v in walk(doc) if isinstance(v, dict)]
    for path, table in tables:
        where = label(path) if path else "top level"
        b.doc("unknown_key", path + ("bogus_key",), "made_up", f"{where}: an unknown key bogus_key = 1",
              _add_key(path, "bogus_key", 1), names=("bogus_key",))
        for key in list(table):
            typos = [t for t in _typos(key) if t not in table]
            if not typos:
                continue
            t_replace, t_extra = typos[0], typos[-1]
            b.doc("unknown_key", path + (key,), f"typo_{t_replace}", f"{where}: {key} misspelt {t_replace}",
                  _rename(path, key, t_replace), names=(t_replace,))
            b.doc("unknown_key", path + (key,), f"extra_{t_extra}", f"{where}: {t_extra} given beside {key}",
                  _add_key(path, t_extra, table[key]), names=(t_extra,))
    b.doc("unknown_key", ("bogus_table",), "table", "an unknown table [bogus_table]",
          _add_key((), "bogus_table", {"x": 1}), names=("bogus_table",))
    for path, v in list(walk(doc)):
        if isinstance(path[-1], int):
            b.doc("delete", path, "element", f"{label(path)} removed from its array", _delete(path))
        else:
            b.doc("delete", path, "key", f"{label(path)} deleted", _delete(path))


def _zero_all(key):
    def edit(d):
        for p, x in list(walk(d[key], (key,))):
            if is_number(x):
                set_at(d, p, 0 if isinstance(x, int) else 0.0)
    return edit


def gen_semantic(b: _Builder, doc: dict):
    """Every number of one top-level table (or of all elements of an array of tables) set to 0."""
    for key, v in doc.items():
        if not isinstance(v, (dict, list)):
            continue
        hit = [p for p, x in walk(v, (key,)) if is_number(x)]
        if hit:
            b.doc("semantic", (key,), "all_zero", f"every number in {label((key,))} set to 0 ({len(hit)} values)",
                  _zero_all(key))


# ------------------------------------------------------------------------------ text level
def _lines(text: str) -> list[str]:
    return text.splitlines(keepends=True)


def gen_text(b: _Builder, text: str):
    """Broken TOML and declared-twice tables/keys, from the cheap base's TOML text."""
    data = text.encode("utf-8")

    def add(category, variant, description, content: bytes, names=FILE_TOKENS):
        b.add(category, "", variant, description, data=content, names=names)

    for frac in (0.1, 0.33, 0.5, 0.66, 0.9, 0.99):
        cut = int(len(data) * frac)
        add("broken_toml", f"truncate_{int(frac * 100)}", f"file truncated to {int(frac * 100)} % ({cut} bytes)",
            data[:cut])
    lines = _lines(text)
    hdr = next((i for i, ln in enumerate(lines) if ln.startswith("[")), None)
    if hdr is not None:
        ln = lines[hdr]
        for variant, new, what in (("unclosed_header", ln.rstrip("\n").rstrip("]") + "\n", "header without its ]"),
                                   ("extra_bracket", "[" + ln, "header with an extra ["),
                                   ("stray_close", ln.rstrip("\n") + "]]\n", "header with a stray ]]")):
            mod = lines[:hdr] + [new] + lines[hdr + 1:]
            add("broken_toml", variant, f"{what}: {new.strip()!r}", "".join(mod).encode())
    q = next((i for i, ln in enumerate(lines) if '"' in ln and "=" in ln and not ln.startswith("#")), None)
    if q is not None:
        ln = lines[q]
        j = ln.rfind('"')
        mod = lines[:q] + [ln[:j] + ln[j + 1:]] + lines[q + 1:]
        add("broken_toml", "unterminated_string", f"unterminated string on line {q + 1}", "".join(mod).encode())
        mod = lines[:q] + [ln[:j] + "\\q" + ln[j:]] + lines[q + 1:]
        add("broken_toml", "bad_escape", f"invalid escape \\q on line {q + 1}", "".join(mod).encode())
    kv = [i for i, ln in enumerate(lines) if "=" in ln and not ln.lstrip().startswith(("#", "["))]
    if kv:
        i = kv[len(kv) // 2]
        key = lines[i].split("=")[0]
        mod = lines[:i] + [key + "=\n"] + lines[i + 1:]
        add("broken_toml", "missing_value", f"{key.strip()} = (no value) on line {i + 1}", "".join(mod).encode())
        mod = lines[:i] + [key.strip() + " " + lines[i].split("=", 1)[1]] + lines[i + 1:]
        add("broken_toml", "missing_equals", f"no '=' on line {i + 1}", "".join(mod).encode())
        mod = lines[:i] + [key + "= [1, 2\n"] + lines[i + 1:]
        add("broken_toml", "unclosed_array", f"{key.strip()} = [1, 2 (unclosed array)", "".join(mod).encode())
        mod = lines[:i + 1] + [lines[i]] + lines[i + 1:]
        add("duplicate", "key_twice", f"{key.strip()} given twice in one table (line {i + 1})",
            "".join(mod).encode())
    add("broken_toml", "lone_cr", "lines separated by a lone carriage return", text.replace("\n", "\r").encode())
    add("broken_toml", "crlf", "CRLF line endings (valid TOML)", text.replace("\n", "\r\n").encode(), names=())
    # a table header declared twice (invalid TOML)
    for i, ln in enumerate(lines):
        if ln.startswith("[") and not ln.startswith("[["):
            mod = lines + ["\n", ln] + [x for x in lines[i + 1:i + 2] if "=" in x]
            add("duplicate", f"table_twice_{ln.strip()[1:-1]}", f"table {ln.strip()} declared twice",
                "".join(mod).encode())


def gen_encoding(b: _Builder, text: str):
    """Binary, non-UTF-8 and degenerate files, and file-system objects in place of the model file."""
    data = text.encode("utf-8")
    name = b.ex.name
    rnd = _rng("binary", name)

    def add(variant, description, content: bytes = b"", artifact="file"):
        b.add("encoding" if artifact == "file" else "filesystem", "", variant, description,
              data=content, artifact=artifact, names=FILE_TOKENS)

    add("binary_random", "4 KiB of random bytes", rnd.randbytes(4096))
    add("binary_png", "a PNG header and random bytes", b"\x89PNG\r\n\x1a\n" + rnd.randbytes(512))
    add("latin1_title", "non-UTF-8: title with a Latin-1 e-acute",
        ("title = \"caf\xe9\"\n" + text.split("\n", 1)[1]).encode("latin-1", errors="replace"))
    add("invalid_utf8_comment", "non-UTF-8: bytes FF FE in a comment", b"# \xff\xfe\xfd\n" + data)
    add("utf16", "the file in UTF-16 (with BOM)", text.encode("utf-16"))
    add("utf8_bom", "a UTF-8 byte-order mark before the text", b"\xef\xbb\xbf" + data)
    add("nul_byte", "a NUL byte in the middle", data[: len(data) // 2] + b"\x00" + data[len(data) // 2:])
    add("empty", "an empty file", b"")
    add("whitespace", "only blank lines", b"\n   \n\t\n")
    add("comment_only", "only a comment", b"# nothing but a comment\n")
    add("directory", "a directory in place of the model file", artifact="directory")
    add("missing", "a model file that does not exist", artifact="missing")
    add("fifo", "a FIFO (named pipe) in place of the model file", artifact="fifo")
    add("dangling_symlink", "a symbolic link to nowhere", artifact="dangling_symlink")


def gen_nesting(b: _Builder, doc: dict, text: str):
    """Deeply nested arrays, inline tables and table headers."""
    def add(variant, description, content: bytes, names=FILE_TOKENS, target=""):
        b.add("nesting", target, variant, description, data=content, names=names)

    add("array_depth_5000", "a value nested in 5000 arrays", (text + "\ndeep = " + "[" * 5000 + "1" + "]" * 5000 + "\n").encode())
    add("inline_table_depth_2000", "a value nested in 2000 inline tables",
        (text + "\ndeep = " + "{a = " * 2000 + "1" + "}" * 2000 + "\n").encode())
    add("header_depth_1000", "a table header 1000 levels deep",
        (text + "\n[" + ".".join(["a"] * 1000) + "]\nx = 1\n").encode())
    add("dotted_key_depth_1000", "a dotted key 1000 levels deep",
        (text + "\n" + ".".join(["a"] * 1000) + " = 1\n").encode())
    first = next(((p, v) for p, v in walk(doc) if is_number(v)), None)
    if first:
        path, v = first
        for depth in (50, 3000):
            d = copy_doc(doc)
            new = 1.0
            for _ in range(depth):
                new = [new]
            set_at(d, path, new)
            try:
                content = dump(d, f"{label(path)} nested in {depth} arrays")
            except RecursionError:
                continue
            add(f"value_depth_{depth}", f"{label(path)} = 1.0 nested in {depth} arrays", content,
                names=names_for(path), target=fmt_path(path))


def gen_outputs(b: _Builder, base: bytes):
    """Bad output paths for every applicable command: --json and the command's other outputs."""
    for cmd in b.ex.commands:
        options = ((("--json", "file"),) if cmd != "render" else ()) + SECONDARY_OUTPUTS.get(cmd, ())
        for option, what_it_names in options:
            for kind, what in OUTPUT_KINDS.items():
                if option != "--json" and kind == "dev_full":
                    continue
                if what_it_names == "dir" and kind in ("bad_suffix", "long_name"):
                    continue
                if kind == "same_path" and len(options) < 2:
                    continue
                b.add("output", "", f"{cmd}{option}_{kind}", f"drivefem {cmd} {option} into {what}",
                      data=base, output=(option, kind), commands=(cmd,),
                      names=(option, option.lstrip("-"), "output", "directory", "path", "file"))


def _scale_at(path, factor):
    def edit(d):
        set_at(d, path, get_at(d, path) * factor)
    return edit


def _zero_keys(keys):
    def edit(d):
        for p, x in list(walk(d)):
            if is_number(x) and isinstance(p[-1], str) and p[-1] in keys:
                set_at(d, p, 0 if isinstance(x, int) else 0.0)
    return edit


def _set_analysis(values: dict):
    def edit(d):
        an = d.setdefault("analysis", {})
        for k in ("sweep_hz", "omega_rad_s", "frequencies_hz"):
            an.pop(k, None)
        an.update(copy_doc(values))
    return edit


def resonance_omega(doc: dict) -> float | None:
    """sqrt(k / m) of a lumped file with one body (its springs summed), the forcing at its undamped resonance."""
    bodies = doc.get("body")
    if not (isinstance(bodies, list) and len(bodies) == 1 and isinstance(bodies[0], dict)):
        return None
    name, m = bodies[0].get("name"), bodies[0].get("inertia")
    k = sum(s.get("k", 0.0) for s in doc.get("spring", []) if isinstance(s, dict) and name in s.get("between", ())
            and is_number(s.get("k", 0.0)))
    if not (is_number(m) and m > 0 and k > 0):
        return None
    return math.sqrt(k / m)


def gen_extreme(b: _Builder, doc: dict):
    """Schema-valid but physically extreme values: stiffness and inertia contrasts of 1e10 (one value scaled up
    or down against the rest), no damping at all, the forcing at 0 or at an undamped resonance, time constants
    far below any step."""
    for path, v in list(walk(doc)):
        key = path[-1] if isinstance(path[-1], str) else next((p for p in reversed(path) if isinstance(p, str)), "")
        if not is_number(v) or v == 0:
            continue
        where = label(path)
        if key in STIFFNESS_KEYS or key in INERTIA_KEYS:
            what = "stiffness" if key in STIFFNESS_KEYS else "inertia"
            for variant, f in (("x1e10", 1e10), ("x1e-10", 1e-10)):
                b.doc("extreme", path, f"{what}_{variant}", f"{where} scaled by {f:g} ({what} contrast with the rest "
                      "of the model)", _scale_at(path, f))
        if key in TIME_CONSTANT_KEYS and isinstance(path[-1], str):
            new = TIME_CONSTANT_KEYS[key]
            b.set("extreme", path, "time_constant", f"{where} = {new:g} (a time scale far below any step)", new)
    damped = [p for p, x in walk(doc) if is_number(x) and x and isinstance(p[-1], str) and p[-1] in DAMPING_KEYS]
    if damped:
        b.doc("extreme", ("damping",), "undamped", f"every damping value set to 0 ({len(damped)} values)",
              _zero_keys(DAMPING_KEYS), names=("damping",))
    an = doc.get("analysis")
    if isinstance(an, dict) and an.get("type") == "forced" and "steady" not in doc and "rotor" not in doc:
        b.doc("extreme", ("analysis", "omega_rad_s"), "omega_zero", "[analysis] omega_rad_s = [0.0, 1.0] (static)",
              _set_analysis({"omega_rad_s": [0.0, 1.0]}))
        w = resonance_omega(doc)
        if w is not None:
            both = {"omega_rad_s": [w, math.nextafter(w, 0.0)]}
            b.doc("extreme", ("analysis", "omega_rad_s"), "at_resonance", f"[analysis] omega_rad_s = [{w!r}, one "
                  "rounding below] (sqrt(k/m))", _set_analysis(both))
            b.doc("extreme", ("analysis", "omega_rad_s"), "undamped_at_resonance", f"no damping, forced at sqrt(k/m) "
                  f"= {w!r} rad/s", _both(_zero_keys(DAMPING_KEYS), _set_analysis(both)))


def _both(first, second):
    def edit(d):
        first(d)
        second(d)
    return edit


def gen_cli(b: _Builder, base: bytes):
    """Each command-line option of the file's commands with values out of range."""
    for cmd in b.ex.commands:
        for option, value in CLI_ATTACKS.get(cmd, ()):
            variant = f"{cmd}{option}_{value.replace('/', '_').replace(' ', '_').replace(':', '_')}"
            b.add("cli", "", variant, f"drivefem {cmd} {option} {value!r}", data=base, commands=(cmd,),
                  options=(option, value), names=(option, option.lstrip("-"), "scheduler", "directory"))


def mutations_of(ex: Example) -> list[Mutation]:
    """All mutations of one example, in a fixed order with unique, stable ids."""
    b = _Builder(ex)
    base_text = tomli_w.dumps(ex.cheap)
    base = dump(ex.cheap, f"{ex.name} cheap base: " + "; ".join(ex.cheap_notes))
    b.add("control", "", "original", f"{ex.name} as shipped", data=ex.text.encode("utf-8"))
    if ex.cheap_notes:
        b.add("control", "", "cheap_base", "cheap base: " + "; ".join(ex.cheap_notes), data=base)
    gen_values(b, ex.cheap)
    gen_structure(b, ex.cheap)
    gen_keys(b, ex.cheap)
    gen_semantic(b, ex.cheap)
    gen_units(b, ex.cheap)
    gen_text(b, base_text)
    gen_encoding(b, base_text)
    gen_nesting(b, ex.cheap, base_text)
    gen_outputs(b, base)
    gen_extreme(b, ex.cheap)
    gen_cli(b, base)
    return b.out


def all_mutations(examples: list[Example]) -> list[Mutation]:
    return [m for ex in examples for m in mutations_of(ex)]

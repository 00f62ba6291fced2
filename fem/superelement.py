"""Linear super-elements read from matrix files (Matrix Market or Harwell-Boeing), joined to the package's
shafts, and the export of the package's own FE matrices in the same format.

A super-element is a description file (JSON, the *sidecar*) naming its matrices and DOFs::

    {"format": "drivefem superelement 1",
     "title": "tail of the cantilever",
     "M": "tail_M.mtx", "K": "tail_K.mtx", "C": null,        # paths relative to the sidecar; C optional
     "dofs": ["w@x=0", "w_x@x=0", "w@x=0.1125", ...]}        # one unique name per matrix row

Matrices: ``.mtx`` (Matrix Market, :func:`scipy.io.mmread`) or ``.rua`` / ``.rsa`` / ``.hb`` / ``.rb``
(Harwell-Boeing, :func:`scipy.io.hb_read`), real, square, all of the size of ``dofs``; both formats
round-trip doubles exactly (17 significant digits).  The matrices are those of the super-element's free
DOFs (supports applied by the exporting code, or none).

In a hybrid model file (``[[superelement]]``, fem/modelfile/schema/superelement.py) each super-element
DOF is either *joined* to a DOF of the shaft (``join = [{ dof = "w@x=0", x = 0.3375, field = "w" }]``:
the two are one DOF, the matrices are added there) or kept as a new DOF named ``NAME:DOF`` (e.g.
``tail:w@x=0.1125``), which elements, forces and springs address like a body: ``body = "tail:w@x=0.1125"``.
The joined system goes through the hybrid pipeline as the shaft alone would (drivers, reduction, damping).
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem

FORMAT = "drivefem superelement 1"
MATRIX_MARKET = (".mtx",)
HARWELL_BOEING = (".rua", ".rsa", ".hb", ".rb")


@dataclass
class SuperElement:
    """Matrices (sparse, n x n) and DOF names of a linear super-element."""

    name: str
    M: sp.csr_matrix
    K: sp.csr_matrix
    C: sp.csr_matrix | None
    dofs: list[str]
    title: str = ""

    @property
    def n(self) -> int:
        return len(self.dofs)


def _read_matrix(path: Path, where: str, key: str):
    import scipy.io as sio

    suffix = path.suffix.lower()
    if not path.is_file():
        raise ModelError(where, key, str(path), "an existing matrix file")
    try:
        if suffix in MATRIX_MARKET:
            A = sio.mmread(str(path))
        elif suffix in HARWELL_BOEING:
            A = sio.hb_read(str(path))
        else:
            raise ModelError(where, key, str(path), "a Matrix Market (.mtx) or Harwell-Boeing (.rua, .rsa, .hb, .rb) file")
    except ModelError:
        raise
    except Exception as exc:      # the readers raise ValueError, IndexError, ... on malformed files
        raise ModelError(where, key, str(path), f"a readable matrix file ({type(exc).__name__}: {exc})") from None
    A = sp.csr_matrix(A)
    if np.iscomplexobj(A.data):
        raise ModelError(where, key, str(path), "a real matrix")
    return A.astype(float)


def read_superelement(path: str | Path, name: str = "", where: str = "superelement") -> SuperElement:
    """The super-element of a sidecar file (module docstring); errors name the file and the key."""
    path = Path(path)
    if not path.is_file():
        raise ModelError(where, "file", str(path), "an existing super-element description (JSON)")
    try:
        doc = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ModelError(where, "file", str(path), f"a JSON super-element description ({exc})") from None
    w = f"{where} ({path.name})"
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise ModelError(w, "format", doc.get("format") if isinstance(doc, dict) else doc, repr(FORMAT))
    dofs = doc.get("dofs")
    if not isinstance(dofs, list) or not dofs or not all(isinstance(d, str) and d for d in dofs):
        raise ModelError(w, "dofs", dofs, "a non-empty list of DOF names (strings)")
    if len(set(dofs)) != len(dofs):
        dup = sorted({d for d in dofs if dofs.count(d) > 1})
        raise ModelError(w, "dofs", dup, "unique DOF names")
    mats = {}
    for key in ("M", "K", "C"):
        ref = doc.get(key)
        if ref is None:
            if key != "C":
                raise ModelError(w, key, None, f"the file of the {'mass' if key == 'M' else 'stiffness'} matrix "
                                 "(required key missing)")
            continue
        if not isinstance(ref, str):
            raise ModelError(w, key, ref, "a matrix file name (relative to the description)")
        A = _read_matrix(path.parent / ref, w, key)
        if A.shape != (len(dofs), len(dofs)):
            raise ModelError(w, key, f"{A.shape[0]} x {A.shape[1]}", f"a square matrix of the {len(dofs)} DOFs "
                             "listed in dofs")
        if A.nnz and not np.all(np.isfinite(A.data)):
            raise ModelError(w, key, "inf/NaN entries", "finite matrix entries")
        mats[key] = A
    return SuperElement(name=name or path.stem, M=mats["M"], K=mats["K"], C=mats.get("C"), dofs=list(dofs),
                        title=str(doc.get("title", "")))


def write_superelement(path: str | Path, system: LinearSystem, title: str = "", fmt: str = "mtx") -> Path:
    """Write the free DOFs' M, K (and C when nonzero) of ``system`` as matrix files next to the sidecar
    ``path`` (``fmt`` "mtx": Matrix Market, "hb": Harwell-Boeing ``.rua``), the DOF names being the
    system's labels (``w@x=0.1125``).  Returns the sidecar's path."""
    import scipy.io as sio

    if fmt not in ("mtx", "hb"):
        raise ModelError("write_superelement", "fmt", fmt, "'mtx' (Matrix Market) or 'hb' (Harwell-Boeing)")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    f = system.free
    doc = {"format": FORMAT, "title": title or system.title, "M": None, "K": None, "C": None,
           "dofs": [system.label(int(j)) for j in f]}
    for key in ("M", "K", "C"):
        A = sp.csc_matrix(getattr(system, key)[f][:, f])
        A.eliminate_zeros()
        if key == "C" and A.nnz == 0:
            continue
        name = f"{path.stem}_{key}." + ("mtx" if fmt == "mtx" else "rua")
        if fmt == "mtx":
            sio.mmwrite(str(path.parent / name), A, comment=f"{doc['title']}: {key}")
        else:
            sio.hb_write(str(path.parent / name), A)
        doc[key] = name
    path.write_text(json.dumps(doc, indent=1) + "\n")
    return path


def join(system: LinearSystem, parts: list[tuple[SuperElement, dict[str, int]]]) -> tuple[LinearSystem, dict[str, int]]:
    """The shaft's system with the super-elements added: ``parts`` = [(super-element, {its DOF name: index
    of the shaft DOF it is joined to})].  Unjoined super-element DOFs are appended (named ``NAME:DOF``,
    field ``x``, no position).  Returns the system and {``NAME:DOF``: index} of every super-element DOF."""
    n0 = system.n_dofs
    rows, index = [], {}
    n = n0
    maps = []
    for se, joined in parts:
        idx = np.empty(se.n, int)
        for i, d in enumerate(se.dofs):
            if d in joined:
                idx[i] = joined[d]
            else:
                idx[i] = n
                rows.append(f"{se.name}:{d}")
                n += 1
            index[f"{se.name}:{d}"] = int(idx[i])
        maps.append(idx)

    def grow(A):
        A = sp.csr_matrix(A)
        indptr = np.concatenate([A.indptr, np.full(n - n0, A.indptr[-1])])
        return sp.csr_matrix((A.data, A.indices, indptr), shape=(n, n))

    def scatter(A, idx):
        A = sp.coo_matrix(A)
        return sp.csr_matrix((A.data, (idx[A.row], idx[A.col])), shape=(n, n))

    M, K, C, Hm = grow(system.M), grow(system.K), grow(system.C), grow(system.H)
    for (se, _), idx in zip(parts, maps):
        M = M + scatter(se.M, idx)
        K = K + scatter(se.K, idx)
        if se.C is not None:
            C = C + scatter(se.C, idx)
    extra = n - n0
    fields = np.concatenate([np.asarray(system.dof_field, object), np.full(extra, "x", object)])
    xs = np.concatenate([np.asarray(system.dof_x, float), np.full(extra, np.nan)])
    names = np.concatenate([np.asarray(system.dof_name, object), np.array(rows, object)])
    G = system.G
    out = LinearSystem(M=M, K=K, C=C, H=Hm, G=grow(G) if G is not None and G.nnz else None, dof_field=fields,
                       dof_x=xs, dof_name=names, constrained=system.constrained, rigid_modes=None,
                       title=system.title, physics=system.physics)
    return out, index


def export_shaft(model_path: str | Path, out: str | Path, fmt: str = "mtx") -> Path:
    """Assemble the shaft of an FE or hybrid model file and write it as a super-element (its free DOFs)."""
    from .assembly import assemble
    from .modelfile import load
    from .modelfile.build.fe import shaft_model

    doc = load(model_path)
    fe = assemble(shaft_model(doc))
    return write_superelement(out, fe.system, title=doc.title, fmt=fmt)


def main(argv=None) -> int:
    """``python -m fem.superelement MODEL.toml OUT.json [--format mtx|hb]``: export the shaft's matrices."""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m fem.superelement", description=main.__doc__)
    ap.add_argument("model")
    ap.add_argument("out")
    ap.add_argument("--format", choices=("mtx", "hb"), default="mtx")
    args = ap.parse_args(argv)
    try:
        p = export_shaft(args.model, args.out, args.format)
    except ModelError as exc:
        print(f"error: {exc}")
        return 2
    print(f"wrote {p}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

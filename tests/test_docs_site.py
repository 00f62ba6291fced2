"""The documentation site's structure (the build itself is `make docs`, run by CI): every public
package has an API page, and every API page is in the site's navigation."""
import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"^<!-- api: ([\w.]+) -->$", re.M)


def _packages_with_all() -> set[str]:
    out = set()
    for init in sorted(ROOT.glob("*/__init__.py")) + sorted(ROOT.glob("*/*/__init__.py")):
        if init.parts[-2 if init.parent.parent == ROOT else -3] not in {"fem", "discrete"}:
            continue
        tree = ast.parse(init.read_text(encoding="utf-8"))
        if any(isinstance(n, ast.Assign) and any(getattr(t, "id", None) == "__all__" for t in n.targets)
               for n in tree.body):
            out.add(".".join(init.parent.relative_to(ROOT).parts))
    return out


def test_every_public_package_has_an_api_page():
    documented = {m for page in (ROOT / "docs" / "api").glob("*.md") for m in MARKER.findall(page.read_text())}
    missing = _packages_with_all() - documented
    assert {"fem", "discrete", "fem.rotor", "discrete.steady"} <= documented
    assert not missing, (f"packages with __all__ but no API page: {sorted(missing)}; add docs/api/NAME.md with "
                         "'<!-- api: PACKAGE -->' and a nav entry in mkdocs.yml (docs/writing_docs.md)")


def test_every_page_is_in_the_navigation():
    nav = (ROOT / "mkdocs.yml").read_text()
    pages = [p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").rglob("*.md")
             if "hooks" not in p.parts]
    missing = [p for p in pages if not re.search(rf"(^|[\s:]){re.escape(p)}\s*$", nav, re.M)]
    assert not missing, (f"docs pages not in the nav of mkdocs.yml: {missing}; add each as '      - Title: PAGE' "
                         "under its section of 'nav:' (e.g. a geared-train page under 'Nonsmooth and "
                         "nonlinear'), and a row of the README's Documentation table")


def test_the_gallery_shows_every_figure_of_the_docs():
    """docs/gallery.md shows every picture of docs/img/ (a new figure kind gets a place there); the
    pictures of subfolders (e.g. docs/img/gallery/ of `drivefem demo --gallery docs`) belong to the
    page that writes them."""
    gallery = (ROOT / "docs" / "gallery.md").read_text()
    missing = [p.name for p in sorted((ROOT / "docs" / "img").iterdir())
               if p.is_file() and f"img/{p.name}" not in gallery]
    assert not missing, f"pictures of docs/img/ not on docs/gallery.md: {missing}"


def test_the_readme_links_every_page():
    """The README (the landing page and the site's home) links every page of docs/ (the API pages
    through docs/api/index.md), so a new page is reachable from where a reader starts."""
    readme = (ROOT / "README.md").read_text()
    pages = [p.name for p in sorted((ROOT / "docs").glob("*.md")) if p.name != "index.md"] + ["api/index.md"]
    missing = [p for p in pages if f"](docs/{p})" not in readme]
    assert not missing, f"pages of docs/ the README does not link (its Documentation table): {missing}"

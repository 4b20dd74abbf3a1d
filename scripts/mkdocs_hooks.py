"""MkDocs hooks of the famcc documentation site (mkdocs.yml: ``hooks``).

1. Links that leave ``docs/``. The pages under ``docs/`` are read in the repository
   too, where ``../benches/README.md`` is a valid link; on the site it is not. Each
   such relative link is rewritten: to the page that includes that file
   (``INCLUDED``, e.g. ``embedded/README.md`` -> ``firmware.md``), otherwise to the
   file in the repository browser (``repo_url``/blob/main/PATH). A link to a file
   that does not exist is a warning, so ``mkdocs build --strict`` fails on it as on
   any broken link.
2. Optional pages. Pages being written elsewhere (``OPTIONAL``) are added to the
   navigation when their file exists, so that the nav never names a missing file.
"""

from __future__ import annotations

import logging
import posixpath
import re
from pathlib import Path
from typing import Any

log = logging.getLogger("mkdocs.hooks.famcc")

#: Repository files outside docs/ that a docs page includes (include-markdown).
INCLUDED = {
    "embedded/README.md": "firmware.md",
    "crates/famcc-ffi/README.md": "firmware.md",
    "benches/README.md": "performance.md",
}

#: (file under docs/, nav title, title of the nav entry to insert it after).
OPTIONAL = [
    ("tuning.md", "Tuning", "Getting started"),
    ("equations.md", "Paper-to-code map", "Errata"),
    ("glossary.md", "Glossary", "Design decisions"),
]

_FENCE = re.compile(r"^(```|~~~)")
_LINK = re.compile(r"(\]\()([^)\s]+)(\))")
_SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def _rewrite(target: str, page_dir: str, docs: Path, root: Path, repo: str, where: str) -> str:
    if _SCHEME.match(target) or target.startswith(("#", "/")):
        return target
    path, _, anchor = target.partition("#")
    if not path:
        return target
    rel = posixpath.normpath(posixpath.join(page_dir, path))
    if not rel.startswith("../"):
        return target  # inside docs/: MkDocs validates it
    in_repo = posixpath.normpath(posixpath.join(docs.relative_to(root).as_posix(), rel))
    if in_repo.startswith("../") or not (root / in_repo).exists():
        log.warning("%s: link to %r, which is not a file of the repository", where, target)
        return target
    if in_repo in INCLUDED:
        new = posixpath.relpath(INCLUDED[in_repo], page_dir or ".")
        return new + (f"#{anchor}" if anchor else "")
    kind = "tree" if (root / in_repo).is_dir() else "blob"
    return f"{repo.rstrip('/')}/{kind}/main/{in_repo}" + (f"#{anchor}" if anchor else "")


def on_page_markdown(markdown: str, page: Any, config: Any, files: Any) -> str:
    docs = Path(config["docs_dir"]).resolve()
    root = Path(config["config_file_path"]).resolve().parent
    repo = config.get("repo_url") or ""
    page_dir = posixpath.dirname(page.file.src_uri)
    out, fenced = [], False
    for line in markdown.splitlines(keepends=True):
        if _FENCE.match(line.lstrip()):
            fenced = not fenced
        if not fenced:
            line = _LINK.sub(
                lambda m: (
                    m[1] + _rewrite(m[2], page_dir, docs, root, repo, page.file.src_uri) + m[3]
                ),
                line,
            )
        out.append(line)
    return "".join(out)


def _sources(nav: Any) -> list[str]:
    if isinstance(nav, str):
        return [nav]
    if isinstance(nav, dict):
        return [s for v in nav.values() for s in _sources(v)]
    if isinstance(nav, list):
        return [s for v in nav for s in _sources(v)]
    return []


def on_config(config: Any) -> Any:
    nav = config.get("nav")
    if not nav:
        return config
    docs = Path(config["docs_dir"])
    for src, title, after in OPTIONAL:
        named = set(_sources(nav))
        if not (docs / src).is_file() or src in named:
            continue
        titles = [next(iter(item)) if isinstance(item, dict) else None for item in nav]
        at = titles.index(after) + 1 if after in titles else len(nav)
        nav.insert(at, {title: src})
    return config

"""The Rust crates' modules, read from their source: no two modules of a crate use each
other, nor any longer circle of modules (a module declaring or re-exporting its own
submodules aside), and no hand-written source file of a crate is over 400 lines.

A module's uses are the paths it names from its own crate (``use crate::a::b``,
``super::x``, ``crate::a::f(...)`` in code), each resolved to the deepest module it
names; comments, strings and the ``#[cfg(test)]`` module at the end of a file are left
out (test code may reach anywhere).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from test_architecture import find_cycle

ROOT = Path(__file__).resolve().parents[1]
CRATES = sorted(p.parent.name for p in (ROOT / "crates").glob("*/src"))


def modules(src: Path) -> dict[str, Path]:
    """``{module path: file}`` of a crate's ``src`` (the root is ``""``)."""
    out = {}
    for p in sorted(src.rglob("*.rs")):
        parts = list(p.relative_to(src).with_suffix("").parts)
        if parts == ["lib"] or parts == ["main"]:
            parts = []
        elif parts[-1] == "mod":
            parts.pop()
        out["::".join(parts)] = p
    return out


def production_code(text: str) -> str:
    """The file without its test module, comments and string contents."""
    m = re.search(r"#\[cfg\(test\)\]\s*(?:pub(?:\([a-z]+\))?\s+)?mod\s+\w+\s*\{", text)
    text = text[: m.start()] if m else text
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    return "\n".join(line.split("//", 1)[0] for line in text.splitlines())


def expand(path: str) -> list[str]:
    """``a::{b, c::{d, e}}`` -> ``["a::b", "a::c::d", "a::c::e"]``."""
    path = re.sub(r"\s+", "", path)
    if "{" not in path:
        return [path]
    i = path.index("{")
    head, body = path[:i], path[i + 1 : path.rindex("}")]
    items, depth, cur = [], 0, ""
    for ch in body:
        if ch == "," and depth == 0:
            items.append(cur)
            cur = ""
            continue
        depth += (ch == "{") - (ch == "}")
        cur += ch
    items.append(cur)
    return [x for item in items if item for x in expand(head + item)]


def uses(mod: str, path: Path, known: set[str]) -> set[str]:
    """The crate's modules that ``mod`` names in its production code."""
    code = production_code(path.read_text())
    paths = [p for m in re.finditer(r"\buse\s+([^;]+);", code) for p in expand(m.group(1))]
    paths += re.findall(r"\b((?:crate|super|self)(?:::\w+)+)", code)
    here = mod.split("::") if mod else []
    out: set[str] = set()
    for p in paths:
        seg = [s.split(" as ")[0] for s in p.split("::") if s]
        if not seg or seg[0] not in {"crate", "super", "self"}:
            continue
        base = [] if seg[0] == "crate" else list(here)
        seg = seg[1:] if seg[0] == "crate" else seg
        while seg and seg[0] in {"super", "self"}:
            base = base[:-1] if seg[0] == "super" else base
            seg = seg[1:]
        full = base + seg
        for n in range(len(full), -1, -1):
            if (cand := "::".join(full[:n])) in known:
                if cand != mod:
                    out.add(cand)
                break
    return out


def graph(src: Path) -> dict[str, set[str]]:
    """Module -> the modules it uses; a module's own submodules (declared, re-exported)
    are not its uses."""
    mods = modules(src)
    known = set(mods)
    g = {m: uses(m, p, known) for m, p in mods.items()}
    return {m: {t for t in ts if m and not t.startswith(m + "::")} for m, ts in g.items()}


@pytest.mark.parametrize("crate", CRATES)
def test_no_two_modules_of_a_crate_use_each_other(crate: str) -> None:
    g = graph(ROOT / "crates" / crate / "src")
    pairs = sorted({tuple(sorted((a, b))) for a, ts in g.items() for b in ts if a in g[b]})
    assert not pairs, f"{crate}: modules that use each other: {pairs}"
    cycle = find_cycle(g)
    assert cycle is None, f"{crate}: " + " -> ".join(cycle or [])


def test_the_module_graph_sees_a_pair_and_a_longer_circle(tmp_path: Path) -> None:
    src = tmp_path / "src"
    (src / "design").mkdir(parents=True)
    (src / "lib.rs").write_text("mod design;\nmod plants;\npub use design::rules::design;\n")
    (src / "design" / "mod.rs").write_text("mod linear;\nmod rules;\npub const MAX: usize = 8;\n")
    (src / "design" / "linear.rs").write_text(
        "use super::{rules::manifold, MAX};\n// use super::coefficients::x;\n"
    )
    (src / "design" / "rules.rs").write_text(
        'use super::MAX;\nfn f() { let s = "super::linear::x"; super::linear::radius(); }\n'
        "#[cfg(test)]\nmod tests {\n    use crate::plants::*;\n}\n"
    )
    (src / "plants.rs").write_text("pub fn x() { crate::design::MAX; }\n")
    g = graph(src)
    assert g["design::linear"] == {"design", "design::rules"}
    assert g["design::rules"] == {"design", "design::linear"}  # the test module is left out
    assert g["design"] == set() and g[""] == set()  # its own submodules are not uses
    assert find_cycle(g) == ["design::linear", "design::rules", "design::linear"]
    (src / "design" / "rules.rs").write_text("use super::MAX;\n")
    (src / "design" / "mod.rs").write_text("mod linear;\nuse crate::plants::x;\n")
    (src / "design" / "linear.rs").write_text("use crate::plants::x;\n")
    assert find_cycle(graph(src)) == ["design", "plants", "design"]


def _generated(p: Path) -> bool:
    return "@generated" in p.read_text()[:200]


@pytest.mark.parametrize("crate", CRATES)
def test_no_hand_written_source_file_of_a_crate_is_over_400_lines(crate: str) -> None:
    src = ROOT / "crates" / crate / "src"
    long = {
        str(p.relative_to(ROOT)): n
        for p in sorted(src.rglob("*.rs"))
        if not _generated(p) and (n := len(p.read_text().splitlines())) > 400
    }
    assert not long, long

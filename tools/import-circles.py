#!/usr/bin/env python3
"""File-level import circles inside each crate of the workspace.

For every crate (a directory with a `Cargo.toml` and `src/lib.rs` or `src/main.rs`, and
the `tests/` crate), the files are the modules reached from the crate root through
`mod` declarations. A file depends on another when one of its `use` declarations, or a
path written in its code (`crate::…`, `super::…`, `self::…`, or a child module's
name), names an item defined in the other file. Names are followed through `use`
declarations (re-exports and globs included) to the file that defines them, so a path
through a facade (`crate::stages::Sampler`) counts as a dependency of the file that
defines `Sampler`, not of `stages/mod.rs`. A `pub use` (a re-export) is not itself a
dependency of the re-exporting file unless its own code uses the name; `mod`
declarations are not imports.

Prints every strongly connected component of more than one file, per crate, and exits
with status 1 when there is one; prints nothing and exits 0 otherwise.

Usage: tools/import-circles.py [--why] [workspace-root]   (--why: the edges of each circle)
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ITEM = re.compile(
    r"^\s*(?:pub(?:\([^)]*\))?\s+)?(?:unsafe\s+|async\s+|const\s+|extern\s+\"C\"\s+)*"
    r"(?:fn|struct|enum|trait|type|const|static|union|mod)\s+([A-Za-z_][A-Za-z0-9_]*)",
    re.M,
)
MACRO = re.compile(r"macro_rules!\s*([A-Za-z_][A-Za-z0-9_]*)")
MOD_DECL = re.compile(
    r"((?:#\[[^\]]*\]\s*)*)(?:pub(?:\([^)]*\))?\s+)?mod\s+([A-Za-z_][A-Za-z0-9_]*)\s*;"
)
PATH_ATTR = re.compile(r'#\[path\s*=\s*"([^"]+)"\]')
USE = re.compile(r"(?:^|[;{}\s])((?:pub(?:\([^)]*\))?\s+)?)use\s+([^;]+);", re.S)
INLINE = re.compile(r"(?<![A-Za-z0-9_:])((?:crate|super|self)(?:::[A-Za-z_][A-Za-z0-9_]*)+)")


def strip(text: str) -> str:
    """The source without comments, string and char literals (kept as blanks)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    i += 1
        elif c == "r" and re.match(r'r#*"', text[i:i + 10]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + len(m.group(0)))
            i = n if j < 0 else j + len(end)
            out.append('""')
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            out.append('""')
        elif c == "'" and re.match(r"'(\\.|[^\\'])'", text[i:i + 4]):
            i += len(re.match(r"'(\\.|[^\\'])'", text[i:]).group(0))
            out.append("' '")
        else:
            out.append(c)
            i += 1
    return "".join(out)


def inline_modules_as_self(text: str) -> str:
    """`super::` inside an inline module (`mod tests { … }`) names the file's own module:
    written as `self::` so that it resolves to this file (one level of nesting)."""
    out, i = [], 0
    for m in re.finditer(r"\bmod\s+[A-Za-z_][A-Za-z0-9_]*\s*\{", text):
        if m.start() < i:
            continue
        depth, j = 0, m.end() - 1
        while j < len(text):
            if text[j] == "{":
                depth += 1
            elif text[j] == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        out.append(text[i:m.end()])
        out.append(re.sub(r"\bsuper::", "self::", text[m.end():j]))
        i = j
    out.append(text[i:])
    return "".join(out)


def expand(tree: str) -> list[tuple[list[str], str]]:
    """`a::{b, c::d as e, f::*}` → [(["a", "b"], "b"), (["a", "c", "d"], "e"), (["a", "f", "*"], "*")]."""
    tree = re.sub(r"\s+", "", tree)
    out: list[tuple[list[str], str]] = []

    def walk(prefix: list[str], text: str) -> None:
        # split text at top-level commas
        parts, depth, start = [], 0, 0
        for k, ch in enumerate(text):
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            elif ch == "," and depth == 0:
                parts.append(text[start:k])
                start = k + 1
        parts.append(text[start:])
        for part in filter(None, parts):
            brace = part.find("{")
            if brace >= 0 and part.endswith("}"):
                head = [s for s in part[:brace].split("::") if s]
                walk(prefix + head, part[brace + 1:-1])
                continue
            alias = None
            if "as" in part and re.search(r"[A-Za-z0-9_]as[A-Za-z_]", part):
                m = re.match(r"(.*[A-Za-z0-9_*])as([A-Za-z_][A-Za-z0-9_]*)$", part)
                if m:
                    part, alias = m.group(1), m.group(2)
            segs = [s for s in part.split("::") if s]
            if segs == ["self"]:
                segs = []
            full = prefix + segs
            if full:
                out.append((full, alias or full[-1]))

    walk([], tree)
    return out


class Module:
    def __init__(self, path: tuple[str, ...], file: Path):
        self.path = path
        self.file = file
        self.children: dict[str, tuple[str, ...]] = {}
        self.text = inline_modules_as_self(strip(file.read_text(encoding="utf-8")))
        self.defined = set(ITEM.findall(self.text)) | set(MACRO.findall(self.text))
        # (path segments, visible name, is a re-export)
        self.uses: list[tuple[list[str], str, bool]] = []
        for m in USE.finditer(self.text):
            reexport = bool(m.group(1).strip())
            for segs, name in expand(m.group(2)):
                self.uses.append((segs, name, reexport))


class Crate:
    def __init__(self, root_file: Path):
        self.modules: dict[tuple[str, ...], Module] = {}
        self.load((), root_file, root_file.parent)

    def load(self, path: tuple[str, ...], file: Path, dir_: Path) -> None:
        module = Module(path, file)
        self.modules[path] = module
        for m in MOD_DECL.finditer(module.text):
            attrs, name = m.group(1), m.group(2)
            custom = PATH_ATTR.search(attrs or "")
            if custom:
                child = file.parent / custom.group(1)
            else:
                child = dir_ / f"{name}.rs"
                if not child.exists():
                    child = dir_ / name / "mod.rs"
            if not child.exists():
                continue
            child_dir = child.parent if child.name == "mod.rs" else child.parent / child.stem
            module.children[name] = path + (name,)
            self.load(path + (name,), child, child_dir)

    def start(self, module: Module, first: str) -> tuple[str, ...] | None:
        if first == "crate":
            return ()
        if first == "self":
            return module.path
        if first == "super":
            return module.path[:-1]
        return None

    def resolve(self, module: Module, segs: list[str], depth: int = 0) -> Path | None:
        """The file defining the item `segs` names from `module` (None: outside the crate)."""
        if depth > 20 or not segs:
            return None
        here = self.start(module, segs[0])
        rest = segs[1:]
        if here is None:
            if segs[0] in module.children:
                here, rest = module.children[segs[0]], segs[1:]
            else:
                # A name `module` imported (a `use` alias): follow it.
                for useg, name, _ in module.uses:
                    if name == segs[0] and useg != segs:
                        return self.resolve(module, useg + segs[1:], depth + 1)
                return None
        while rest and rest[0] == "super":
            here, rest = here[:-1], rest[1:]
        current = self.modules.get(here)
        while current and rest:
            name = rest[0]
            if name in current.children:
                current = self.modules.get(current.children[name])
                rest = rest[1:]
                continue
            if name == "*":
                return current.file
            if name in current.defined:
                return current.file
            for useg, alias, _ in current.uses:
                if alias == name:
                    found = self.resolve(current, useg, depth + 1)
                    return found if found else current.file
            for useg, alias, _ in current.uses:
                if alias == "*":
                    found = self.resolve(current, useg[:-1] + [name], depth + 1)
                    if found and found != current.file:
                        return found
            return current.file
        return current.file if current else None

    def edges(self) -> dict[Path, set[Path]]:
        graph: dict[Path, set[Path]] = {m.file: set() for m in self.modules.values()}
        self.why: dict[tuple[Path, Path], str] = {}
        for module in self.modules.values():
            body = USE.sub(" ", module.text)
            # A re-export is a dependency too when the file's own code uses the name.
            paths = [
                segs
                for segs, name, reexport in module.uses
                if not reexport or (name != "*" and re.search(rf"\b{re.escape(name)}\b", body))
            ]
            paths += [p.split("::") for p in INLINE.findall(body)]
            for segs in paths:
                if segs[-1] == "*":
                    segs = segs[:-1]
                target = self.resolve(module, segs)
                if target and target != module.file:
                    graph[module.file].add(target)
                    self.why.setdefault((module.file, target), "::".join(segs))
        return graph


def components(graph: dict[Path, set[Path]]) -> list[list[Path]]:
    """Tarjan's strongly connected components."""
    index: dict[Path, int] = {}
    low: dict[Path, int] = {}
    stack: list[Path] = []
    on: set[Path] = set()
    found: list[list[Path]] = []
    counter = [0]
    sys.setrecursionlimit(10000)

    def visit(v: Path) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            scc = []
            while True:
                w = stack.pop()
                on.discard(w)
                scc.append(w)
                if w == v:
                    break
            found.append(scc)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return [sorted(c) for c in found if len(c) > 1]


def crate_roots(workspace: Path) -> list[Path]:
    roots = []
    for manifest in sorted(workspace.glob("**/Cargo.toml")):
        if "target" in manifest.parts or ".git" in manifest.parts:
            continue
        for name in ("src/lib.rs", "src/main.rs", "lib.rs"):
            root = manifest.parent / name
            if root.exists():
                roots.append(root)
    return roots


def main() -> int:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    workspace = Path(args[0] if args else Path(__file__).resolve().parents[1])
    circles = 0
    for root in crate_roots(workspace):
        crate = Crate(root)
        graph = crate.edges()
        for scc in components(graph):
            circles += 1
            shown = ", ".join(str(p.relative_to(workspace)) for p in scc)
            print(f"{root.parent.relative_to(workspace)}: circle of {len(scc)} files: {shown}")
            if "--why" in sys.argv:
                for a in scc:
                    for b in sorted(graph[a] & set(scc)):
                        print(f"    {a.relative_to(root.parent)} -> {b.relative_to(root.parent)}"
                              f" ({crate.why[(a, b)]})")
    return 1 if circles else 0


if __name__ == "__main__":
    sys.exit(main())

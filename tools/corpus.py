#!/usr/bin/env python3
"""Audit a corpus of LaTeX / Markdown written by others with `verify audit`, and report.

Every document of the corpus folder (a `.tex` holding a display -- `\\begin{equation`,
`\\begin{align`, `$$`, `\\[`, `\\begin{eqnarray`, `\\begin{gather`, `\\begin{multline` -- or a
`.md` holding one, `$$` or the same environments, which the audit reads alike) is audited with

    BIN audit DOC --format json [--units FILE]

one process per document, at most two at once, 60 s each. The report (Markdown) gives, per
source (the first folder under the corpus, `owner__repo`, with its repository and commit from
SOURCES.md), the documents, relations, the share read (not unreadable), the counts per status,
the documents whose audit failed (exit code and first line of its message) and the time; then
the totals; then the constructs the LaTeX reader lacks, ranked by count, each with an example;
then every inconsistent relation (each a possible false alarm to check by hand).

    python3 tools/corpus.py /work/corpus --sources /work/corpus/SOURCES.md \\
        --bin target/release/verify --out reports/corpus.md --json corpus.json

Standard library only (Python 3.11).
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from pathlib import Path

TEX_MARKERS = (
    "\\begin{equation",
    "\\begin{align",
    "$$",
    "\\[",
    "\\begin{eqnarray",
    "\\begin{gather",
    "\\begin{multline",
)
STATUSES = ("consistent", "inconsistent", "undetermined", "unreadable")
MAX_JOBS = 2


@dataclass
class Doc:
    """One audited document and what its audit gave."""

    path: Path
    rel: str  # path relative to the corpus folder
    source: str  # the first folder under the corpus
    rc: int | None = None  # None: timed out or could not start
    seconds: float = 0.0
    message: str = ""  # first line of the error, for a failed audit
    relations: list[dict] = field(default_factory=list)
    preambles: list[Path] = field(default_factory=list)  # macro files given with --preamble

    def counts(self) -> Counter:
        return Counter(r.get("status", "?") for r in self.relations)


# ---------------------------------------------------------------- inputs


def read_sources(path: Path | None) -> dict[str, dict]:
    """`## owner/repo` sections of SOURCES.md, each with its commit (the first 40-hex string
    of the section) and its description line, keyed by the folder name `owner__repo`."""
    out: dict[str, dict] = {}
    if path is None:
        return out
    text = path.read_text(encoding="utf-8", errors="replace")
    sections = re.split(r"(?m)^##\s+", text)[1:]
    for sec in sections:
        head, _, body = sec.partition("\n")
        repo = head.strip().strip("`")
        m = re.search(r"\b[0-9a-f]{40}\b", body)
        desc = re.search(r"(?mi)^-?\s*description:\s*(.+)$", body)
        lic = re.search(r"(?mi)^-?\s*licen[cs]e:\s*(.+)$", body)
        out[repo.replace("/", "__")] = {
            "repo": repo,
            "commit": m.group(0) if m else "",
            "description": desc.group(1).strip() if desc else "",
            "licence": lic.group(1).strip() if lic else "",
        }
    return out


def has_display(path: Path) -> bool:
    """Whether the document holds a display marker outside TeX comments; `\\[2pt]` (a line
    break with its space) is no `\\[`."""
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return False
    if path.suffix.lower() == ".tex":
        text = re.sub(r"(?<!\\)%.*", "", text)
    text = text.replace("\\\\[", "")
    return any(m in text for m in TEX_MARKERS)


SEARCH = re.compile(r"\\input@path\s*\{((?:\{[^{}]*\})*)\}")
INPUT = re.compile(r"\\(?:input|include|subfile)\s*\{([^}]*)\}")
# `\import{dir}{file}` (from the main file's folder) and `\subimport{dir}{file}` (from the
# folder of the file that holds it)
IMPORT = re.compile(r"\\(sub)?(?:import|inputfrom|includefrom)\s*\{([^}]*)\}\s*\{([^}]*)\}")
SUBFILES = re.compile(r"\\documentclass\s*\[[^\]]*\]\s*\{subfiles\}")


def strip_comments(text: str) -> str:
    return re.sub(r"(?<!\\)%.*", "", text)


def included(main: Path) -> set[Path]:
    """The files a main document reads through `\\input`, `\\include` and `\\subfile`,
    transitively, relative to its folder (as `verify audit` follows them)."""
    seen: set[Path] = set()
    todo = [main]
    while todo:
        f = todo.pop()
        try:
            text = strip_comments(f.read_text(encoding="utf-8", errors="replace"))
        except OSError:
            continue
        # the folders of `\\input@path`, in the file or in its own class or packages
        search = SEARCH.findall(text)
        for cls in re.findall(r"\\(?:documentclass|usepackage)(?:\[[^\]]*\])?\{([^}]*)\}", text):
            for ext in (".cls", ".sty"):
                own = main.parent / (cls.strip() + ext)
                if own.is_file():
                    search += SEARCH.findall(strip_comments(own.read_text(encoding="utf-8", errors="replace")))
        for sub, folder, name in IMPORT.findall(text):
            base = f.parent if sub else main.parent
            for n in (name.strip(), name.strip() + ".tex"):
                cand = base / folder.strip() / n
                if cand.is_file() and cand not in seen:
                    seen.add(cand)
                    todo.append(cand)
                    break
        for name in INPUT.findall(text):
            # a path macro (`\\mainpath/Header`): the paper's folder on its author's machine
            name = re.sub(r"\\[A-Za-z]+\s*/?", "", name).lstrip("/")
            dirs = [""] + [d for found in search for d in re.findall(r"\{([^{}]*)\}", found)]
            cands = [main.parent / d / n for d in dirs for n in (name.strip(), name.strip() + ".tex")]
            for cand in cands:
                if cand.is_file() and cand not in seen:
                    seen.add(cand)
                    todo.append(cand)
                    break
    return seen


def macro_files(source_dir: Path) -> list[Path]:
    """A source's files of macros only (`.sty`, or a `.tex` with definitions and no display
    and no `\\documentclass`): the preamble of its Markdown notes, which keep their macros
    apart."""
    out = []
    for p in sorted(source_dir.rglob("*")):
        if not p.is_file() or p.suffix.lower() not in (".tex", ".sty"):
            continue
        text = strip_comments(p.read_text(encoding="utf-8", errors="replace"))
        defines = re.search(r"\\(newcommand|renewcommand|def|DeclareMathOperator)\b", text)
        if defines and "\\documentclass" not in text and (p.suffix == ".sty" or not has_display(p)):
            out.append(p)
    return out


def nearest_main(p: Path, top: Path, mains: list[Path]) -> list[Path]:
    """The main file in `p`'s folder or the nearest folder above it, up to `top` (the first by
    name when a folder holds several), as a list of none or one."""
    d = p.parent
    while True:
        here = sorted(m for m in mains if m.parent == d)
        if here:
            return here[:1]
        if d == top or top not in d.parents:
            return []
        d = d.parent


def find_documents(corpus: Path) -> list[Doc]:
    """Every document as its author compiles it: each `.tex` with `\\documentclass` or
    `\\begin{document}` that no other reads (its
    `\\input` files read through it, not again alone), each other `.tex` with a display that
    no main document reads (with the main file nearest above it as `--preamble`), and each
    `.md` with a display (with its source's macro files as `--preamble`)."""
    files = [p for p in sorted(corpus.rglob("*")) if p.is_file()]
    mains = []
    for p in files:
        if p.suffix.lower() == ".tex":
            text = strip_comments(p.read_text(encoding="utf-8", errors="replace"))
            # a main file: its class, or its document (a class given in an `\\input` header)
            if "\\documentclass" in text or "\\begin{document}" in text:
                mains.append(p)
    read_by_main: set[Path] = set()
    for m in mains:
        read_by_main |= included(m)
    # the main files that are papers of their own (not read by another, not a `subfiles`
    # chapter, which the audit reads with its own main file's preamble)
    whole = [m for m in mains if m not in read_by_main and not SUBFILES.search(strip_comments(
        m.read_text(encoding="utf-8", errors="replace")))]
    preambles: dict[str, list[Path]] = {}
    docs = []
    for p in files:
        if p.suffix.lower() not in (".tex", ".md"):
            continue
        rel = p.relative_to(corpus).as_posix()
        if "/" not in rel:  # SOURCES.md, README.md at the top: not a document of a source
            continue
        source = rel.split("/", 1)[0]
        if p in read_by_main:
            continue
        if p in mains or has_display(p):
            doc = Doc(path=p, rel=rel, source=source)
            if p.suffix.lower() == ".tex" and p not in mains:
                # a section no main file reads (a draft, a chapter left out): read with the
                # preamble of the main file nearest above it, as it was written to be
                doc.preambles = nearest_main(p, corpus / source, whole)
            if p.suffix.lower() == ".md":
                if source not in preambles:
                    preambles[source] = macro_files(corpus / source)
                doc.preambles = preambles[source]
            docs.append(doc)
    return docs


def units_required(binary: str) -> bool:
    """Whether `BIN audit --help` shows `--units` as a required argument (in the usage line,
    outside brackets)."""
    try:
        h = subprocess.run(
            [binary, "audit", "--help"], capture_output=True, text=True, timeout=60
        )
    except (OSError, subprocess.TimeoutExpired):
        return False
    usage = next((l for l in h.stdout.splitlines() if l.lower().startswith("usage")), "")
    outside = re.sub(r"\[[^\]]*\]", "", usage)
    return "--units" in outside


# ---------------------------------------------------------------- running


def audit(doc: Doc, binary: str, units: str | None, timeout: float) -> Doc:
    cmd = [binary, "audit", str(doc.path), "--format", "json"]
    for pre in doc.preambles:
        cmd += ["--preamble", str(pre)]
    if units:
        cmd += ["--units", units]
    t0 = time.monotonic()
    try:
        # its own process group, so that a timeout ends it and whatever it started
        p = subprocess.Popen(
            cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True
        )
    except OSError as e:
        doc.seconds = time.monotonic() - t0
        doc.rc = None
        doc.message = f"could not run: {e}"
        return doc
    try:
        out_b, err_b = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        p.communicate()
        doc.seconds = time.monotonic() - t0
        doc.rc = None
        doc.message = f"timed out after {timeout:g} s"
        return doc
    doc.seconds = time.monotonic() - t0
    doc.rc = p.returncode
    out = out_b.decode("utf-8", errors="replace")
    err = err_b.decode("utf-8", errors="replace")
    if p.returncode != 0:
        doc.message = first_line(err) or first_line(out) or "(no message)"
        return doc
    try:
        data = json.loads(out)
        doc.relations = list(data.get("relations", []))
    except (json.JSONDecodeError, AttributeError) as e:
        doc.message = f"exit 0 but the output is not the audit's JSON ({e})"
    return doc


def first_line(s: str) -> str:
    return next((l.strip() for l in s.splitlines() if l.strip()), "")


# ---------------------------------------------------------------- analysis


def construct_of(detail: str) -> str:
    """The construct an unreadable relation's detail names: the text after `column N: ` up to
    the last ` (at `, with `the command \\xyz` kept as the command's name alone."""
    d = detail
    if d.startswith("the LaTeX reader: "):
        d = d[len("the LaTeX reader: ") :]
    m = re.search(r"column \d+: ", d)
    if m:
        d = d[m.end() :]
        at = d.rfind(" (at `")
        if at >= 0:
            d = d[:at]
    d = d.strip()
    m = re.match(r"the command `(\\[^`]*)`", d)
    if m:
        return f"the command `{m.group(1)}`"
    # numbers quoted in the construct vary from row to row (`a multi-digit script ... (`12`)`)
    return re.sub(r"`\d+`", "`N`", d)


def short(s: str, n: int) -> str:
    s = re.sub(r"\s+", " ", s or "").strip()
    return s if len(s) <= n else s[: n - 1] + "…"


def code(s: str) -> str:
    """A Markdown code span safe inside a table cell."""
    s = s.replace("|", "\\|")
    fence = "``" if "`" in s else "`"
    pad = " " if s.startswith("`") or s.endswith("`") else ""
    return f"{fence}{pad}{s}{pad}{fence}"


def cell(s: str) -> str:
    return s.replace("|", "\\|").replace("\n", " ")


def pct(a: int, b: int) -> str:
    return f"{100.0 * a / b:.1f} %" if b else "–"


def fmt_rc(d: Doc) -> str:
    return "timeout" if d.rc is None and d.message.startswith("timed out") else (
        "—" if d.rc is None else str(d.rc)
    )


# ---------------------------------------------------------------- report


def summary_row(name: str, docs: list[Doc], extra: str = "") -> str:
    c: Counter = Counter()
    for d in docs:
        c += d.counts()
    n = sum(c.values())
    failed = sum(1 for d in docs if d.rc != 0)
    secs = sum(d.seconds for d in docs)
    read = n - c["unreadable"]
    return (
        f"| {name}{extra} | {len(docs)} | {n} | {pct(read, n)} | "
        + " | ".join(str(c[s]) for s in STATUSES)
        + f" | {failed} | {secs:.1f} |"
    )


SUMMARY_HEAD = (
    "| source | documents | relations | read | consistent | inconsistent | undetermined "
    "| unreadable | failed audits | time (s) |\n|---|---|---|---|---|---|---|---|---|---|"
)


def report(
    docs: list[Doc],
    sources: dict[str, dict],
    args: argparse.Namespace,
    units: str | None,
    wall: float,
) -> str:
    by_source: dict[str, list[Doc]] = defaultdict(list)
    for d in docs:
        by_source[d.source].append(d)
    L: list[str] = []
    L.append("# Corpus audit\n")
    L.append(
        f"`verify audit --format json` on every document of `{args.corpus}` holding a display "
        f"(binary `{args.bin}`, units {('`' + units + '`') if units else 'none'}, "
        f"{args.jobs} at once, {args.timeout:g} s each; wall time {wall:.1f} s). "
        "A relation is *read* unless its status is `unreadable`.\n"
    )

    # ---- summary per source and totals
    L.append("## Summary\n")
    L.append(SUMMARY_HEAD)
    total_rel = sum(len(d.relations) for d in docs)
    for s in sorted(by_source, key=str.lower):
        repo = sources.get(s, {}).get("repo", s)
        n = sum(len(d.relations) for d in by_source[s])
        L.append(summary_row(repo, by_source[s], f" ({pct(n, total_rel)} of relations)"))
    L.append(summary_row("**all**", docs))
    L.append("")

    # ---- per source
    L.append("## Sources\n")
    for s in sorted(by_source, key=str.lower):
        meta = sources.get(s, {})
        repo = meta.get("repo", s)
        L.append(f"### {repo}\n")
        if meta.get("commit"):
            L.append(f"Commit `{meta['commit']}`" + (f"; licence: {meta['licence']}" if meta.get("licence") else "") + ".")
        if meta.get("description"):
            L.append(meta["description"])
        L.append("")
        L.append(SUMMARY_HEAD.replace("| source |", "| |", 1))
        L.append(summary_row(repo, by_source[s]))
        L.append("")
        L.append(
            "| document | relations | read | cons. | incons. | undet. | unread. | exit | time (s) |\n"
            "|---|---|---|---|---|---|---|---|---|"
        )
        for d in by_source[s]:
            c = d.counts()
            n = len(d.relations)
            L.append(
                f"| {code(d.rel.split('/', 1)[1])} | {n} | {pct(n - c['unreadable'], n)} | "
                + " | ".join(str(c[x]) for x in STATUSES)
                + f" | {fmt_rc(d)} | {d.seconds:.2f} |"
            )
        failed = [d for d in by_source[s] if d.rc != 0 or d.message]
        if failed:
            L.append("\nFailed audits:\n")
            for d in failed:
                L.append(f"- `{d.rel}`: exit {fmt_rc(d)}: {cell(short(d.message, 200))}")
        L.append("")

    # ---- failed audits overall
    failed = [d for d in docs if d.rc != 0 or d.message]
    L.append("## Failed audits\n")
    if failed:
        msgs = Counter(d.message.replace(str(d.path), "DOC") for d in failed)
        L.append(f"{len(failed)} of {len(docs)} documents; by message:\n")
        for m, k in msgs.most_common():
            L.append(f"- {k} × {cell(short(m, 200))}")
    else:
        L.append("None.")
    L.append("")

    # ---- unread constructs
    unread = [(d, r) for d in docs for r in d.relations if r.get("status") == "unreadable"]
    groups: dict[str, list[tuple[Doc, dict]]] = defaultdict(list)
    for d, r in unread:
        groups[construct_of(r.get("detail", ""))].append((d, r))
    ranked = sorted(groups.items(), key=lambda kv: (-len(kv[1]), kv[0]))
    L.append("## Unread constructs\n")
    L.append(
        f"{len(unread)} unreadable relations of {total_rel} ({pct(len(unread), total_rel)}), "
        f"{len(ranked)} distinct constructs, ranked by count (documents: how many documents "
        "show it; the example is the first met).\n"
    )
    L.append("| # | construct | relations | share | documents | example document | example LaTeX |\n|---|---|---|---|---|---|---|")
    for i, (k, items) in enumerate(ranked, 1):
        d, r = items[0]
        ndocs = len({x.rel for x, _ in items})
        L.append(
            f"| {i} | {code(k)} | {len(items)} | {pct(len(items), len(unread))} | {ndocs} | "
            f"{code(d.rel)} | {code(short(r.get('latex', ''), 100))} |"
        )
    L.append("")

    # ---- inconsistent relations
    inc = [(d, r) for d in docs for r in d.relations if r.get("status") == "inconsistent"]
    L.append("## Inconsistent relations\n")
    L.append(
        f"{len(inc)} relations; each is a possible false alarm to check by hand.\n"
    )
    if inc:
        L.append("| document | number | LaTeX | detail |\n|---|---|---|---|")
        for d, r in inc:
            L.append(
                f"| {code(d.rel)} | {cell(str(r.get('number') or '—'))} | "
                f"{code(short(r.get('latex', ''), 100))} | {cell(short(r.get('detail', ''), 160))} |"
            )
    L.append("")
    return "\n".join(L)


def records(docs: list[Doc], sources: dict[str, dict]) -> dict:
    def repo(s: str) -> str:
        return sources.get(s, {}).get("repo", s)

    return {
        "documents": [
            {
                "source": repo(d.source),
                "doc": d.rel,
                "exit": d.rc,
                "seconds": round(d.seconds, 3),
                "message": d.message,
                "relations": len(d.relations),
            }
            for d in docs
        ],
        "relations": [
            {
                "source": repo(d.source),
                "doc": d.rel,
                "number": r.get("number"),
                "label": r.get("label"),
                "latex": r.get("latex", ""),
                "status": r.get("status"),
                "detail": r.get("detail", ""),
                "construct": construct_of(r.get("detail", ""))
                if r.get("status") == "unreadable"
                else None,
            }
            for d in docs
            for r in d.relations
        ],
    }


# ---------------------------------------------------------------- main


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("corpus", type=Path, help="the corpus folder (owner__repo/... below it)")
    ap.add_argument("--bin", default="target/release/verify", help="the verify binary")
    ap.add_argument("--sources", type=Path, help="SOURCES.md: repository and commit of each source")
    ap.add_argument("--out", type=Path, default=Path("reports/corpus.md"), help="the Markdown report")
    ap.add_argument("--json", type=Path, help="also dump the per-relation records here")
    ap.add_argument("--units", help="a units file for every audit (default: none, or a minimal one if the audit requires it)")
    ap.add_argument("--jobs", type=int, default=MAX_JOBS, help=f"audits at once (at most {MAX_JOBS})")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per document")
    args = ap.parse_args(argv)
    args.jobs = max(1, min(MAX_JOBS, args.jobs))

    if not args.corpus.is_dir():
        print(f"no corpus folder {args.corpus}", file=sys.stderr)
        return 2
    if not (os.path.isfile(args.bin) and os.access(args.bin, os.X_OK)):
        print(f"no executable binary {args.bin}", file=sys.stderr)
        return 2
    if args.sources is None and (args.corpus / "SOURCES.md").is_file():
        args.sources = args.corpus / "SOURCES.md"
    sources = read_sources(args.sources)
    docs = find_documents(args.corpus)
    if not docs:
        print(f"no document with a display under {args.corpus}", file=sys.stderr)
        return 2

    units = args.units
    tmp = None
    if units is None and units_required(args.bin):
        tmp = tempfile.TemporaryDirectory()
        units = os.path.join(tmp.name, "units.toml")
        Path(units).write_text('[symbols]\nt = "s"\n', encoding="utf-8")

    t0 = time.monotonic()
    done = 0
    with cf.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        futs = [ex.submit(audit, d, args.bin, units, args.timeout) for d in docs]
        for f in cf.as_completed(futs):
            done += 1
            d = f.result()
            print(
                f"[{done}/{len(docs)}] {d.rel}: {len(d.relations)} relations, exit {fmt_rc(d)}, {d.seconds:.2f} s",
                file=sys.stderr,
            )
    wall = time.monotonic() - t0

    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(report(docs, sources, args, args.units or (units and "minimal (t = s)"), wall), encoding="utf-8")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(records(docs, sources), ensure_ascii=False, indent=1) + "\n", encoding="utf-8")
    if tmp:
        tmp.cleanup()
    n = sum(len(d.relations) for d in docs)
    unread = sum(1 for d in docs for r in d.relations if r.get("status") == "unreadable")
    print(
        f"{len(docs)} documents, {n} relations, {pct(n - unread, n)} read; report {args.out}",
        file=sys.stderr,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The paper's numbers live in core/paper (issue 35, item 6; ctest architecture.paper_facts).

Outside core/paper, no code of core, app, ui or python writes b2 = 0.693, D = 6400, the 138-chain's 0.352 or the
literature's gamma = 1.57 as a number of its own, nor compares a period with 138: it reads
core/paper/PaperTable.hpp.  Comments and strings may quote the paper (a tooltip's example, a help text); the code
outside them may not.  Usage: check_paper_facts.py ROOT [EXTRA_FILE]  (EXTRA_FILE: one more file to scan, for the
test's own check that it fails on a planted copy).
"""
import pathlib
import re
import sys

FACTS = [
    (re.compile(r"(?<![0-9.])0\.693(?![0-9])"), "b2 = 0.693"),
    (re.compile(r"(?<![0-9.'])6'?400(?![0-9.])"), "D = 6400"),
    (re.compile(r"(?<![0-9.])0\.352(?![0-9])"), "x + sqrt K = 0.352"),
    (re.compile(r"(?<![0-9.])1\.57(?![0-9])"), "gamma = 1.57"),
    (re.compile(r"(?:==|!=|=|\()\s*138(?![0-9.])"), "the period 138"),
]
TOKENS = re.compile(r'//[^\n]*|/\*.*?\*/|R"([^(]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)


def code_only(text):
    """The text with comments and string/char literals blanked (newlines kept, so line numbers stay)."""
    def blank(m):
        s = m.group(0)
        if s.startswith("'") and len(s) <= 4:  # a char literal, or a digit separator: keep the separator's digits
            return s
        return re.sub(r"[^\n]", " ", s)
    return TOKENS.sub(blank, text)


def main():
    root = pathlib.Path(sys.argv[1])
    files = [p for d in ("core", "app", "ui", "python") for p in (root / d).rglob("*")
             if p.suffix in {".hpp", ".cpp", ".inl", ".h"} and "core/paper/" not in p.as_posix()]
    if len(sys.argv) > 2:
        files.append(pathlib.Path(sys.argv[2]))
    offenders = []
    for f in files:
        for n, line in enumerate(code_only(f.read_text(encoding="utf-8")).splitlines(), 1):
            for pattern, what in FACTS:
                if pattern.search(line):
                    offenders.append(f"{f}:{n}: {what}: {line.strip()}")
    if offenders:
        print("the paper's numbers written outside core/paper (read core/paper/PaperTable.hpp):")
        print("\n".join("  " + o for o in offenders))
        return 1
    print(f"{len(files)} sources: the paper's numbers only in core/paper")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""architecture.front_end_ranges (issue 35: front ends fill, call and format): no range check in app/, ui/ or python/.
A value's range is a rule of the request that holds it (core: the request's validationError(), core/limits' table and
its one wording); a front end parses text into a value, hands it to core and prints core's message.

A range check here is either
  * a message of one: "must lie in [", "must be in (", "must be >= …", "out of range", or
  * a throw whose condition (on its line or the line before) compares a value with a number: `if (v > 1000) throw …`,
    or with a name (issue 51: re-checks against names passed): `if (n > kMaxSeeds) throw …`, `v[1] <= replicas`,
    `*last > rule->max` (a relational operator with spaces around it, its right side a name, not a template's <…>).
Comments are skipped, and so is a line that says it is "a conversion, not a range" (a Python int bounded before it
becomes a C++ integer, with core's wording), and so are throws of std::out_of_range and std::logic_error (a program's own invariant, not a
user's value).  Usage: check_front_end_ranges.py ROOT [EXTRA_FILE]; EXTRA_FILE is scanned as well (the test's
planted copy, which must make it fail)."""
import pathlib, re, sys

root = pathlib.Path(sys.argv[1])
files = [p for d in ("app", "ui", "python") for p in sorted((root / d).rglob("*")) if p.suffix in (".cpp", ".hpp")]
files += [pathlib.Path(a) for a in sys.argv[2:]]

MESSAGE = re.compile(r"must (lie|be) in [\[(]|must be (a number |a whole number )?(>=|<=|>|<|≥|≤)|out of range")
THROW = re.compile(r"\bthrow\b|return fail\(|\bwhy = ")
NAMED = re.compile(r"[\w\])]\s+(<|>|<=|>=)\s+(?![0-9])[A-Za-z_*]")
COMPARE = re.compile(r"(?<![<>=!])(<|>|<=|>=)\s*-?[0-9][0-9'.eE+]*\b(?!\s*[>)]\s*\()|\b[0-9][0-9'.eE+]*\s*(<|>|<=|>=)(?![<>=])")


def code(line):
    """The line without a // comment, string literals (a message may quote a comparison) and counts of options or
    items (`cmd.count("--seed") > 0`, `states.size() > 1`: which were given, not a value's range)."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"\b(count|size)\([^()]*\)\s*(<|>|<=|>=)\s*[0-9]+", "", line)
    return line.split("//", 1)[0]


offenders = []
for path in files:
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    for i, line in enumerate(lines):
        stripped = line.lstrip()
        if stripped.startswith(("//", "*", "/*")):
            continue
        where = f"{path.relative_to(root) if path.is_relative_to(root) else path}:{i + 1}: {stripped}"
        if MESSAGE.search(line.split("//", 1)[0]):
            offenders.append(where)
        elif THROW.search(code(line)) and not re.search(r"std::(out_of_range|logic_error)", line):
            condition = code(line) if "if" in code(line) else (code(lines[i - 1]) if i > 0 else "")
            if "a conversion, not a range" in line + (lines[i - 1] if i > 0 else ""):
                continue
            if re.search(r"\bif\b", condition) and (COMPARE.search(condition) or NAMED.search(condition)):
                offenders.append(where)

if offenders:
    print("range checks in the front ends (a request's rule belongs in core, with core/limits' wording):")
    for o in offenders:
        print("  " + o)
    sys.exit(1)
print(f"{len(files)} front-end sources: no range check")

#!/usr/bin/env python3
"""architecture.shapes (issue 51, item 5): the house's rules checked by the shape of the code, not by a name.

  flags     core speaks in roles, not in a front end's options: no "--flag" in a string of a core .cpp (outside
            core/report and core/paper, whose reproduction commands are command lines by definition).  Each front
            end names a role its own way (core/tail/TailPlan.hpp's optionName; the CLI's flagOf, Python's keywords).
  json      one JSON field reader (core/io/Json.hpp): no function outside core/io that reads a primitive field of a
            JSON value, i.e. returns a number, a string, a bool or a JSON reference and takes a JSON value and a key.
  map loop  one loop over the map (core/map/OrbitIterator.hpp): no step of N or N⁻¹ (forwardStep, backwardStep,
            .forward(z), .backward(z)) outside core/map, except the vectorised kernels listed in KERNELS with the
            reason each keeps its own loop.
  range     one range wording, core/limits' ("<name> = <value> must lie in [lo, hi]", rangeError, realRangeError, …):
            no string outside core/limits that words a range itself ("must lie in [", "must be in (", "must be >= ",
            "must be 1 ... 16"), except the lines RANGES lists with the reason each keeps its words.

Usage: check_shapes.py ROOT [EXTRA_FILE ...]; each EXTRA_FILE is checked by every rule as if it were a core source
(the test's planted copy, which must make each rule fail)."""
import pathlib, re, sys

root = pathlib.Path(sys.argv[1])
extra = [pathlib.Path(a) for a in sys.argv[2:]]

# The loops over the map that stay where they are: hot, vectorised or lane-by-lane kernels whose step is the
# arithmetic contract itself (docs/design.md, "Arithmetic contract"), and one tool that traces both directions.
KERNELS = {
    "core/kernels": "the trapping kernels (scalar lanes, AVX2, AVX-512F, IFMA), bit-identical to FixedPointMap",
    "core/trapping": "the block kernel of a trapping run (N⁻¹ with the randomizing zone)",
    "core/measures/MeasureKernelScalar.cpp": "the indicator maps' lanes",
    "core/measures/RotationNumber.cpp": "the rotation number's sub-sequence w_k = z_kn (wraps accumulated, not stopped)",
    "core/theory/BoxExtension.cpp": "traces a segment of the small box in both directions of the large box's map",
}

# Ranges worded by hand that stay, each with its reason (a line of the file holding the text given).
RANGES = {
    ("core/markovtree/MarkovTree.cpp", "P_1 = w S(1) = "): "realRangeError's words with long doubles (w may pass 1e308)",
    ("core/trapping/TrappingParameters.cpp", "must lie in [0, 1)"): "Xr: closed below, open above (no such function)",
    ("core/atlas/AtlasExport.cpp", "must lie in [area_lower, area_upper]"): "bounds named by their fields",
    ("core/map/FixedPointMap.cpp", "must lie in [0, 2^52)"): "a unit coordinate given as text, open above",
    ("core/map/OrbitIterator.cpp", "must lie in [0, 2^52)"): "a unit coordinate, open above",
    ("core/view/Viewport.cpp", "grid units must lie in ["): "a long double size against 2^52",
}
RANGE = re.compile(r'"(\\.|[^"\\])*?(must (lie|be) in [\[(]|must be >= |must be [^"]*\d \.\.\. )')
FLAG = re.compile(r'"(\\.|[^"\\])*?(?<![A-Za-z0-9-])--[a-z][a-z0-9]*(-[a-z0-9]+)*')
JSON_HELPER = re.compile(
    r"^\s*(static\s+|inline\s+|\[\[nodiscard\]\]\s+)*(const\s+)?"
    r"(std::u?int\d+_t|double|float|bool|std::string|(nlohmann::)?(ordered_)?json&)\s+\w+\s*"
    r"\(const (nlohmann::)?(ordered_)?json&\s*\w*,\s*(const\s+)?(std::string|std::string_view|char\s*\*|char)")
MAP_STEP = re.compile(r"\b(forwardStep|backwardStep)\s*\(|\.(forward|backward)\(\s*z\s*\)")


def code(line):
    """The line without its // comment (a string holding // is kept: FLAG reads strings)."""
    stripped = line.lstrip()
    if stripped.startswith(("//", "*", "/*")):
        return ""
    return re.sub(r"\s//(?!.*\").*$", "", line)


def sources(folders, suffixes):
    for folder in folders:
        yield from (p for p in sorted((root / folder).rglob("*")) if p.suffix in suffixes)
    yield from extra


def rel(path):
    return str(path.relative_to(root)) if path.is_relative_to(root) else str(path)


offenders = {"flags": [], "json": [], "map loop": [], "range": []}
for path in sources(["core"], (".cpp",)):
    name = rel(path)
    if name.startswith(("core/report/", "core/paper/")):
        continue
    for i, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines()):
        if FLAG.search(code(line)):
            offenders["flags"].append(f"{name}:{i + 1}: {line.strip()}")
for path in sources(["core", "app", "ui", "python"], (".cpp", ".hpp", ".inl")):
    name = rel(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    for i, line in enumerate(lines):
        if not name.startswith("core/io/") and JSON_HELPER.search(code(line)):
            offenders["json"].append(f"{name}:{i + 1}: {line.strip()}")
        if (not name.startswith("core/map/") and not any(name.startswith(k) for k in KERNELS)
                and MAP_STEP.search(code(line))):
            offenders["map loop"].append(f"{name}:{i + 1}: {line.strip()}")
        if (not name.startswith("core/limits/") and RANGE.search(code(line))
                and not any(name == f and text in line for f, text in RANGES)):
            offenders["range"].append(f"{name}:{i + 1}: {line.strip()}")

failed = False
for rule, found in offenders.items():
    if found:
        failed = True
        print(f"{rule}:")
        for o in found:
            print("  " + o)
if failed:
    sys.exit(1)
print("no --flag in core's messages, no JSON field reader outside core/io, no loop over the map outside core/map "
      "and the kernels, no range worded outside core/limits")

#!/usr/bin/env python3
"""archipelago-cli run --orbits BEGIN:END and merge (issue #15, item 4): the parts of a run computed by separate
jobs merge into the file of the single run (the same histograms, subsets, longest segments and orbit states, in any
order of the parts); parts that do not fit (another spec, overlapping or missing orbits, different blocks done, an
edited or truncated file) are one ERROR line naming the file and the field, with nothing written; bad --orbits
ranges are refused before any work."""
import json, os, subprocess, tempfile, time

from clitest import check, cli, finish, interrupt, run, wait_for_file

tmp = tempfile.mkdtemp(prefix="archipelago-cli-merge-")
params = ["--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--q", "4", "--T", "20000", "--M", "10", "--subsets", "3",
          "--longestKept", "5", "--threads", "2", "--quiet"]
VOLATILE = ("elapsedSeconds", "checksum", "kernel", "program")  # timing and provenance; all the rest must be equal


def content(path):
    d = json.load(open(path))
    return {k: v for k, v in d.items() if k not in VOLATILE}


def p(name):
    return os.path.join(tmp, name)


def one_error(r, *words):
    lines = r.stderr.strip().splitlines()
    return (r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ")
            and all(w in lines[0] for w in words))


whole = run("run", *params, "--out", p("whole.json"))
check(whole.returncode == 0, "the single run: " + whole.stderr.strip()[-200:])
ranges = [(0, 3), (3, 4), (4, 10)]
for b, e in ranges:
    r = run("run", *params, "--orbits", f"{b}:{e}", "--out", p(f"part{b}.json"))
    check(r.returncode == 0, f"run --orbits {b}:{e}: " + r.stderr.strip()[-200:])
part = json.load(open(p("part3.json")))
check(part["orbitBegin"] == 3 and part["orbitEnd"] == 4 and len(part["orbits"]) == 1,
      "run --orbits 3:4 writes orbits [3, 4) only")
whole_orbits = json.load(open(p("whole.json")))["orbits"]
check(part["orbits"][0] == whole_orbits[3], "orbit 3 of the part is orbit 3 of the single run")

r = run("merge", p("part4.json"), p("part0.json"), p("part3.json"), "--out", p("merged.json"))
check(r.returncode == 0, "merge of three parts in any order: " + r.stderr.strip())
check(content(p("merged.json")) == content(p("whole.json")), "merged parts equal the single run (all but timing)")
d = json.load(open(p("merged.json")))
check(d["orbitBegin"] == 0 and d["orbitEnd"] == 10 and d["finished"], "the merged file covers [0, M), finished")
r = run("stats", p("merged.json"))
check(r.returncode == 0, "stats reads the merged file (its checksum is valid)")

# --- parts that do not fit: one ERROR naming the file and the field, nothing written -----------------------------
for name, extra in [("otherT", ["--T", "20001", "--orbits", "3:4"]), ("otherseed", ["--seed", "8", "--orbits", "3:4"]),
                    ("overlap", ["--orbits", "2:4"]), ("short", ["--orbits", "0:2"])]:
    base = [x if x != "20000" else "20001" for x in params] if name == "otherT" else params
    extra = extra[2:] if name == "otherT" else extra
    check(run("run", *base, *extra, "--out", p(name + ".json")).returncode == 0, "part " + name)
cases = [
    ("another seed", [p("part0.json"), p("otherseed.json"), p("part4.json")], ["otherseed.json", "'seed'"]),
    ("another T", [p("part0.json"), p("otherT.json"), p("part4.json")], ["otherT.json", "'T'"]),
    ("overlapping ranges", [p("part0.json"), p("overlap.json"), p("part4.json")], ["overlap.json", "'orbitBegin'", "overlap"]),
    ("a gap", [p("short.json"), p("part3.json"), p("part4.json")], ["part3.json", "'orbitBegin'", "[2, 3)"]),
    ("a missing first range", [p("part3.json"), p("part4.json")], ["part3.json", "'orbitBegin'", "[0, 3)"]),
    ("a missing last range", [p("part0.json"), p("part3.json")], ["part3.json", "'orbitEnd'", "[4, 10)"]),
    # Issue 36, class 3: refused by the one output-path policy, before the parts are read.
    ("the same part twice", [p("part0.json"), p("part0.json"), p("part3.json"), p("part4.json")],
     ["part0.json", "give each input once"]),
]
for what, files, words in cases:
    out = p("bad.json")
    r = run("merge", *files, "--out", out)
    check(one_error(r, *words) and not os.path.exists(out), f"{what}: one ERROR naming {words}, nothing written: "
          + r.stderr.strip())

# blocksDone: parts of one (long) spec, each interrupted (SIGINT writes its checkpoint) after a different time
slow = [x if x != "20000" else "2000000000" for x in params]
for (b, e), wait in [((0, 3), 0), ((3, 4), 0.4), ((4, 10), 0.8)]:
    proc = subprocess.Popen([cli, "run", *slow, "--orbits", f"{b}:{e}", "--max-chunk", "16",
                             "--checkpoint-interval", "0", "--out", p(f"slowo{b}.json"), "--checkpoint", p(f"slow{b}.json")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for_file(p(f"slow{b}.json"), proc)
    time.sleep(wait)
    interrupt(proc)
done = {f: json.load(open(p(f)))["blocksDone"] for f in ("slow0.json", "slow3.json", "slow4.json")}
check(len(set(done.values())) > 1, f"the interrupted parts stopped at different blocks {done}")
r = run("merge", p("slow0.json"), p("slow3.json"), p("slow4.json"), "--out", p("bad.json"))
check(one_error(r, "'blocksDone'") and not os.path.exists(p("bad.json")),
      f"parts at different blocks done: one ERROR naming 'blocksDone': " + r.stderr.strip())

# an edited part (checksum) and a truncated part: the file named, nothing written
text = open(p("part3.json")).read()
open(p("edited.json"), "w").write(text.replace('"blocksDone": 20000', '"blocksDone": 19999'))
open(p("truncated.json"), "w").write(text[: len(text) // 2])
for name, word in [("edited.json", "modified"), ("truncated.json", "truncated.json")]:
    r = run("merge", p("part0.json"), p(name), p("part4.json"), "--out", p("bad.json"))
    check(one_error(r, name, word) and not os.path.exists(p("bad.json")),
          f"{name}: one ERROR naming the file, nothing written: " + r.stderr.strip())

# --out is one of the parts: refused, the part intact
before = open(p("part0.json")).read()
r = run("merge", p("part0.json"), p("part3.json"), p("part4.json"), "--out", p("part0.json"))
check(one_error(r, "part0.json") and open(p("part0.json")).read() == before, "--out a part: refused, part intact")

# --- bad --orbits: refused before any work --------------------------------------------------------------------
for bad in ["5:5", "6:3", "0:11", "a:3", "3", "1:2:3", "-1:3", "nan:3", "0:1e400", ":"]:
    out = p("never.json")
    r = run("run", *params, "--orbits", bad, "--out", out)
    # core's rule and words (issue 35): "orbits [5, 5) must satisfy …", as Python's start_range; a parse error
    # names the option ("--orbits '3' must be …")
    check(one_error(r, "orbits") and not os.path.exists(out), f"--orbits {bad!r}: one ERROR, nothing written: "
          + r.stderr.strip())
r = run("run", "--resume", p("slow0.json"), "--orbits", "0:3", "--out", p("never.json"))
check(one_error(r, "--orbits") and not os.path.exists(p("never.json")), "--resume with --orbits is refused")
finish()

#!/usr/bin/env python3
"""Issue 36, the newest surfaces tried as a hostile user would: classes 4 (work without bound), 6 (accepted
nonsense) and 7 (messages) of archipelago-cli, each case classified as in the other harnesses (hostile.py: clean
error, valid, crash, hang, silent wrong) and the table printed; the test fails unless every crash, hang and
silent-wrong cell is 0, and each case's message is checked.

  work without bound   manifold --spacing 1e-17 … 1e-300 recursed for hours (ManifoldCurve's refinement), 1e-16
                       ran to --max-points for 13 s, --max-points 1e8 with --length 1e6 took 6 GiB unchecked: each is
                       refused before work, with the bound it exceeds
  accepted nonsense    rotation --kernel bogus for one orbit; tail --slice ''; ARCHIPELAGO_KERNEL with a control
                       character quoted raw (two lines); a re-signed tail file whose replica has survivors and no
                       walkers (resumed, and its P was wrong)"""
import hashlib, json, os, resource, shutil, tempfile, time

from clitest import check, finish
from hostile import classify, invoke, print_table, problems, record

tmp = tempfile.mkdtemp(prefix="archipelago-issue36-")
under_asan = "ASAN_OPTIONS" in os.environ
# A hang is no answer within this (every case here is refused before work, in well under a second; ASan: 3x).
HANG = 180 if under_asan else 60


def case(category, name, args, words, env=None, preexec_fn=None):
    """A case that must be one ERROR line containing `words`, before any work (a refusal after 20 s is not)."""
    start = time.monotonic()
    rc, _, err = invoke(args, timeout=HANG, env=env, preexec_fn=preexec_fn)
    seconds = time.monotonic() - start
    outcome = classify(rc, err, True, lambda: True)
    if outcome == "clean error" and (words not in err or seconds > 20):
        outcome = "silent wrong"  # another message, or refused only after the work
    record(category, name, outcome, f"{err.strip()[:200]} ({seconds:.1f} s)")


def with_checksum(d):
    """A tail file's document `d` signed again (TailFile.cpp: SHA-256 of the document without it, as dumped)."""
    d = dict(d)
    d.pop("checksum", None)
    text = json.dumps(d, indent=1, sort_keys=True, ensure_ascii=False)
    d["checksum"] = "sha256:" + hashlib.sha256(text.encode()).hexdigest()
    return d


started = time.monotonic()

# ------------------------------------------------------------------------------------------ work without bound
for spacing in ["1e-17", "1e-16", "1e-300"]:
    case("work without bound", f"manifold --length 1 --spacing {spacing}",
         ["manifold", "--length", "1", "--spacing", spacing], f"spacing = {spacing} must lie in [1e-14, 1]")
if under_asan:
    print("skipped under ASan: manifold --max-points 1e8 (an address-space limit cannot hold ASan's shadow memory)")
else:
    def four_gib():
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))

    # 10^8 points of the branch need ~12 GB: on a machine (here, a 4 GiB address space) that has less, refused.
    case("work without bound", "manifold --max-points 1e8 --spacing 1e-9 --length 1e6 (4 GiB address space)",
         ["manifold", "--max-points", "1e8", "--spacing", "1e-9", "--length", "1e6", "--out",
          os.path.join(tmp, "m.csv")], "needs about", preexec_fn=four_gib)
    check(not os.path.exists(os.path.join(tmp, "m.csv")), "the refused manifold wrote nothing")

# ------------------------------------------------------------------------------------------- accepted nonsense
case("accepted nonsense", "rotation --kernel bogus (one orbit)",
     ["rotation", "--x", "-0.3", "--y", "0", "--iterations", "1000", "--kernel", "bogus"], "unknown kernel 'bogus'")
env = dict(os.environ, ARCHIPELAGO_KERNEL="scalar\n")
case("accepted nonsense", "ARCHIPELAGO_KERNEL='scalar\\n' (quoted on one line)",
     ["rotation", "--x", "-0.3", "--y", "0", "--iterations", "1000"], "unknown kernel 'scalar\\n'", env=env)
tail_settings = ["--first", "150", "--t-max", "400", "--population", "8", "--replicas", "2", "--min-ancestors", "1"]
case("accepted nonsense", "tail --slice ''", ["tail", *tail_settings, "--slice", "", "--out",
                                              os.path.join(tmp, "slice.json"), "--quiet"], "--slice '' must be")

# A re-signed tail file whose replica 0 has survivors and no walkers: refused on load (its invariants), not resumed.
full = os.path.join(tmp, "tail.json")
rc, _, err = invoke(["tail", *tail_settings, "--out", full, "--quiet"], timeout=HANG)
check(rc == 0, f"a small tail file ({err.strip()})")
d = json.load(open(full))
replica = d["state"]["replicas"][0]
check(replica["levels"][-1][0] > 0 and len(replica["walkers"]) > 0, "its replica 0 set out for the last level")
replica["walkers"] = []
edited = os.path.join(tmp, "no-walkers.json")
json.dump(with_checksum(d), open(edited, "w"), indent=1, sort_keys=True, ensure_ascii=False)
control = os.path.join(tmp, "signed-again.json")  # the same file signed again unedited: read as it was
json.dump(with_checksum(json.load(open(full))), open(control, "w"), indent=1, sort_keys=True, ensure_ascii=False)
rc, out, err = invoke(["merge", control, "--out", os.path.join(tmp, "merged.json")], timeout=HANG)
check(rc == 0, f"the tail file signed again unedited is read ({err.strip()})")
for reader in (["tail", "--resume", edited, "--out", os.path.join(tmp, "resumed.json"), "--quiet"],
               ["merge", edited, "--out", os.path.join(tmp, "merged2.json")]):
    case("accepted nonsense", f"{reader[0]} of a re-signed tail file with survivors and no walkers", reader,
         "replica 0: holds 0 walkers where its counts give")

print_table(started)
if not problems:
    shutil.rmtree(tmp, ignore_errors=True)
finish()

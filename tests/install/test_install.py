#!/usr/bin/env python3
"""`cmake --install` into a temporary prefix (issue 31), and what it installed used from there: every program in
bin/ answers --version and --help (the GUI with QT_QPA_PLATFORM=offscreen, and without any display), the CLI runs
a small run, no installed program depends on the build tree; the desktop entry, icon and AppStream metainfo in
share/ agree with each other and with bin/ (and pass desktop-file-validate and appstreamcli validate where those
are installed); a manual page per program (help2man); the Python package imports from PYTHONPATH=PREFIX/<its
folder>, not from the build tree, and runs; nothing is installed outside bin/, share/, that folder and
lib/archipelago/ (the private Qwt). Issue 36 class 9: the run paths are relative to the program ($ORIGIN), and as
root the programs installed (and the build tree's GUI) start as another user, nobody (they failed to load a Qwt
in the building user's ~/.cache).
Arguments: cmake, the build folder, the programs expected (;-separated), the manual pages expected, the Python
package's folder relative to the prefix and the interpreter to import it with (both empty without the module)."""
import json, os, re, shutil, subprocess, sys, tempfile
import xml.etree.ElementTree as ET

cmake, build, programs, pages, pydir, python = sys.argv[1:7]
programs, pages = [p for p in programs.split(";") if p], [p for p in pages.split(";") if p]
failures = 0


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    failures += 0 if cond else 1


prefix = tempfile.mkdtemp(prefix="archipelago-install-")
r = subprocess.run([cmake, "--install", build, "--prefix", prefix], capture_output=True, text=True)
check(r.returncode == 0, f"cmake --install {build} --prefix {prefix} " + r.stderr.strip()[-500:])
files = sorted(os.path.relpath(os.path.join(d, f), prefix) for d, _, fs in os.walk(prefix) for f in fs)
print("     installed: " + ", ".join(files))
allowed = ("bin/", "share/", "lib/archipelago/") + ((pydir.rstrip("/") + "/",) if pydir else ())
check(all(f.startswith(allowed) for f in files), f"everything under {', '.join(allowed)} "
      f"(not: {[f for f in files if not f.startswith(allowed)]})")

# --- the programs ------------------------------------------------------------------------------------------------
no_display = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
version = re.search(r"project\(Archipelago VERSION ([0-9.]+)", open(os.path.join(
    os.path.dirname(__file__), "..", "..", "CMakeLists.txt")).read()).group(1)
for name in programs:
    exe = os.path.join(prefix, "bin", name)
    if not os.access(exe, os.X_OK):
        check(False, f"bin/{name} installed")
        continue
    runs = [("--version", dict(no_display, QT_QPA_PLATFORM="offscreen")), ("--version", no_display),
            ("--help", no_display)]
    for option, env in runs:
        r = subprocess.run([exe, option], capture_output=True, text=True, env=env, cwd=prefix, timeout=60)
        out = r.stdout + r.stderr
        expected = version if option == "--version" else "Usage:"
        check(r.returncode == 0 and expected in out,
              f"bin/{name} {option}{' (QT_QPA_PLATFORM=offscreen)' if 'QT_QPA_PLATFORM' in env else ' (no display)'}"
              f": {out.strip().splitlines()[0] if out.strip() else '(nothing)'}")
    dynamic = subprocess.run(["readelf", "-d", exe], capture_output=True, text=True).stdout
    paths = re.findall(r"\((?:RPATH|RUNPATH)\)\s+Library r(?:un)?path: \[(.*)\]", dynamic)
    check(not any(os.path.realpath(build) in os.path.realpath(p) for p in ":".join(paths).split(":")
                  if p and not p.startswith("$ORIGIN")),
          f"bin/{name}: no run path into the build tree ({paths or 'none'})")
    # Issue 36 class 9: a run path to an absolute folder (the building user's ~/.cache) fails for other users
    # and other prefixes; a private library is found relative to the program.
    check(all(p.startswith("$ORIGIN") for p in ":".join(paths).split(":") if p),
          f"bin/{name}: every run path relative to the program ({paths or 'none'})")
    needed = re.findall(r"\(NEEDED\)\s+Shared library: \[(libqwt[^]]*)\]", dynamic)
    private = os.path.join(prefix, "lib/archipelago")
    if needed and os.path.isdir(private):
        check(all(os.path.exists(os.path.join(private, n)) for n in needed) and
              any(p == "$ORIGIN/../lib/archipelago" for p in ":".join(paths).split(":")),
              f"bin/{name}: its Qwt {needed} installed in lib/archipelago/, and found there")
cli = os.path.join(prefix, "bin", "archipelago-cli")
r = subprocess.run([cli, "run", "--K", "0.1", "--M", "16", "--q", "4", "--T", "1000", "--quiet", "--out",
                    os.path.join(prefix, "run.json")], capture_output=True, text=True, timeout=60)
check(r.returncode == 0 and json.load(open(os.path.join(prefix, "run.json")))["finished"],
      "bin/archipelago-cli run: a small run finished " + r.stderr.strip())

# --- as another user (issue 36 class 9) --------------------------------------------------------------------------
def readable_by_others(path):
    """Whether every folder above `path` can be traversed, and `path` read, by a user who is not its owner."""
    path = os.path.realpath(path)
    parts = [path] + [os.path.dirname(path)]
    while parts[-1] != "/":
        parts.append(os.path.dirname(parts[-1]))
    return all(os.stat(p).st_mode & 0o005 == 0o005 for p in parts[1:]) and os.stat(path).st_mode & 0o004


runuser = shutil.which("runuser")
if os.geteuid() == 0 and runuser:
    os.chmod(prefix, 0o755)  # mkdtemp makes it 0700
    as_nobody = dict(no_display, QT_QPA_PLATFORM="offscreen", HOME="/nonexistent")
    targets = [(f"bin/{n}", os.path.join(prefix, "bin", n)) for n in programs]
    gui = os.path.join(build, "app/gui/archipelago")
    if os.path.exists(gui):
        targets.append(("the build tree's app/gui/archipelago", gui))
    for label, exe in targets:
        if not readable_by_others(exe):
            print(f"     not run as nobody: {exe} cannot be reached by other users (a folder above it is private)")
            continue
        r = subprocess.run([runuser, "-u", "nobody", "--", exe, "--version"], capture_output=True, text=True,
                           env=as_nobody, cwd="/", timeout=60)
        out = (r.stdout + r.stderr).strip()
        check(r.returncode == 0 and version in out,
              f"{label} --version as the user nobody: {out.splitlines()[0] if out else '(nothing)'}")
else:
    print("     not run as another user: needs root and runuser (CI runs as root)")

# --- share/: the desktop entry, its icon, the metainfo -----------------------------------------------------------
if "archipelago" in programs:
    desktop = os.path.join(prefix, "share/applications/archipelago.desktop")
    entry = dict(re.findall(r"^(\w+)=(.*)$", open(desktop).read(), re.M)) if os.path.exists(desktop) else {}
    check(entry.get("Exec", "").split()[:1] == ["archipelago"] and entry.get("Icon") == "archipelago",
          f"share/applications/archipelago.desktop runs bin/archipelago, icon 'archipelago' ({entry.get('Exec')})")
    check(os.path.exists(os.path.join(prefix, "share/icons/hicolor/scalable/apps/archipelago.svg")),
          "share/icons/hicolor/scalable/apps/archipelago.svg")
    metainfo = os.path.join(prefix, "share/metainfo/archipelago.metainfo.xml")
    root = ET.parse(metainfo).getroot() if os.path.exists(metainfo) else None
    if root is None:
        check(False, "share/metainfo/archipelago.metainfo.xml")
    else:
        launch = root.findtext("launchable")
        binaries = [b.text for b in root.iter("binary")]
        check(root.findtext("id") == "archipelago" and launch == "archipelago.desktop" and binaries and
              all(os.path.exists(os.path.join(prefix, "bin", b)) for b in binaries),
              f"share/metainfo/archipelago.metainfo.xml: launches {launch}, provides {binaries}, all installed")
    tool = shutil.which("desktop-file-validate")
    if tool:
        r = subprocess.run([tool, desktop], capture_output=True, text=True)
        errors = [l for l in (r.stdout + r.stderr).splitlines() if "error:" in l]
        check(r.returncode == 0 and not errors, "desktop-file-validate: no error " + (r.stdout + r.stderr).strip())
    else:
        print("     not validated: no desktop-file-validate (Debian desktop-file-utils)")
    tool = shutil.which("appstreamcli")
    if tool:
        r = subprocess.run([tool, "validate", "--no-net", metainfo], capture_output=True, text=True)
        # The only issue allowed: the id is not a reverse domain name (the project has none; see the file).
        issues = [l for l in r.stdout.splitlines() if re.match(r"[EWI]: ", l)]
        check(all("cid-desktopapp-is-not-rdns" in l for l in issues),
              f"appstreamcli validate: no issue but the id's ({issues or 'none'})")
    else:
        print("     not validated: no appstreamcli (Debian appstream)")

# --- manual pages -------------------------------------------------------------------------------------------------
for page in pages:
    path = os.path.join(prefix, "share/man/man1", page)
    text = open(path, errors="replace").read() if os.path.exists(path) else ""
    name = page[:-2]
    named = re.search(r"\.SH NAME\n" + re.escape(name) + r" \\- ", text) is not None
    ok = text.startswith(".\\\" DO NOT MODIFY") and ".TH" in text and named and os.path.realpath(build) not in text
    if name == "archipelago-cli":
        commands = re.findall(r"^  ([a-z][a-z0-9-]*) ", subprocess.run([cli, "--help"], capture_output=True,
                                                                       text=True).stdout, re.M)
        ok = ok and commands and all(f".SS {c}\n" in text for c in commands)
        name += f" (a subsection per command: {', '.join(commands)})"
    check(ok, f"share/man/man1/{page}: help2man's page of {name}")
    if ok and shutil.which("man"):
        r = subprocess.run(["man", "-l", path], capture_output=True, text=True,
                           env=dict(os.environ, MANWIDTH="100", LC_ALL="C"))
        check(r.returncode == 0 and "--help" in r.stdout, f"man -l {page} renders it")
if not pages:
    print("     no manual pages expected (no help2man when configured)")

# --- the Python package -------------------------------------------------------------------------------------------
if pydir:
    site = os.path.join(prefix, pydir)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = site
    code = ("import archipelago as ap, json; r = ap.start(K=0.1, M=16, q=4, T=1000); r.advance(threads=1); "
            "print(json.dumps({'file': ap.__file__, 'version': ap.__version__, 'finished': r.finished}))")
    r = subprocess.run([python, "-s", "-c", code], capture_output=True, text=True, env=env, cwd=prefix, timeout=60)
    got = json.loads(r.stdout) if r.returncode == 0 else {}
    where = os.path.realpath(got.get("file", "/"))
    check(where.startswith(os.path.realpath(site) + os.sep),
          f"PYTHONPATH={site}: import archipelago from there ({got.get('file')}) " + r.stderr.strip()[-300:])
    check(got.get("version") == version and got.get("finished") is True, f"and it runs ({got})")
else:
    print("     no Python package expected (not built)")

if failures:
    print(f"the prefix is kept: {prefix}")
else:
    shutil.rmtree(prefix)
print(f"{failures} failed" if failures else "all passed")
sys.exit(1 if failures else 0)

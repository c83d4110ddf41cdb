#!/usr/bin/env python3
"""The Debian package, installed as a user installs software (issue 42; label package, run by .ci/run once, not by
the default test run: it installs into the system, so it needs root).  From the configured and built tree:
  1. cpack builds archipelago_<version>_<arch>.deb (cmake/ArchipelagoPackage.cmake); its control fields (Depends
     from dpkg-shlibdeps) and file list are printed, and the list holds what it must;
  2. apt-get install ./archipelago_*.deb;
  3. from PATH: every program's --version, a small archipelago-cli run + stats, import archipelago in python3 from
     another folder (found in /usr/lib/python3/dist-packages, no PYTHONPATH), the GUI offscreen with --screenshot,
     man archipelago-cli; desktop-file-validate and appstreamcli validate on the installed files;
  4. lintian on the .deb: no error (its warnings and notes are printed);
  5. apt-get remove --purge archipelago: nothing of the package's file list is left.
Arguments: cpack, the build folder, the programs expected (;-separated), the manual pages expected."""
import json, os, re, shutil, subprocess, sys, tempfile, time

cpack, build, programs, pages = sys.argv[1:5]
programs, pages = [p for p in programs.split(";") if p], [p for p in pages.split(";") if p]
version = re.search(r"project\(Archipelago VERSION ([0-9.]+)", open(os.path.join(
    os.path.dirname(__file__), "..", "..", "CMakeLists.txt")).read()).group(1)
failures = 0
started = time.monotonic()


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    failures += 0 if cond else 1


def sh(*args, **kw):
    kw.setdefault("capture_output", True)
    kw.setdefault("text", True)
    kw.setdefault("timeout", 900)
    return subprocess.run(list(args), **kw)


def note(what):
    print(f"     [{time.monotonic() - started:5.0f} s] {what}", flush=True)


class Stop(Exception):
    """A step failed that the next ones need."""


if os.geteuid() != 0:
    print("FAIL the package test installs into the system: run it as root (CI does)")
    sys.exit(1)

apt_env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
work = tempfile.mkdtemp(prefix="archipelago-package-")
os.chmod(work, 0o755)  # apt's download user (_apt) reads the .deb from here
installed = False
try:
    # --- 1. the package -------------------------------------------------------------------------------------------
    r = sh(cpack, "--config", os.path.join(build, "CPackConfig.cmake"), "-B", work)
    debs = [f for f in os.listdir(work) if re.fullmatch(rf"archipelago_{re.escape(version)}_[a-z0-9]+\.deb", f)]
    check(r.returncode == 0 and len(debs) == 1, f"cpack: {debs} " + (r.stdout + r.stderr).strip()[-800:])
    if not debs:
        raise Stop
    deb = os.path.join(work, debs[0])
    note(f"built {deb} ({os.path.getsize(deb) // 1024} KiB)")
    fields = sh("dpkg-deb", "--field", deb).stdout
    print("\n".join("     | " + l for l in fields.splitlines()))
    control = dict(re.findall(r"^([A-Za-z-]+): (.*)$", fields, re.M))
    depends = [d.strip() for d in control.get("Depends", "").split(",") if d.strip()]
    check(control.get("Package") == "archipelago" and control.get("Version") == version,
          f"Package archipelago, Version {version} (project() in CMakeLists.txt)")
    check(any(d.startswith("libc6") for d in depends) and any(d.startswith("libstdc++6") for d in depends),
          "Depends from dpkg-shlibdeps (libc6, libstdc++6, …)")
    if "archipelago" in programs:
        check(any(re.match(r"libqt[56]widgets", d) for d in depends), "Depends names the Qt that the GUI links")
    listing = sh("dpkg-deb", "--contents", deb).stdout
    entries = [l.split()[-1] if " -> " not in l else l.split(" -> ")[0].split()[-1] for l in listing.splitlines()]
    files = sorted(e[1:] for e in entries if not e.endswith("/"))  # ./usr/bin/x -> /usr/bin/x
    print("     files: " + ", ".join(files))
    expected = [f"/usr/bin/{p}" for p in programs] + [f"/usr/share/man/man1/{p}.gz" for p in pages] + [
        "/usr/share/doc/archipelago/copyright", "/usr/share/doc/archipelago/changelog.gz"]
    if "archipelago" in programs:
        expected += ["/usr/share/applications/archipelago.desktop", "/usr/share/metainfo/archipelago.metainfo.xml",
                     "/usr/share/icons/hicolor/scalable/apps/archipelago.svg"]
    missing = [f for f in expected if f not in files]
    check(not missing, f"the package holds the programs, manual pages, desktop entry, icon, metainfo, copyright "
          f"(missing: {missing})")
    python_files = [f for f in files if "/archipelago/" in f and "python" in f]
    check(not python_files or all(f.startswith("/usr/lib/python3/dist-packages/archipelago/") for f in python_files),
          f"the Python module in /usr/lib/python3/dist-packages ({python_files})")
    qwt = [f for f in files if "libqwt" in f]
    check(all(f.startswith("/usr/lib/archipelago/") for f in qwt), f"a private Qwt only in /usr/lib/archipelago ({qwt})")
    check(all(f.startswith(("/usr/bin/", "/usr/share/", "/usr/lib/archipelago/", "/usr/lib/python3/dist-packages/"))
              for f in files), "nothing outside /usr/bin, /usr/share, /usr/lib/archipelago and Python's folder")

    # --- 2. installed as a user installs it -----------------------------------------------------------------------
    r = sh("apt-get", "-o", "DPkg::Lock::Timeout=600", "install", "-y", "./" + debs[0], cwd=work, env=apt_env)
    installed = r.returncode == 0
    check(installed, "apt-get install -y ./" + debs[0] + " " + (r.stdout + r.stderr).strip()[-1500:])
    note("installed")
    if not installed:
        raise Stop

    # --- 3. from PATH ---------------------------------------------------------------------------------------------
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LD_LIBRARY_PATH", "DISPLAY",
                                                            "WAYLAND_DISPLAY")}
    env.update(PATH="/usr/bin:/bin", QT_QPA_PLATFORM="offscreen")
    for p in programs:
        where = shutil.which(p, path=env["PATH"])
        r = sh(p, "--version", env=env, cwd=work, timeout=120) if where else None
        out = (r.stdout + r.stderr).strip() if r else ""
        check(where == f"/usr/bin/{p}" and r.returncode == 0 and version in out, f"{p} --version from PATH: {out}")
    r = sh("archipelago-cli", "run", "--K", "0.1", "--M", "16", "--q", "4", "--T", "2000", "--quiet", "--out", "run.json",
           env=env, cwd=work, timeout=300)
    check(r.returncode == 0 and json.load(open(os.path.join(work, "run.json")))["finished"],
          "archipelago-cli run: a small run " + r.stderr.strip())
    r = sh("archipelago-cli", "stats", "run.json", env=env, cwd=work, timeout=300)
    check(r.returncode == 0 and "D" in r.stdout, "archipelago-cli stats run.json " + r.stderr.strip()[-300:])
    # Issue 54, finding 7: a command-line run by a user without a login session (nobody: no XDG_RUNTIME_DIR) once
    # printed Qt's "QStandardPaths: XDG_RUNTIME_DIR not set" on stderr.
    runuser = shutil.which("runuser")  # in /usr/sbin, outside the PATH the installed programs run with
    if "archipelago-reproduce" in programs and os.geteuid() == 0 and runuser:
        quiet = tempfile.mkdtemp(dir=work)
        os.chmod(quiet, 0o777)
        r = sh(runuser, "-u", "nobody", "--", "env", "-u", "XDG_RUNTIME_DIR", "archipelago-reproduce", "--only", "tmax",
               os.path.join(quiet, "report"), env=env, cwd=quiet, timeout=300)
        check(r.returncode == 0 and r.stderr == "",
              f"archipelago-reproduce --only tmax as nobody without XDG_RUNTIME_DIR: nothing on stderr ({r.stderr.strip()!r})")
    code = ("import archipelago as ap, json; r = ap.start(K=0.1, M=16, q=4, T=1000); r.advance(threads=1); "
            "print(json.dumps({'file': ap.__file__, 'version': ap.__version__, 'finished': r.finished}))")
    if any("python3" in f for f in files):
        r = sh("python3", "-c", code, env=dict(env, PYTHONDONTWRITEBYTECODE="1"), cwd=work, timeout=300)
        got = json.loads(r.stdout) if r.returncode == 0 else {}
        check(got.get("file", "").startswith("/usr/lib/python3/dist-packages/archipelago/") and
              got.get("version") == version and got.get("finished") is True,
              f"python3 -c 'import archipelago' from {work}: {got} " + r.stderr.strip()[-300:])
        # Imported by root without PYTHONDONTWRITEBYTECODE: Python writes __pycache__ into the package's folder,
        # which the package's prerm removes (step 5 checks that nothing is left).
        r = sh("python3", "-c", "import archipelago", env=env, cwd=work, timeout=300)
        check(r.returncode == 0, "import archipelago as root, bytecode written " + r.stderr.strip()[-300:])
    if "archipelago" in programs:
        shot = os.path.join(work, "screenshot.png")
        r = sh("archipelago", "--screenshot", shot, "--after", "1", env=env, cwd=work, timeout=600)
        ok = os.path.exists(shot) and open(shot, "rb").read(8) == b"\x89PNG\r\n\x1a\n"
        check(r.returncode == 0 and ok, f"archipelago --screenshot offscreen: {r.stdout.strip()} {r.stderr.strip()[-300:]}")
        r = sh("desktop-file-validate", "/usr/share/applications/archipelago.desktop")
        check(r.returncode == 0 and "error" not in (r.stdout + r.stderr).lower(),
              "desktop-file-validate /usr/share/applications/archipelago.desktop " + (r.stdout + r.stderr).strip())
        r = sh("appstreamcli", "validate", "--no-net", "/usr/share/metainfo/archipelago.metainfo.xml")
        issues = [l for l in r.stdout.splitlines() if re.match(r"[EWI]: ", l)]
        # The only issue allowed: the id is not a reverse domain name (docs/install.md).
        check(all("cid-desktopapp-is-not-rdns" in l for l in issues),
              f"appstreamcli validate /usr/share/metainfo/archipelago.metainfo.xml: {issues or 'no issue'}")
    if "archipelago-cli.1" in pages and shutil.which("man"):
        r = sh("man", "-P", "cat", "archipelago-cli", env=dict(env, MANWIDTH="100", LC_ALL="C"))
        check(r.returncode == 0 and "archipelago-cli" in r.stdout, "man archipelago-cli")
    note("used")

    # --- 4. lintian -----------------------------------------------------------------------------------------------
    if shutil.which("lintian"):
        r = sh("lintian", "--display-info", deb, timeout=1200)
        tags = [l for l in r.stdout.splitlines() if re.match(r"[EWIPX]: ", l)]
        print("\n".join("     lintian | " + l for l in tags) or "     lintian: no tag")
        errors = [l for l in tags if l.startswith("E: ")]
        check(not errors and "error" not in r.stderr.lower(), f"lintian: no error ({len(errors)} errors, "
              f"{sum(l.startswith('W: ') for l in tags)} warnings) {r.stderr.strip()[-300:]}")
        note("lintian")
    else:
        check(False, "lintian installed (scripts/install-deps.sh)")
except Stop:
    pass
finally:
    # --- 5. removed, and nothing left -------------------------------------------------------------------------------
    if installed:
        r = sh("apt-get", "-o", "DPkg::Lock::Timeout=600", "remove", "--purge", "-y", "archipelago", env=apt_env)
        check(r.returncode == 0, "apt-get remove --purge -y archipelago " + (r.stdout + r.stderr).strip()[-600:])
        left = [f for f in files if os.path.lexists(f)]
        folders = {os.path.dirname(f) for f in files if "archipelago" in os.path.dirname(f)}
        left += sorted(d for d in folders if os.path.lexists(d))
        check(not left, f"nothing of the package is left after the purge (left: {left})")
        r = sh("dpkg-query", "-W", "-f=${Status}", "archipelago")
        check("installed" not in r.stdout or "not-installed" in r.stdout, f"dpkg knows no archipelago ({r.stdout})")
        note("removed")
    if failures:
        print(f"the package and its work folder are kept: {work}")
    else:
        shutil.rmtree(work)
print(f"{failures} failed" if failures else "all passed")
sys.exit(1 if failures else 0)

#!/usr/bin/env python3
"""Issue 42: a PNG says where it came from.  The PNGs of `portrait` and `indicator` carry, as tEXt chunks (read here
by an independent parser that checks every chunk's CRC), the program and its version (project() in
CMakeLists.txt), the commit it was built from, the map (K, xmin, xmax) and the view as asked, and the image's
parameters; the K scan's heat map the program at least.  (The GUI's portrait export: gui.portrait_view.)"""
import os, re, struct, tempfile, zlib

from clitest import check, finish, run

version = re.search(r"project\(Archipelago VERSION ([0-9.]+)", open(os.path.join(
    os.path.dirname(__file__), "..", "..", "CMakeLists.txt")).read()).group(1)


def png_chunks(path):
    """[(type, data)] of a PNG file, every CRC checked; None when it is not a well-formed PNG ending in IEND."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    chunks, pos = [], 8
    while pos + 12 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        crc, = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) != crc:
            return None
        chunks.append((kind.decode("latin1"), body))
        pos += 12 + length
        if kind == b"IEND":
            return chunks if pos == len(data) else None
    return None


def text_chunks(path):
    """{keyword: text} of the tEXt chunks (Latin-1), or None."""
    chunks = png_chunks(path)
    if chunks is None:
        return None
    return {k.decode("latin1"): v.decode("latin1") for t, b in chunks if t == "tEXt" for k, v in [b.split(b"\0", 1)]}


def check_program(text, what):
    check(text is not None and text.get("Software") == f"archipelago {version}" and text.get("Version") == version,
          f"{what}: tEXt Software and Version = {version} ({text and text.get('Software')})")
    commit = (text or {}).get("Commit", "")
    check(re.fullmatch(r"[0-9a-f]{12}(-dirty)?|unknown", commit) is not None, f"{what}: tEXt Commit '{commit}'")


def check_view(text, view, what):
    got = [float((text or {}).get(f"View {e}", "nan")) for e in ("x0", "x1", "y0", "y1")]
    check(all(abs(g - v) <= 1e-15 * max(1, abs(v)) for g, v in zip(got, view)), f"{what}: tEXt View = {got}")


with tempfile.TemporaryDirectory() as d:
    view = (-0.45, -0.2, -0.1, 0.125)
    png = os.path.join(d, "portrait.png")
    r = run("portrait", "--K", "0.2", "--xmin", "-0.9", "--xmax", "0.55", "--view=" + ",".join(map(str, view)),
            "--size", "40x30", "--points", "20000", "--orbits", "8", "--out", png, "--quiet")
    check(r.returncode == 0, f"portrait exits 0 ({r.stderr.strip()})")
    text = text_chunks(png)
    print("     portrait.png:", text)
    check_program(text, "portrait")
    check(text is not None and (text.get("K"), text.get("xmin"), text.get("xmax")) == ("0.2", "-0.9", "0.55"),
          "portrait: tEXt K, xmin, xmax as given")
    check_view(text, view, "portrait")
    check(text is not None and text.get("Image") == "phase portrait, density" and text.get("Size") == "40x30"
          and text.get("Points") == "20000" and text.get("Orbits") == "8" and text.get("Seed") == "1",
          "portrait: tEXt Image, Size, Points, Orbits, Seed")

    png = os.path.join(d, "indicator.png")
    r = run("indicator", "--kind", "dig", "--view=" + ",".join(map(str, view)), "--size", "8x6", "--iterations", "1000",
            "--out", png, "--quiet")
    check(r.returncode == 0, f"indicator exits 0 ({r.stderr.strip()})")
    text = text_chunks(png)
    check_program(text, "indicator")
    check(text is not None and text.get("K") == "0.1" and text.get("Image") == "indicator map, dig"
          and text.get("Iterations") == "1000", f"indicator: tEXt K, Image, Iterations ({text})")
    check_view(text, view, "indicator")

    # A PNG without text has none (the parser is not fooled): the bytes of a 1x1 PNG written here.
    raw = b"\x89PNG\r\n\x1a\n"
    for kind, body in ((b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)),
                       (b"IDAT", zlib.compress(b"\0\0\0\0")), (b"IEND", b"")):
        raw += struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    open(os.path.join(d, "plain.png"), "wb").write(raw)
    check(text_chunks(os.path.join(d, "plain.png")) == {}, "a PNG without text chunks reads as none")

finish()

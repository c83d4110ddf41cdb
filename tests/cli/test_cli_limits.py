"""archipelago-cli limits prints core's one table of limits (issue 35, item 2), and docs/cli.md holds the same table
between its markers: the documentation cannot drift from the limits the program enforces."""
import pathlib
import subprocess
import sys

cli = sys.argv[1]
printed = subprocess.run([cli, "limits"], capture_output=True, text=True, timeout=600, check=True).stdout
doc = (pathlib.Path(__file__).resolve().parents[2] / "docs" / "cli.md").read_text(encoding="utf-8")
begin, end = "<!-- limits -->\n", "<!-- /limits -->"
assert begin in doc and end in doc, "docs/cli.md has no limits table between its markers"
documented = doc[doc.index(begin) + len(begin):doc.index(end)]
if documented != printed:
    print("docs/cli.md's limits table differs from `archipelago-cli limits`:\n--- docs\n" + documented +
          "--- program\n" + printed)
    sys.exit(1)
rows = [line for line in printed.splitlines() if line.startswith("| ") and not line.startswith("| limit")]
assert len(rows) == 14, rows  # issue 54: the Markov tree's states and survival values; issue 51: the seeds
assert "| threads | " in printed and "| 0 … 256 |" in printed, printed
print(f"cli.limits: {len(rows)} limits, docs/cli.md agrees")

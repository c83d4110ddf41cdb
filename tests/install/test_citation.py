#!/usr/bin/env python3
"""CITATION.cff (issue 42): a valid Citation File Format 1.2.0 file, read with a YAML parser (no network): the keys
the format requires (cff-version 1.2.0, message, title, authors, each author a person or an entity), no key the
format does not know, type software, the program's version equal to project() in CMakeLists.txt (the one place;
the AppStream metainfo's newest release too), and the paper it reproduces as a reference: C. F. F. Karney,
Long-time correlations in the stochastic regime, Physica D 8 (1983) 360-380.
Argument: the source folder."""
import os, re, sys
import xml.etree.ElementTree as ET

import yaml

root = sys.argv[1]
failures = 0


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    failures += 0 if cond else 1


# The keys of the format (https://github.com/citation-file-format/citation-file-format, schema.json of 1.2.0).
TOP = {"abstract", "authors", "cff-version", "commit", "contact", "date-released", "doi", "identifiers", "keywords",
       "license", "license-url", "message", "preferred-citation", "references", "repository", "repository-artifact",
       "repository-code", "title", "type", "url", "version"}
REFERENCE = {"abbreviation", "abstract", "authors", "collection-doi", "collection-title", "collection-type", "commit",
             "conference", "contact", "copyright", "data-type", "database", "database-provider", "date-accessed",
             "date-downloaded", "date-published", "date-released", "department", "doi", "edition", "editors",
             "editors-series", "end", "entry", "filename", "format", "identifiers", "institution", "isbn", "issn",
             "issue", "issue-date", "issue-title", "journal", "keywords", "languages", "license", "license-url",
             "loc-end", "loc-start", "location", "medium", "month", "nihmsid", "notes", "number", "number-volumes",
             "pages", "patent-states", "pmcid", "publisher", "recipients", "repository", "repository-artifact",
             "repository-code", "scope", "section", "senders", "start", "status", "term", "thesis-type", "title",
             "translators", "type", "url", "version", "volume", "volume-title", "year", "year-original"}
PERSON = {"family-names", "given-names", "name-particle", "name-suffix", "affiliation", "address", "alias", "city",
          "country", "email", "fax", "orcid", "post-code", "region", "tel", "website"}
ENTITY = {"name", "address", "alias", "city", "country", "date-end", "date-start", "email", "fax", "location",
          "orcid", "post-code", "region", "tel", "website"}


def valid_author(a):
    return isinstance(a, dict) and (("name" in a and set(a) <= ENTITY) or
                                    (("family-names" in a or "given-names" in a) and set(a) <= PERSON))


cff = yaml.safe_load(open(os.path.join(root, "CITATION.cff"), encoding="utf-8"))
version = re.search(r"project\(Archipelago VERSION ([0-9.]+)",
                    open(os.path.join(root, "CMakeLists.txt")).read()).group(1)
check(isinstance(cff, dict), "CITATION.cff is a YAML mapping")
check(cff.get("cff-version") == "1.2.0", f"cff-version 1.2.0 ({cff.get('cff-version')!r})")
check(all(isinstance(cff.get(k), str) and cff[k].strip() for k in ("message", "title")), "message and title")
check(isinstance(cff.get("authors"), list) and cff["authors"] and all(valid_author(a) for a in cff["authors"]),
      f"authors: persons or entities ({cff.get('authors')})")
check(set(cff) <= TOP, f"only the format's keys (not: {sorted(set(cff) - TOP)})")
check(cff.get("type") == "software", "type software")
check(cff.get("version") == version, f"version {cff.get('version')!r} = project() in CMakeLists.txt ({version})")
releases = [r.get("version") for r in ET.parse(os.path.join(root, "resources/archipelago.metainfo.xml")).iter("release")]
check(releases[:1] == [version], f"the metainfo's newest release {releases[:1]} is that version too")

papers = [r for r in cff.get("references", []) if isinstance(r, dict) and r.get("type") == "article"]
karney = [r for r in papers if any(a.get("family-names") == "Karney" for a in r.get("authors", []))]
check(len(karney) == 1, "the paper it reproduces, Karney's, is a reference")
if karney:
    p = karney[0]
    check(set(p) <= REFERENCE and all(valid_author(a) for a in p["authors"]), "the reference has only the format's keys")
    check(p.get("title") == "Long-time correlations in the stochastic regime", f"its title ({p.get('title')})")
    check("Physica D" in str(p.get("journal")) and (p.get("volume"), p.get("start"), p.get("end"), p.get("year")) ==
          (8, 360, 380, 1983), f"Physica D 8 (1983) 360-380 ({p.get('journal')}, {p.get('volume')}, {p.get('start')}"
          f"-{p.get('end')}, {p.get('year')})")
    check(p["authors"][0].get("given-names", "").startswith("Charles F. F"), "C. F. F. Karney")
sys.exit(1 if failures else 0)

#!/usr/bin/python3
"""Fails when a count that README.md or docs/ states about the project
differs from the real thing, counted here from the source tree:

- the bad-input cases (README "tests/bad_input: N cases"; docs/reliability.md
  the scene cases, the command lines and their sum), counted the way
  tests/bad_input/run_bad_input.py loads them;
- the bundled scenes: every scenes/*.yaml is named in the README's
  "Scenes" item and no scene named there is missing;
- the paper's scenes: the number README.md and docs/scenes.md give equals
  the scenes/paper/*_small.yaml files, each has its test case in
  tests/app/test_paper_scenes.cpp, and each paper-size scene
  (scenes/paper/NAME.yaml) its run in tests/app/test_paper_size_runs.cpp
  (their sizes in docs/scenes.md: tests/app/test_paper_scene_sizes.cpp);
- docs/claims.md: every test file it names exists, and every test case it
  names ("name" after the file) is a TEST_CASE of that file.

usage: tests/check_doc_counts.py SOURCE_DIR"""
import pathlib
import re
import sys

WORDS = {"one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8, "nine": 9,
         "ten": 10, "eleven": 11, "twelve": 12}


def number(text: str) -> int:
    return WORDS[text.lower()] if text.lower() in WORDS else int(text.replace(",", ""))


def flat(text: str) -> str:
    """Markdown with its line breaks folded: a claim may wrap."""
    return re.sub(r"\s+", " ", text)


def test_case_names(source: str) -> set:
    """The names of a C++ file's Catch2 TEST_CASEs, adjacent string literals
    joined (a long name may be split over lines)."""
    names = set()
    for m in re.finditer(r'TEST_CASE\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+)', source):
        names.add("".join(re.findall(r'"((?:[^"\\]|\\.)*)"', m.group(1))))
    return names


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    readme = flat((root / "README.md").read_text(encoding="utf-8"))
    scenes_md = flat((root / "docs" / "scenes.md").read_text(encoding="utf-8"))
    problems = []

    # Bad-input cases.
    sys.path.insert(0, str(root / "tests" / "bad_input"))
    import run_bad_input  # noqa: E402  (the suite's own loader)

    cases = len(run_bad_input.load_cases())
    stated = re.findall(r"tests/bad_input`?: ([0-9][0-9,]*) cases", readme)
    if not stated:
        problems.append("README.md: no 'tests/bad_input: N cases' found")
    for s in stated:
        if number(s) != cases:
            problems.append(f"README.md says {s} bad-input cases; tests/bad_input has {cases}")

    reliability = flat((root / "docs" / "reliability.md").read_text(encoding="utf-8"))
    scene_cases = len([c for c in run_bad_input.load_cases() if c[4] is not None])
    for label, pattern, real in (("scene cases", r"`cases/\*\.yaml` — one scene per case \(([0-9]+)\)", scene_cases),
                                 ("command lines", r"`cli\.txt` — one command line per line \(([0-9]+)\)",
                                  cases - scene_cases),
                                 ("cases in all", r"was written\. ([0-9][0-9,]*) cases", cases),
                                 ("cases in all", r"run_bad_input\.py \[FILTER\]`\), ([0-9][0-9,]*) cases", cases),
                                 ("scene cases", r"was written\. [0-9,]+ cases \(([0-9]+) \+", scene_cases),
                                 ("command lines", r"was written\. [0-9,]+ cases \([0-9]+ \+ ([0-9]+)\)",
                                  cases - scene_cases)):
        found = re.findall(pattern, reliability)
        if not found:
            problems.append(f"docs/reliability.md: no '{pattern}' found")
        for s in found:
            if number(s) != real:
                problems.append(f"docs/reliability.md says {s} bad-input {label}; tests/bad_input has {real}")

    # Bundled scenes, by name in the README's Scenes item.
    item = re.search(r"- \*\*Scenes\*\*:(.*?)(?= - \*\*|$)", readme)
    if not item:
        problems.append("README.md: no '- **Scenes**:' item found")
    else:
        named = set(re.findall(r"`([a-z_0-9]+)`", item.group(1)))
        on_disk = {p.stem for p in (root / "scenes").glob("*.yaml")}
        for s in sorted(on_disk - named):
            problems.append(f"README.md's Scenes item does not name scenes/{s}.yaml")
        for s in sorted(named - on_disk):
            problems.append(f"README.md's Scenes item names `{s}`, which is not in scenes/")

    # The paper's scenes.
    small = sorted(p.name[: -len("_small.yaml")] for p in (root / "scenes" / "paper").glob("*_small.yaml"))
    for where, text, pattern in (("README.md", readme, r"The paper's (\w+) Table-1 scenes"),
                                 ("docs/scenes.md", scenes_md, r"The paper's (\w+) scenes")):
        found = re.findall(pattern, text)
        if not found:
            problems.append(f"{where}: no '{pattern}' found")
        for s in found:
            if number(s) != len(small):
                problems.append(f"{where} says {s} paper scenes; scenes/paper has {len(small)} small ones")
    tests = (root / "tests" / "app" / "test_paper_scenes.cpp").read_text(encoding="utf-8")
    for name in small:
        if f"the paper's {name}, small" not in tests:
            problems.append(f"scenes/paper/{name}_small.yaml: no test case \"the paper's {name}, small…\" "
                            "in tests/app/test_paper_scenes.cpp")

    runs = (root / "tests" / "app" / "test_paper_size_runs.cpp").read_text(encoding="utf-8")
    for p in sorted((root / "scenes" / "paper").glob("*.yaml")):
        name = p.stem
        if not name.endswith("_small") and f"the paper's {name} at the paper's size runs a frame" not in runs:
            problems.append(f"scenes/paper/{name}.yaml: no test case \"the paper's {name} at the paper's size runs "
                            "a frame\" in tests/app/test_paper_size_runs.cpp")

    # The claims table: its tests exist.
    claims = (root / "docs" / "claims.md").read_text(encoding="utf-8")
    named_tests = 0
    for row in (line for line in claims.splitlines() if line.startswith("| ") and "`tests/" in line):
        test_cell = row.rstrip().rstrip("|").split("|")[-1]
        for part in re.finditer(r"`(tests/[^`]+)`((?:[:;] \"[^\"]+\")*)", test_cell):
            path = root / part.group(1)
            if not path.is_file():
                problems.append(f"docs/claims.md names {part.group(1)}, which does not exist")
                continue
            declared = test_case_names(path.read_text(encoding="utf-8"))
            for name in re.findall(r'"([^"]+)"', part.group(2)):
                named_tests += 1
                if name not in declared:
                    problems.append(f"docs/claims.md names the test case \"{name}\", which is not in {part.group(1)}")
    if named_tests == 0:
        problems.append("docs/claims.md: no test case found (the table's format changed?)")

    for p in problems:
        print(p)
    print(f"{cases} bad-input cases, {len(list((root / 'scenes').glob('*.yaml')))} scenes, "
          f"{len(small)} paper scenes; {len(problems)} wrong counts")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

"""The README's commands are the ones CI runs, every one of them runs as the README says, and every
relative link in the README and in docs/ leads somewhere (issue 44)."""

import importlib.util
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = sorted((ROOT / "docs").glob("*.md"))
MAX_README_LINES = 600


def test_ci_runs_the_readme_test_command():
    readme = README.read_text()
    blocks = re.findall(r"```sh\n(.*?)\n```", readme, re.S)
    test_cmd = blocks[1].strip()
    assert "pytest" in test_cmd
    ci = (ROOT / ".ci" / "run").read_text()
    assert test_cmd in ci.splitlines()


def test_readme_is_short():
    lines = README.read_text().count("\n")
    assert lines <= MAX_README_LINES, f"README.md has {lines} lines; at most {MAX_README_LINES} (the rest goes to docs/)"


# ------------------------------------------------------------------ every command the README shows

def readme_commands(text: str) -> list[tuple[tuple[str, ...], int]]:
    """Every `camcam …` line of the README's sh/console blocks, in order, without repeats: (argv, exit status).

    A line's exit status is 0 unless its comment says `exit N`. A console block's lines may start with `$ `.
    """
    found: list[tuple[tuple[str, ...], int]] = []
    for block in re.findall(r"```(?:sh|console)\n(.*?)\n```", text, re.S):
        for line in block.splitlines():
            line = line.strip().removeprefix("$ ")
            if not line.startswith("camcam "):
                continue
            m = re.search(r"#.*?\bexit (\d+)", line)
            cmd = (tuple(shlex.split(line, comments=True)[1:]), int(m.group(1)) if m else 0)
            if cmd not in found:
                found.append(cmd)
    return found


def output_of(argv: tuple[str, ...]) -> str | None:
    for flag in ("-o", "--output"):
        if flag in argv:
            return argv[argv.index(flag) + 1]
    return None


def command_groups() -> dict[str, list[tuple[tuple[str, ...], int]]]:
    """Commands that write into the same folder run together, in the README's order; the others alone."""
    groups: dict[str, list] = {}
    for argv, status in readme_commands(README.read_text()):
        key = output_of(argv) or " ".join(argv)
        groups.setdefault(key, []).append((argv, status))
    return groups


GROUPS = command_groups()


def test_the_readme_shows_the_commands():
    names = {argv[0] for group in GROUPS.values() for argv, _ in group}
    assert {"laws", "motion", "run", "optimize", "fit", "reverse", "size", "batch"} <= names
    # each example that should succeed writes into a folder of its own, apart from an explicit --force
    plain = [output_of(argv) for g in GROUPS.values() for argv, s in g if s == 0 and "--force" not in argv]
    plain = [o for o in plain if o is not None]
    assert len(plain) == len(set(plain)), f"two README examples write into one folder: {sorted(plain)}"


def _needs_missing_extra(argv: tuple[str, ...]) -> str | None:
    if ({"--scheduler", "--workers"} & set(argv)) and importlib.util.find_spec("distributed") is None:
        return "dask[distributed] (camcam[scale]) is not installed"
    return None


@pytest.mark.parametrize("key", list(GROUPS), ids=lambda k: re.sub(r"\W+", "-", k)[:48])
def test_readme_command_runs(key, tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for argv, status in GROUPS[key]:
        if (why := _needs_missing_extra(argv)) is not None:
            pytest.skip(why)
        args = list(argv)
        out = output_of(argv)
        if out is not None:
            i = args.index(out, args.index("-o" if "-o" in args else "--output"))
            args[i] = str(tmp_path / Path(out).name)
        proc = subprocess.run([sys.executable, "-m", "camcam", *args], cwd=ROOT, env=env,
                              capture_output=True, text=True, timeout=600)
        shown = "camcam " + " ".join(argv)
        assert proc.returncode == status, (
            f"README: `{shown}` should exit {status}, exited {proc.returncode}\n{proc.stderr[-2000:]}")
        if status == 2:
            assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr


# ------------------------------------------------------------------ links

def _prose(text: str) -> str:
    """The text without fenced code blocks and inline code spans (links there are not links)."""
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*`", "", text)


def slugs(text: str) -> set[str]:
    """GitHub's anchors of a page's headings."""
    found: set[str] = set()
    for title in re.findall(r"^#{1,6} (.+?)\s*$", re.sub(r"^```.*?^```", "", text, flags=re.S | re.M), re.M):
        title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title).replace("`", "")
        slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
        base, n = slug, 0
        while slug in found:
            n += 1
            slug = f"{base}-{n}"
        found.add(slug)
    return found


@pytest.mark.parametrize("page", [README, *DOCS], ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_lead_somewhere(page):
    broken = []
    for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", _prose(page.read_text())):
        if re.match(r"[a-z][a-z0-9+.-]*:", target):       # http:, https:, mailto:
            continue
        path, _, anchor = target.partition("#")
        dest = (page.parent / path).resolve() if path else page
        if not dest.exists():
            broken.append(f"{target}: no file {dest}")
        elif anchor and dest.suffix == ".md" and anchor not in slugs(dest.read_text()):
            broken.append(f"{target}: no heading #{anchor} in {dest.relative_to(ROOT)}")
    assert not broken, f"{page.relative_to(ROOT)}: " + "; ".join(broken)


def test_docs_pages_are_linked_from_the_readme():
    readme = README.read_text()
    missing = [p.name for p in DOCS if f"(docs/{p.name}" not in readme]
    assert not missing, f"docs pages the README does not link: {missing}"


def test_every_benchmark_table_says_how_to_remake_it():
    """docs/benchmarks.md: each table follows a `Re-make: PYTHONPATH=. python benchmarks/….py` line."""
    lines = (ROOT / "docs" / "benchmarks.md").read_text().splitlines()
    last_table_end, bad = 0, []
    for i, line in enumerate(lines):
        if line.startswith("|") and (i == 0 or not lines[i - 1].startswith("|")):
            scripts = [m.group(1) for l in lines[last_table_end:i]
                       if (m := re.match(r"Re-make: `PYTHONPATH=\. python (benchmarks/\w+\.py)", l))]
            if not scripts:
                bad.append(f"line {i + 1}: {line[:60]}")
            elif not (ROOT / scripts[-1]).exists():
                bad.append(f"line {i + 1}: {scripts[-1]} does not exist")
        if line.startswith("|"):
            last_table_end = i + 1
    assert not bad, "benchmark tables without the command that re-makes them: " + "; ".join(bad)


def test_the_python_examples_run(monkeypatch):
    """The README's ```python blocks are doctests: the Python face (camcam.run_job) works as shown."""
    import doctest

    blocks = re.findall(r"```python\n(.*?)\n```", README.read_text(), re.S)
    assert blocks, "the README shows camcam.run_job"
    monkeypatch.chdir(ROOT)  # the examples name samples/… from the repository's top
    parser, runner = doctest.DocTestParser(), doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for k, block in enumerate(blocks):
        runner.run(parser.get_doctest(block, {}, f"README python block {k + 1}", str(README), 0))
    result = runner.summarize(verbose=False)
    assert result.failed == 0 and result.attempted >= 6, result

"""The design-space campaign (issue 43): random valid specs over every cam family, follower, post and size.

Each case (deterministic from ``--seed`` and its index, :func:`tests.designspace.draw_case`) is written
as a spec, run by ``camcam run`` in a subprocess, classified by its exit status and one-line cause, its
advice followed (at most two reruns), and an exit-0 program measured: read back by LinuxCNC's rs274
against the exact curves (disc cams, posts rs274 reads) or by the report's 3-D groove figure (barrels).
The generator and the runner are in ``tests/designspace.py`` (``tests/test_anycam.py`` runs a subset).

    PYTHONPATH=. .venv/bin/python benchmarks/anycam.py --cases 500 [--seed S] [--jobs 2] [--json FILE]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import Counter, defaultdict
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.designspace import classify, draw_case, run_case, to_toml  # noqa: E402


def _one(args):
    seed, index = args
    return run_case(draw_case(seed, index))


def summary(records: list[dict], wall_s: float, cpu_s: float) -> str:
    out = []
    n = len(records)
    out.append(f"{n} cases")
    st = Counter(r["status"] for r in records)
    out.append("exit status: " + ", ".join(f"{k}: {v}" for k, v in sorted(st.items())))
    by_cause = Counter((r["status"], r["cause"]) for r in records)
    out.append("causes:")
    for (s, c), v in sorted(by_cause.items(), key=lambda kv: (kv[0][0], -kv[1])):
        fams = Counter(r["family"] for r in records if (r["status"], r["cause"]) == (s, c))
        first = next(r["key"] for r in records if (r["status"], r["cause"]) == (s, c))
        out.append(f"  exit {s}  {v:4d}  {c}   [{', '.join(f'{f} {k}' for f, k in fams.most_common())}; e.g. case {first}]")
    fam = defaultdict(Counter)
    for r in records:
        fam[r["family"]][r["status"]] += 1
    out.append("per family (exit status: count):")
    for f in sorted(fam):
        out.append(f"  {f:26s} " + ", ".join(f"{k}: {v}" for k, v in sorted(fam[f].items())))
    extra = [r for r in records if r["status"] in (2, 3) and len(r["lines"]) != 1]
    out.append(f"exit 2/3 with other than one stderr line: {len(extra)}"
               + (f" (e.g. case {extra[0]['key']}: {len(extra[0]['lines'])} lines)" if extra else ""))
    # deviation of passed programs
    measured = [(r["key"], r["readback"], r["family"]) for r in records
                if r["status"] == 0 and r["readback"] and r["cause"] == "ok"]  # not the accepted FAILs
    for how in ("rs274 read-back", "report 3-D groove"):
        ms = [(k, rb, f) for k, rb, f in measured if rb.get("how") == how and rb.get("multiple") is not None]
        if ms:
            k, rb, f = max(ms, key=lambda x: x[1]["multiple"])
            over = sum(1 for _, x, _ in ms if x["multiple"] > 1.0)
            out.append(f"worst passed deviation ({how}): {rb['multiple']:.3f} x tolerance "
                       f"({rb['deviation']:.5f} of {rb['tolerance']:g} mm, case {k} {f}, {rb.get('where', '')}); "
                       f"{len(ms)} programs measured, {over} over 1.0")
    sw = [(r["key"], r["readback"]) for r in records if r["cause"] == "ok" and r["readback"]
          and r["readback"].get("swept_multiple") is not None]
    if sw:
        k, rb = max(sw, key=lambda x: x[1]["swept_multiple"])
        out.append(f"worst passed 5-axis groove, rs274's moves swept (tests/nc/test_fiveaxis.py): "
                   f"{rb['swept_multiple']:.3f} x tolerance (overcut {rb['swept_overcut']:.5f}, left "
                   f"{rb['swept_left']:.5f} of {rb['tolerance']:g} mm, case {k}); {len(sw)} programs")
    errs = [(r["key"], r["readback"]["error"]) for r in records if r["status"] == 0 and r["readback"].get("error")]
    if errs:
        out.append(f"read-back faults: {len(errs)} (e.g. case {errs[0][0]}: {errs[0][1][:160]})")
    rej = [r["key"] for r in records if r["status"] == 0 and str(r["readback"].get("rs274", "")).startswith("rejected")]
    out.append(f"barrel programs rs274 rejected: {len(rej)}" + (f" (e.g. {rej[0]})" if rej else ""))
    unread = Counter(r["readback"].get("how") for r in records if r["status"] == 0 and r["readback"]
                     and r["readback"].get("multiple") is None)
    if unread:
        out.append("exit-0 programs not measured: " + ", ".join(f"{k}: {v}" for k, v in unread.items()))
    # advice
    adv = [r for r in records if r["advice"] is not None]
    named = [r for r in adv if r["advice"]["named"]]
    informal = [r for r in adv if not r["advice"]["named"] and r["advice"]["informal"]]
    out.append(f"advice: {len(adv)} exit 2/3; {len(named)} name a spec key with a value, {len(informal)} a value "
               f"in an informal form (followed as well), {len(adv) - len(named) - len(informal)} no value")
    for label, group in (("key = value", named), ("informal", informal), ("all followed", named + informal)):
        followed = [r for r in group if r["advice"].get("result")]
        res = Counter(r["advice"]["result"] for r in followed)
        good = res["exit 0"] + res["other reason"]
        rate = f"{good / len(followed):.0%}" if followed else "n/a"
        out.append(f"  {label}: {len(followed)} followed: {res['exit 0']} reached exit 0, {res['other reason']} a "
                   f"different reason, {res['same reason']} the same reason again -> success {rate}")
    final = Counter(r["advice"]["steps"][-1]["cause"] for r in named + informal if r["advice"]["steps"])
    if final:
        out.append("  last rerun's outcome: " + ", ".join(f"{c}: {v}" for c, v in final.most_common()))
    forms = Counter(r["advice"]["form"] for r in adv if not r["advice"]["named"])
    if forms:
        out.append("advice naming no machine-applicable key/value (numbers as #):")
        for f, v in forms.most_common():
            out.append(f"  {v:3d}  {f[:400]}")
    out.append(f"time: {wall_s:.1f} s wall, {cpu_s:.1f} CPU s (user + sys of camcam runs, rs274 and read-back)")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--seed", type=int, default=43)
    ap.add_argument("--start", type=int, default=0, help="first case index")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--json", help="write every case's record here (JSON lines)")
    ap.add_argument("--show", type=int, nargs="*", help="print these cases' specs and exit")
    ap.add_argument("--merge", nargs="+", help="print the summary of earlier --json files (no runs)")
    ap.add_argument("--wall", type=float, help="with --merge: the runs' wall seconds in all")
    a = ap.parse_args(argv)
    if a.merge:
        records = [json.loads(line) for f in a.merge for line in open(f) if line.strip()]
        for r in records:  # classified again, by this version's table
            r["cause"] = classify(r["status"], r["lines"])
        print(summary(records, a.wall or float("nan"), sum(r["cpu_s"] for r in records)))
        return 0
    if a.show:
        for i in a.show:
            print(f"# case {a.seed}:{i} ({draw_case(a.seed, i).family})\n{to_toml(draw_case(a.seed, i).spec)}")
        return 0
    t0 = time.perf_counter()
    jobs = [(a.seed, i) for i in range(a.start, a.start + a.cases)]
    records = []
    sink = open(a.json, "w") if a.json else None
    with ProcessPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for k, rec in enumerate(pool.map(_one, jobs, chunksize=1), 1):
            records.append(rec)
            if sink:
                sink.write(json.dumps(rec) + "\n")
                sink.flush()
            if k % 10 == 0:
                print(f"... {k}/{len(jobs)} cases, {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
    if sink:
        sink.close()
    wall = time.perf_counter() - t0
    cpu = sum(r["cpu_s"] for r in records)
    print(summary(records, wall, cpu))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

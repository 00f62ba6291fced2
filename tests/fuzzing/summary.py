"""Figures of a fuzz run: counts by class, command, mutation category and example; failures grouped by
root cause with one reproducer each."""
from __future__ import annotations

from collections import Counter, defaultdict

from .classify import CLASSES, PROPERTY_CLASSES, Outcome


def counts(outcomes: list[Outcome], by: str) -> dict[str, Counter]:
    """``{value of attribute by: Counter(class -> runs)}``."""
    table: dict[str, Counter] = defaultdict(Counter)
    for o in outcomes:
        table[getattr(o, by)][o.cls] += 1
    return dict(sorted(table.items()))


def markdown_table(table: dict[str, Counter], first: str) -> str:
    cols = [c for c in CLASSES if any(row[c] for row in table.values())] or ["OK"]
    lines = [f"| {first} | runs | " + " | ".join(cols) + " |", "|---" * (len(cols) + 2) + "|"]
    total = Counter()
    for key, row in table.items():
        total.update(row)
        lines.append(f"| {key} | {sum(row.values())} | " + " | ".join(str(row[c] or "") for c in cols) + " |")
    lines.append(f"| **all** | {sum(total.values())} | " + " | ".join(str(total[c] or "") for c in cols) + " |")
    return "\n".join(lines)


def groups(outcomes: list[Outcome]) -> list[dict]:
    """Failures grouped by (class, root cause), largest first, each with its keys and one reproducer."""
    by: dict[tuple, list[Outcome]] = defaultdict(list)
    for o in outcomes:
        if o.failed:
            by[(o.cls, o.root_cause)].append(o)
    out = []
    for (cls, cause), items in by.items():
        items.sort(key=lambda o: (o.duration_s if cls != "HANG" else 0, o.id))
        first = items[0]
        out.append({
            "class": cls, "root_cause": cause, "runs": len(items),
            "files": len({o.id for o in items}),
            "commands": dict(Counter(o.command for o in items).most_common()),
            "categories": dict(Counter(o.category for o in items).most_common()),
            "targets": [t for t, _ in Counter(o.target or o.id.split("/")[-1] for o in items).most_common(8)],
            "example": {"id": first.id, "description": first.description, "command": first.command,
                        "detail": first.detail, "repro": first.repro},
        })
    order = {c: i for i, c in enumerate(CLASSES)}
    out.sort(key=lambda g: (order[g["class"]], -g["runs"], g["root_cause"]))
    return out


def figures(outcomes: list[Outcome]) -> dict:
    """The headline figures: runs, distinct mutated files, counts per class, time."""
    per_class = Counter(o.cls for o in outcomes)
    files = {o.id for o in outcomes if o.category != "control"}
    return {
        "runs": len(outcomes),
        "mutated_files": len(files),
        "controls": len({o.id for o in outcomes if o.category == "control"}),
        "per_class": {c: per_class.get(c, 0) for c in CLASSES},
        "property_failures": sum(per_class.get(c, 0) for c in PROPERTY_CLASSES),
        "files_with_property_failure": len({o.id for o in outcomes if o.cls in PROPERTY_CLASSES}),
        "flags": dict(Counter(f for o in outcomes for f in o.flags if f not in CLASSES).most_common()),
        "cpu_seconds_in_runs": round(sum(o.duration_s for o in outcomes), 1),
        "longest_run_s": max((o.duration_s for o in outcomes), default=0.0),
    }


def text_summary(outcomes: list[Outcome], wall_s: float | None = None) -> str:
    """A plain-text summary for the terminal and the test log."""
    f = figures(outcomes)
    head = (f"{f['runs']} runs of {f['mutated_files']} mutated files (+{f['controls']} controls)"
            + (f" in {wall_s:.0f} s" if wall_s is not None else "") + ": "
            + ", ".join(f"{c} {n}" for c, n in f["per_class"].items() if n)
            + "".join(f"; flag {k}: {v}" for k, v in f["flags"].items()))
    parts = [head, "", "by command:", markdown_table(counts(outcomes, "command"), "command"), "",
             "by mutation category:", markdown_table(counts(outcomes, "category"), "category")]
    gs = groups(outcomes)
    if gs:
        parts += ["", f"{len(gs)} root causes (class, runs, cause):"]
        parts += [f"  {g['class']:<10} {g['runs']:>5}  {g['root_cause']}" for g in gs[:40]]
        if len(gs) > 40:
            parts.append(f"  ... and {len(gs) - 40} more (see failures.json)")
    return "\n".join(parts)


def markdown_report(outcomes: list[Outcome], meta: dict) -> str:
    """The full markdown report: figures, the three tables and every root-cause group with a reproducer."""
    f = figures(outcomes)
    lines = ["# drivefem model-file fuzz run", ""]
    lines += [f"- {k}: {v}" for k, v in meta.items()]
    lines += [f"- runs: {f['runs']} over {f['mutated_files']} mutated files (+{f['controls']} controls)",
              "- per class: " + ", ".join(f"{c} {n}" for c, n in f["per_class"].items()),
              f"- runs failing an issue-11 property (HANG, TRACEBACK, BADEXIT, NONFINITE): {f['property_failures']}"
              f" ({f['files_with_property_failure']} files)",
              "- flags beside the class (memory_error: MemoryError in stderr; nonfinite_printed: nan/inf printed "
              "on stdout with exit 0): " + (", ".join(f"{k} {v}" for k, v in f["flags"].items()) or "none"), ""]
    for by, title in (("command", "By command"), ("category", "By mutation category"), ("example", "By example")):
        lines += [f"## {title}", "", markdown_table(counts(outcomes, by), by), ""]
    lines += ["## Failures by root cause", ""]
    for g in groups(outcomes):
        ex = g["example"]
        lines += [f"### {g['class']}: {g['root_cause']}", "",
                  f"- runs: {g['runs']} ({g['files']} files); commands: "
                  + ", ".join(f"{k} {v}" for k, v in g["commands"].items())
                  + "; categories: " + ", ".join(f"{k} {v}" for k, v in g["categories"].items()),
                  "- keys: " + ", ".join(f"`{t}`" for t in g["targets"]),
                  f"- example: `{ex['id']}` ({ex['description']}), `drivefem {ex['command']}`",
                  f"- detail: {ex['detail']}" if ex["detail"] else "",
                  "", "```sh", ex["repro"], "```", ""]
    return "\n".join(lines)

"""The README's "Advice" on speed against accuracy and the sentences around the tradeoff
tables, written from the committed ``workbook-gen tradeoff --json`` output
(docs/tradeoff/*.json): every number, and every claim that a number decides (which step
reaches an accuracy, whether float64 matters, whether time is flat), is computed here.

Seconds: a row's CPU seconds (``cpu_seconds``, process time of generate + audit) where the
file has them, else its wall seconds, said as such (the older files were measured under
load and record no CPU time).
"""

from __future__ import annotations

import datetime
import math
import re

LOADED = 1.5
TIERS = (("*Quick look, charts, design iterations*", 1e-2),
         ("*Reading off a stroke, a peak acceleration or a minimum transmission angle to "
          "1e-4*", 1e-4),
         ("*Extremes to 1e-6 or better*", 1e-6))


def sci(x: float) -> str:
    """1 significant digit: 7e-3."""
    mantissa, exponent = f"{x:.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def mb(x: int) -> str:
    return f"{x / 1e6:.1f} MB" if x >= 1e6 else f"{x / 1e3:.0f} kB"


def span(lo: float, hi: float, fmt: str = ".1f") -> str:
    """"lo-hi", or one figure when they agree to the digits shown."""
    a, b = format(lo, fmt), format(hi, fmt)
    return a if a == b else f"{a}-{b}"


def secs(row: dict) -> str:
    """The row's CPU seconds if recorded, else its wall seconds, with which it is."""
    cpu = row.get("cpu_seconds")
    value, kind = (cpu, "CPU") if cpu is not None else (row["seconds"], "wall")
    return f"{value:.2g} s {kind}" if value < 10 else f"{value:.0f} s {kind}"


def time_of(row: dict) -> float:
    cpu = row.get("cpu_seconds")
    return cpu if cpu is not None else row["seconds"]


def step_of(row: dict) -> float:
    return float(row["setting"].split()[0])


def label(row: dict, unit: str) -> str:
    return f"{row['setting'].split()[0]}°" if unit == "deg" else row["setting"]


def rows(data: dict, dimension: str, prefix: str = "") -> list[dict]:
    return [r for r in data["rows"] if r["dimension"] == dimension
            and r["setting"].startswith(prefix)]


def when(data: dict) -> str:
    run = data.get("run")
    if not run:
        return "load not recorded"
    date = datetime.datetime.strptime(run["started"], "%Y-%m-%dT%H:%M:%SZ").strftime(
        "%-d %b %Y %H:%M UTC")
    load = run.get("load_start")
    if load is not None and load > LOADED:
        return f"{date}, under load {load:.1f} (1-minute load average at the start)"
    return f"{date}, quiet machine (load average {load:.1f})"


def runtime_block(all_data: dict[str, dict], labels: dict[str, str]) -> str:
    parts = []
    for name, data in sorted(all_data.items(), key=lambda kv: list(labels).index(kv[0])
                             if kv[0] in labels else len(labels)):
        cpu = data.get("cpu_seconds")
        cpu = f", {cpu:.0f} s CPU" if cpu is not None else ""
        parts.append(f"{data['seconds']:.0f} s{cpu} ({labels.get(name, name)}; {when(data)})")
    return ("A whole run took " + ", ".join(parts) + ". Seconds are wall time and grow with "
            "the machine's load; CPU seconds (`cpu_seconds` of each row, the process time of "
            "the same work) much less so, and errors and cells not at all.\n")


def _precision(all_data: dict[str, dict]) -> str:
    worst = max(r["max_error"] for d in all_data.values() for r in rows(d, "precision", "float64")
                if r["max_error"] is not None)
    finest = min(r["max_error"] for d in all_data.values() for r in rows(d, "step")
                 if r["max_error"] is not None)
    if worst < finest / 100:
        return (f"Float64 is never the limit: the formulas agree with 50 digits to {sci(worst)} "
                f"or better even next to the extremes, in every scene above, so the error is "
                "the step's or the method's.")
    return (f"Float64 can be the limit: the formulas differ from 50 digits by up to "
            f"{sci(worst)}, against {sci(finest)} for the finest step.")


def _tier(steps: list[dict], target: float, unit: str) -> str:
    for r in steps:  # coarse to fine
        if r["max_error"] is not None and r["max_error"] <= target:
            return (f"{label(r, unit)} ({secs(r)}, {mb(r['bytes'])}, extremes within "
                    f"{sci(r['max_error'])})")
    last = steps[-1]
    return (f"no step of the table reaches it ({label(last, unit)} leaves "
            f"{sci(last['max_error'])}; {secs(last)}, {mb(last['bytes'])})")


def _convergence(steps: list[dict], unit: str) -> str:
    first, last = steps[0], steps[-1]
    order = (math.log(first["max_error"] / last["max_error"])
             / math.log(step_of(first) / step_of(last)))
    text = (f"extremes converge about as the step to the power {order:.1f} "
            f"({label(first, unit)} to {label(last, unit)})")
    # a coarse step as good as a finer one: the pair with the least gain, if far below order 2
    pairs = [(a["max_error"] / b["max_error"], a, b) for a, b in zip(steps, steps[1:])]
    gain, a, b = min(pairs, key=lambda p: p[0] / (step_of(p[1]) / step_of(p[2])) ** 2)
    if gain < (step_of(a) / step_of(b)) ** 2 / 2:
        culprit = max(b["errors"], key=lambda k: b["errors"][k] or 0.0)
        text += (f", but where the true extreme falls between grid points a coarser step can "
                 f"be nearly as good as a finer one (from {label(a, unit)} to {label(b, unit)} "
                 f"the error falls only from {sci(a['max_error'])} to {sci(b['max_error'])}, "
                 f"set by {culprit})")
    return text


def _rates(data: dict, unit: str) -> str:
    analytic = rows(data, "derivative", "analytic")
    central = rows(data, "derivative", "central")
    forward = rows(data, "derivative", "forward")
    if not (analytic and central and forward):
        return ""
    worst = max(r["max_error"] for r in analytic)
    cells = [a["cells"] / c["cells"] for a, c in zip(analytic, central)]
    times = [time_of(a) / time_of(c) for a, c in zip(analytic, central)]
    kind = "CPU" if all(r.get("cpu_seconds") is not None for r in analytic) else "wall"
    last_c, last_f = central[-1], forward[-1]
    where = last_c["setting"].split(", ")[1]
    where = f"{where.split()[0]}°" if unit == "deg" else where
    return (f"*Velocities and accelerations*: always the analytic columns ({sci(worst)} at every "
            f"step, and a sewing-machine workbook with them has {span(min(cells), max(cells))}x "
            f"the cells and takes {span(min(times), max(times))}x the "
            f"{kind} time of the positions-only one with difference columns); central "
            f"differences reach {sci(last_c['max_error'])} at {where}, forward differences "
            f"{sci(last_f['max_error'])} even there.")


def _unit_of(data: dict, quantity: str) -> str:
    from workbook_gen.scene import load_scene
    from pathlib import Path
    root = Path(__file__).resolve().parent.parent
    try:
        return load_scene(root / data["scene"].split(" (")[0]).template.quantity(quantity).unit
    except Exception:  # a renamed quantity or scene: say no unit rather than fail
        return ""


def _methods(all_data: dict[str, dict], labels: dict[str, str]) -> str:
    parts, timing = [], []
    for data in all_data.values():
        methods = [r for r in rows(data, "method") if r["max_error"] is not None]
        if not methods:
            continue
        closed, iterative = methods[0], methods[1:]
        lo, hi = min(map(time_of, iterative)), max(map(time_of, iterative))
        grow = iterative[-1]["cells"] / iterative[0]["cells"]
        kind = "CPU" if all(r.get("cpu_seconds") is not None for r in iterative) else "wall"
        flat = "flat" if hi / lo < 1.3 else f"varies {hi / lo:.1f}x"
        timing.append(f"{labels.get(data['name'], data['name'])} {span(lo, hi, '.2g')} s {kind}, {flat}, "
                      f"while its cells grow {grow:.1f}x")
        if iterative[0]["setting"].startswith("newton"):
            full = next((r for r in iterative if r["max_error"] <= 10 * closed["max_error"]),
                        None)
            if full is None:
                parts.append(f"Newton does not reach the closed form's precision in "
                             f"{iterative[-1]['setting'].split()[1]} iterations")
                continue
            k = int(full["setting"].split()[1])
            before = next((r for r in iterative if r["setting"] == f"newton {k - 1}"), None)
            step = (iterative[1]["cells"] - iterative[0]["cells"]) / closed["cells"]
            left = f" ({k - 1} leave {sci(before['max_error'])})" if before else ""
            parts.append(f"Newton needs {k} iterations for the five-bar's full precision{left}, "
                         f"{100 * step:.1f} % more cells per iteration")
        else:
            halvings = [int(r["note"].split()[0]) for r in iterative]
            decades = math.log10(iterative[0]["max_error"] / iterative[-1]["max_error"])
            per = (halvings[-1] - halvings[0]) / decades
            paper = next((r for r in iterative if r["setting"] == "epsilon 1e-04"), None)
            name = next(iter(paper["errors"])) if paper else ""
            unit = _unit_of(data, name) if paper else ""
            said = (f"the paper's epsilon 1e-4 leaves {sci(paper['max_error'])} relative, "
                    f"{sci(paper['abs_error'])} {unit}".rstrip() + "; ") if paper else ""
            last = iterative[-1]
            parts.append(f"halving gains a decade of error per {per:.1f} halvings ({said}"
                         f"{last['setting']} needs {halvings[-1]} halvings, "
                         f"{last['cells'] / closed['cells']:.1f}x the closed form's cells)")
    if not parts:
        return ""
    worst = max(r["max_error"] for d in all_data.values() for r in rows(d, "method")[:1]
                if r["max_error"] is not None)
    text = (f"*Iterative methods*: prefer the closed form (within {sci(worst)} of 50 digits, "
            "fewest cells); " + "; ".join(parts) + ".")
    if timing:
        text += (" Time per method setting: " + "; ".join(timing) + ": the cost of an "
                 "iteration shows in cells and bytes more than in seconds.")
    return text


def advice_block(all_data: dict[str, dict], labels: dict[str, str],
                 main: str = "sewing_machine") -> str:
    """The Advice paragraph: tiers of accuracy read off ``main``'s steps, rates from its
    derivative rows, methods from every scene that has them."""
    data = all_data[main]
    unit = data["input"]["unit"]
    steps = rows(data, "step")
    sentences = ["**Advice.**", _precision(all_data)]
    for i, (who, target) in enumerate(TIERS):
        text = f"{who}: {_tier(steps, target, unit)}"
        if i == 1:
            text += "; " + _convergence(steps, unit)
        if i == 2:
            first, last = steps[0], steps[-1]
            reached = any(r["max_error"] is not None and r["max_error"] <= target
                          for r in steps)
            text += (", or better the coarse table plus a local refinement" if reached else
                     ": use a coarse table plus a local refinement")
            text += (f"; a {step_of(first) / step_of(last):.0f}x finer step costs "
                     f"{last['cells'] / first['cells']:.0f}x the cells and cuts the error "
                     f"{sci(first['max_error'] / last['max_error'])}-fold")
        sentences.append(text + ".")
    sentences.append(_rates(data, unit))
    sentences.append(_methods(all_data, labels))
    return (" ".join(s for s in sentences if s) + f" (Steps: {labels.get(main, main)}; "
            "seconds: CPU where the file records it, else wall time.)\n")


def newton_block(data: dict) -> str:
    """The sentence under the five-bar's table: Newton's rate and what the audit flags."""
    newton = [r for r in rows(data, "method", "newton") if r["max_error"] is not None]
    if not newton:
        return "No Newton rows.\n"
    closed = next((r["max_error"] for r in rows(data, "method", "closed")), None) or 0.0
    # pairs in the quadratic regime: not yet at rounding (10x the closed form's error)
    quad = [b["max_error"] / a["max_error"] ** 2 for a, b in zip(newton, newton[1:])
            if a["max_error"] < 1e-3 and b["max_error"] > 10 * closed]
    flagged = [int(r["setting"].split()[1]) for r in newton if "audit flags" in r["note"]]
    text = ""
    if quad:
        text = (f"Newton converges quadratically (each error about {span(min(quad), max(quad))}"
                f" x the square of the one before, until rounding); ")
    found = re.search(r"iterations = (\d+)", data.get("scene", ""))
    uses = int(found.group(1)) if found else None
    if flagged:
        which = f"{flagged[0]}..{flagged[-1]}" if len(flagged) > 1 else str(flagged[0])
        text += f"the audit flags {which} iterations (1e-9 against its reference model)"
        if uses is None:
            text += "."
        elif uses > flagged[-1]:
            text += f", which is why the copy uses {uses}."
        else:
            text += f", and the copy uses {uses}: it needs more."
    else:
        text += "the audit flags none of them."
    return text[0].upper() + text[1:] + "\n"

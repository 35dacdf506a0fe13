"""Fuzzing `unsatmpm check` with mutated case files (issue 15, item 7).

A fixed-seed corpus: every case file of examples/ and verification/, each mutated by one of
delete a line, duplicate a line, retype a value, change a number, truncate, insert random bytes, nest deeply,
add aliases, swap two lines' values, or drop an indentation, run through `check`. Each run must
- end by itself within 5 s (no hang), with exit code 0 or 1 (no crash, no signal, no 4);
- stay under 500 MB of resident memory;
- on exit 1, name the file; for a content error (any but the file-level ones: unreadable,
  too large, not a regular file), also its line, as FILE:LINE:COLUMN.
Usage: fuzz_check.py UNSATMPM REPO_ROOT [--count N] [--seed S] [--keep DIR]
Exits 1 with the failing mutations listed (and, with --keep, written to DIR).
"""
import argparse
import os
import random
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TIMEOUT_S = 5.0
MAX_RSS_KB = 500 * 1024
FILE_LEVEL = ("cannot open the file", "cannot read the file", "not a regular file",
              "more than a case file's limit", "larger than a case file's limit")


def seeds(root):
    files = sorted((root / "examples").glob("*.yaml")) + sorted(
        (root / "verification").glob("*/case*.yaml"))
    return [(f.relative_to(root).as_posix(), f.read_text()) for f in files]


SCALARS = ["abc", "'1.0'", "-1", "0", "1e308", "-1e308", ".nan", ".inf", "[]", "{}", "[1, 2]",
           "{a: 1}", "true", "~", "!!str 1", "&x 1", "*x", "'", "\"", "18446744073709551617",
           "0x10", "1_000", "2e9", "[2e9, 2e9]", "-0", "null"]


def mutate(text, rng):
    lines = text.split("\n")
    kind = rng.choice(["delete", "duplicate", "retype", "truncate", "bytes", "nesting", "alias",
                       "swap", "indent", "retype", "delete", "number", "number"])
    i = rng.randrange(len(lines))
    if kind == "delete":
        del lines[i]
    elif kind == "duplicate":
        lines.insert(i, lines[i])
    elif kind == "retype":
        value_lines = [k for k, l in enumerate(lines) if re.search(r":\s*\S", l) and
                       not l.lstrip().startswith("#")]
        if value_lines:
            k = rng.choice(value_lines)
            head = lines[k][:lines[k].index(":") + 1]
            lines[k] = head + " " + rng.choice(SCALARS)
    elif kind == "number":  # one number scaled, negated, zeroed or nudged
        numbers = list(re.finditer(r"(?<![\w.])-?\d+(\.\d*)?([eE][-+]?\d+)?", text))
        if numbers:
            m = rng.choice(numbers)
            v = float(m.group(0))
            new = rng.choice([v * 1e-3, v * 1e3, -v, 0.0, v + 1e-7, v * 0.5, v * 2.0, v + 1.0])
            if re.fullmatch(r"-?\d+", m.group(0)) and rng.random() < 0.5:
                new = int(new)
            return kind, text[:m.start()] + repr(new) + text[m.end():]
    elif kind == "truncate":
        return kind, text[:rng.randrange(len(text) + 1)]
    elif kind == "bytes":
        pos = rng.randrange(len(text) + 1)
        junk = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 16)))
        return kind, text[:pos] + junk.decode("latin-1") + text[pos:]
    elif kind == "nesting":
        depth = rng.choice([50, 500, 5000])
        lines.insert(i, "deep: " + "[" * depth + "1" + "]" * depth)
    elif kind == "alias":
        lines.insert(0, "base: &b [1, 2, 3]")
        lines.insert(1, "more: &m [*b, *b, *b, *b, *b, *b, *b, *b]")
        lines.insert(2, "most: [*m, *m, *m, *m, *m, *m, *m, *m]")
    elif kind == "swap":
        j = rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    elif kind == "indent":
        lines[i] = lines[i].lstrip() if lines[i].startswith(" ") else "   " + lines[i]
    return kind, "\n".join(lines)


def run_check(exe, path):
    """Exit status (negative: signal), wall time [s], peak RSS [kB], stderr."""
    def limits():
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))  # a safety net for CI
    with tempfile.TemporaryFile() as err:
        t0 = time.monotonic()
        proc = subprocess.Popen([exe, "check", str(path)], stdout=subprocess.DEVNULL, stderr=err,
                                preexec_fn=limits)
        status, usage, timed_out = None, None, False
        while status is None:
            pid, st, ru = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                status, usage = st, ru
            elif time.monotonic() - t0 > TIMEOUT_S:
                proc.send_signal(signal.SIGKILL)
                _, status, usage = os.wait4(proc.pid, 0)
                timed_out = True
            else:
                time.sleep(0.005)
        proc.returncode = 0  # reaped by wait4
        elapsed = time.monotonic() - t0
        err.seek(0)
        message = err.read().decode("utf-8", "replace")
    code = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
    return code, elapsed, usage.ru_maxrss, message, timed_out


def judge(name, code, elapsed, rss, message, timed_out):
    """The first problem with one run, or None."""
    if timed_out:
        return f"hung (killed after {TIMEOUT_S:g} s)"
    if code not in (0, 1):
        return f"exit {code}: {message.strip()[-300:]}"
    if rss > MAX_RSS_KB:
        return f"{rss / 1024:.0f} MB resident"
    if code == 1:
        if name not in message:
            return f"message does not name the file: {message.strip()[:300]}"
        if not any(s in message for s in FILE_LEVEL) and not re.search(
                re.escape(name) + r":\d+:\d+:", message):
            return f"message has no line: {message.strip()[:300]}"
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("unsatmpm")
    ap.add_argument("root")
    ap.add_argument("--count", type=int, default=330)
    ap.add_argument("--seed", type=int, default=20261124)
    ap.add_argument("--keep")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    corpus = seeds(Path(args.root))
    failures, codes, kinds = [], {0: 0, 1: 0}, {}
    with tempfile.TemporaryDirectory() as work:
        for n in range(args.count):
            seed_name, text = corpus[n % len(corpus)]
            kind, mutated = mutate(text, rng)
            kinds[kind] = kinds.get(kind, 0) + 1
            name = f"fuzz_{n:04d}.yaml"
            path = Path(work) / name
            path.write_bytes(mutated.encode("latin-1", "replace") if kind == "bytes" else
                             mutated.encode("utf-8"))
            code, elapsed, rss, message, timed_out = run_check(args.unsatmpm, path)
            codes[code] = codes.get(code, 0) + 1
            problem = judge(str(path), code, elapsed, rss, message, timed_out)
            if problem:
                failures.append(f"{name} ({kind} of {seed_name}): {problem}")
                if args.keep:
                    Path(args.keep).mkdir(parents=True, exist_ok=True)
                    (Path(args.keep) / name).write_bytes(path.read_bytes())
    print(f"{args.count} mutated cases from {len(corpus)} seeds; mutations: " +
          ", ".join(f"{k} {v}" for k, v in sorted(kinds.items())) + "; exit codes: " +
          ", ".join(f"{k}: {v}" for k, v in sorted(codes.items())))
    for f in failures:
        print("FAIL:", f)
    print(f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

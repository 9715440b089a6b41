#!/usr/bin/env python3
"""The soak of docs/robustness.md ("Soak"): hours of the project's long-running parts, watched.

    ./dev.sh soak [MINUTES]          (builds, then runs this; default 60 minutes)
    python3 tools/soak.py --ibs PATH [--minutes M] [--fuzz-seconds S] [--fuzz-jobs J]
                          [--transactions N] [--out DIR] [--parts bench,campaign,fuzz]

1. A real-time test bench for MINUTES: `ibs run --realtime` of an INTERBUS ring (an MC6000 and a
   VF1000) whose drives also answer on a LUSTBUS pseudo-terminal, with a DFS-1 controller on a
   second line, its control channel on a Unix socket, and `--stats-every 60 s`. This script is the
   traffic: a LUSTBUS host asks the drives without a pause, a DFS-1 host asks the controller every
   second, a control client connects every 15 s with a good line and a bad one (one of the good
   ones a device fault of the servo, once a minute), another stays connected and silent the whole
   run. Each minute (each `ibs-stats:` line) it samples the process's resident memory and open
   descriptors from /proc beside the line's wake-up latency, overruns and counters.
   It fails on growth -- descriptors that are not flat, resident memory that grows more than
   2 MiB + 64 KiB a minute after the first minute (the samples while the run runs; the last one,
   at its end, is the summary's work) -- and on every count the traffic does not
   explain: a LUSTBUS or DFS-1 check error, dropped telegram or unanswered request, a control
   line reported bad that was good or not reported that was bad, an error of a drive other than
   the injected faults, a bus cycle without valid data, an exit other than 0, a socket left.
   Wake-up latency and overruns are reported, not judged: they are the machine's.
2. The fault campaign: `ibs campaign --seed 1 --transactions N` (default 10^7), 0 violations.
3. Every fuzz target for S seconds (default 600), J at a time (default: the cores): fuzz/run.sh,
   no finding.

Prints the per-minute table, the checks and the other two parts' results as Markdown at the end
(the lines to paste into docs/robustness.md), keeps everything in DIR (default build/soak), and
exits 0 only when every check held. The environment variables SOAK_FUZZ_SECONDS, SOAK_FUZZ_JOBS
and SOAK_TRANSACTIONS give the defaults of their options (a short validation run:
`SOAK_FUZZ_SECONDS=5 SOAK_TRANSACTIONS=100000 ./dev.sh soak 3`).
"""
import argparse
import datetime
import json
import os
import platform
import re
import select
import socket
import subprocess
import sys
import termios
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EOT, STX, ETX, ENQ = 0x04, 0x02, 0x03, 0x05


def scenario_text(minutes):
    return f"""# The soak's test bench (tools/soak.py, docs/robustness.md "Soak").
name = "soak"
duration = "{int(minutes * 60)} s"

[[device]]
name = "servo"
type = "mc6000"
supi = 11
ibcnf = 2
watchdog_ms = 100
lustbus = 1

[[device]]
name = "fan"
type = "vf1000"
lustbus = 2

[lustbus]
pty = true
baud = 9600

[dfs1]
pty = true

[[dfs1.controller]]
name = "press"
uid = 7

[[timeline]]
at = "0 s"
device = "servo"
read = 85

[[timeline]]
at = "0 s"
device = "fan"
read = 85

[[timeline]]
at = "0 s"
device = "servo"
state = "enabled"

[[timeline]]
at = "0 s"
device = "servo"
speed = 1500

[[timeline]]
at = "200 ms"
device = "fan"
write = {{ parameter = 1, value = 1 }}

[[timeline]]
at = "1 s"
device = "fan"
state = "enabled"

[[timeline]]
at = "1 s"
device = "fan"
frequency = 25
"""


def open_line(path):
    """The pty raw at 9600 baud, 7E1 (LUSTBUS manual 4), as examples/testbench/test_host.py does."""
    fd = os.open(path, os.O_RDWR | os.O_NOCTTY)
    attrs = termios.tcgetattr(fd)
    attrs[0] = 0
    attrs[1] = 0
    attrs[2] = termios.CS7 | termios.PARENB | termios.CREAD | termios.CLOCAL
    attrs[3] = 0
    attrs[4] = attrs[5] = termios.B9600
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    return fd


def enquiry(fd, address, code):
    """One LUSTBUS ENQUIRY (LUSTBUS manual: EOT ADR CODE ENQ); the VALUE text, or None."""
    adr = 0x40 + address
    os.write(fd, bytes([EOT, adr]) + code.encode() + bytes([ENQ]))
    answer = b""
    deadline = time.monotonic() + 0.5
    while time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
        if not ready:
            break
        answer += os.read(fd, 256)
        if len(answer) >= 2 and answer[-2] == ETX:
            break
    os.write(fd, bytes([EOT]))
    if len(answer) < 5 or answer[0] != adr or answer[1] != STX or answer[-2] != ETX:
        return None
    bcc = 0
    for b in answer[2:-1]:
        bcc ^= b
    if bcc != answer[-1]:
        return None
    return answer[2:-2].decode(errors="replace").split("=", 1)[-1]


def proc_sample(pid):
    """Resident memory (KiB) and open descriptors of `pid`."""
    rss = None
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                rss = int(line.split()[1])
    return rss, len(os.listdir(f"/proc/{pid}/fd"))


class Bench:
    """The bench run and this script's traffic against it."""

    def __init__(self, ibs, minutes, out):
        self.ibs, self.minutes, self.out = ibs, minutes, out
        self.samples = []
        self.stderr_lines = []
        self.sent = {"lustbus": 0, "lustbus_answered": 0, "dfs1": 0, "dfs1_ok": 0, "control_good": 0,
                     "control_bad": 0, "control_clients": 0, "faults": 0, "lustbus_writes": 0, "lustbus_writes_ok": 0}
        self.checks = []
        self.summary = None

    def read_stderr(self, proc):
        for raw in proc.stderr:
            line = raw.rstrip("\n")
            self.stderr_lines.append(line)
            if line.startswith("ibs-stats: "):
                stats = json.loads(line[len("ibs-stats: "):])
                try:
                    stats["rss_kib"], stats["fds"] = proc_sample(proc.pid)
                except (OSError, ValueError):
                    stats["rss_kib"], stats["fds"] = None, None
                self.samples.append(stats)
                print(f"soak: {stats['t_s'] / 60:5.1f} min  rss {stats['rss_kib']} KiB  fds {stats['fds']}  "
                      f"wake p99 {stats['wake_ns']['p99'] / 1000:.0f} us  overruns {stats['overruns']}",
                      flush=True)

    def control(self, sock_path, lines):
        s = socket.socket(socket.AF_UNIX)
        s.connect(sock_path)
        s.sendall("".join(line + "\n" for line in lines).encode())
        s.close()
        self.sent["control_clients"] += 1

    def run(self):
        os.makedirs(self.out, exist_ok=True)
        scenario = os.path.join(self.out, "soak.toml")
        with open(scenario, "w") as f:
            f.write(scenario_text(self.minutes))
        sock_path = os.path.join(self.out, "control.sock")
        if os.path.exists(sock_path):
            os.unlink(sock_path)
        cmd = [self.ibs, "run", "--realtime", scenario, "--control", "unix:" + sock_path, "--stats-every", "60 s",
               "--json", "-q"]
        print("soak: " + " ".join(cmd), flush=True)
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        reader = threading.Thread(target=self.read_stderr, args=(proc,), daemon=True)
        reader.start()
        ports = {}
        while len(ports) < 2:
            line = proc.stdout.readline()
            if not line:
                raise SystemExit("soak: the bench ended before naming its lines: " + "\n".join(self.stderr_lines))
            key, _, path = line.strip().partition(" pty: ")
            ports[key] = path
        lb = open_line(ports["lustbus"])
        idle = socket.socket(socket.AF_UNIX)  # connected the whole run, silent
        for _ in range(100):
            if os.path.exists(sock_path):
                break
            time.sleep(0.05)
        idle.connect(sock_path)
        start = time.monotonic()
        end = start + self.minutes * 60 - 3  # the last seconds: nothing half-sent at the end
        next_dfs1, next_control, next_write, k = start + 1, start + 5, start + 30, 0
        codes = [(1, "20077"), (2, "00012"), (1, "20408"), (2, "00011")]
        while time.monotonic() < end and proc.poll() is None:
            now = time.monotonic()
            if now - start > 2:  # the fan answers once the master has set 1-MODE (INTERBUS manual 6.1)
                address, code = codes[k % len(codes)]
                k += 1
                self.sent["lustbus"] += 1
                if enquiry(lb, address, code) is not None:
                    self.sent["lustbus_answered"] += 1
            if now >= next_write:
                next_write += 30
                self.sent["lustbus_writes"] += 1
                r = subprocess.run([self.ibs, "lustbus", "write", "--port", ports["lustbus"], "--addr", "1",
                                    "--device", "mc6000", "409", "100"], capture_output=True, text=True, timeout=20)
                self.sent["lustbus_writes_ok"] += r.returncode == 0
            if now >= next_dfs1:
                next_dfs1 += 1
                self.sent["dfs1"] += 1
                r = subprocess.run([self.ibs, "dfs1", "status", "--port", ports["dfs1"], "--uid", "7",
                                    "--timeout-ms", "2000"], capture_output=True, text=True, timeout=20)
                self.sent["dfs1_ok"] += r.returncode == 0
            if now >= next_control:
                next_control += 15
                n = self.sent["control_clients"]
                if n % 4 == 3:
                    # A servo fault of 200 ms with its error (E-OP1), then ENABLED again.
                    good = ['{"device": "servo", "fault": "device", "cause": "E-OP1", "duration": "200 ms"}']
                    self.sent["faults"] += 1
                elif n % 4 == 0:
                    good = ['{"device": "servo", "state": "enabled"}']
                elif n % 4 == 1:
                    good = ['{"device": "fan", "frequency": %d}' % (20 + n % 10)]
                else:
                    good = ['{"device": "servo", "read": 409}']
                bad = ['{"device": "servo", "speed": }']
                self.control(sock_path, good + bad)
                self.sent["control_good"] += len(good)
                self.sent["control_bad"] += len(bad)
            time.sleep(0.02)
        os.close(lb)
        # The rest of standard output (the JSON summary) on a thread of its own: standard error stays
        # the reader's, which must see the run's last `ibs-stats:` line.
        rest = []
        tail = threading.Thread(target=lambda: rest.append(proc.stdout.read()), daemon=True)
        tail.start()
        try:
            proc.wait(timeout=120)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
            self.checks.append(("the run ended on time", False, "killed 120 s after its end"))
        tail.join(timeout=30)
        reader.join(timeout=30)
        out = "".join(rest)
        idle.close()
        with open(os.path.join(self.out, "stderr.txt"), "w") as f:
            f.write("\n".join(self.stderr_lines) + "\n")
        with open(os.path.join(self.out, "samples.json"), "w") as f:
            json.dump({"samples": self.samples, "sent": self.sent}, f, indent=1)
        self.judge(proc.returncode, out, sock_path)

    def judge(self, rc, out, sock_path):
        c = self.checks
        c.append(("exit 0", rc == 0, f"exit {rc}"))
        c.append(("socket removed", not os.path.exists(sock_path), sock_path))
        try:
            self.summary = json.loads(out)
        except ValueError:
            c.append(("JSON summary", False, out[:200]))
            return
        s = self.summary
        bus = s.get("bus", {})
        cycles, valid = bus.get("cycles"), bus.get("valid_cycles")
        c.append(("every bus cycle valid", cycles is not None and cycles == valid, f"{valid} of {cycles}"))
        c.append(("a sample every minute", len(self.samples) >= max(1, int(self.minutes)),
                  f"{len(self.samples)} samples in {self.minutes} min"))
        # Growth: the samples taken while the run ran (not its last, at its end, when it builds its
        # summary).
        samples = [x for x in self.samples if x.get("rss_kib") is not None and not x.get("last")]
        if samples:
            fds = [x["fds"] for x in samples]
            c.append(("descriptors flat", len(set(fds)) == 1, f"{fds[0]} .. {fds[-1]} (min {min(fds)}, max {max(fds)})"))
            first, last = samples[0]["rss_kib"], samples[-1]["rss_kib"]
            allowed = 2048 + 64 * max(0.0, self.minutes - 1)
            c.append(("resident memory flat", last - first <= allowed,
                      f"{first} -> {last} KiB after the first minute (+{last - first} KiB, allowed {allowed:.0f})"))
        # The traffic's counts against the drives', the controllers' and the channel's.
        bench = {d["name"]: d for d in s.get("bench", {}).get("devices", [])}
        for name in ("servo", "fan", "press"):
            d = bench.get(name, {})
            c.append((f"{name}: no check error, nothing dropped", d.get("errors") == 0 and d.get("dropped") == 0,
                      f"{d.get('telegrams')} telegrams, {d.get('answers')} answers, {d.get('errors')} errors, "
                      f"{d.get('dropped')} dropped"))
        sent = self.sent
        c.append(("every LUSTBUS enquiry answered", sent["lustbus"] == sent["lustbus_answered"],
                  f"{sent['lustbus_answered']} of {sent['lustbus']}"))
        c.append(("every LUSTBUS write acknowledged", sent["lustbus_writes"] == sent["lustbus_writes_ok"],
                  f"{sent['lustbus_writes_ok']} of {sent['lustbus_writes']}"))
        c.append(("every DFS-1 status answered", sent["dfs1"] == sent["dfs1_ok"], f"{sent['dfs1_ok']} of {sent['dfs1']}"))
        reported_bad = sum(1 for line in self.stderr_lines if re.match(r"control:\d+:\d+: ", line))
        c.append(("every bad control line reported", reported_bad == sent["control_bad"],
                  f"{reported_bad} reported, {sent['control_bad']} sent"))
        applied = [e for e in s.get("events", []) if e.get("type") == "control"]
        c.append(("every good control line applied", len(applied) == sent["control_good"],
                  f"{len(applied)} applied, {sent['control_good']} sent"))
        errors = [e for d in s.get("devices", []) for e in d.get("errors", [])]
        injected = [e for e in errors if "device fault injected" in e]
        c.append(("no drive error but the injected faults", len(errors) == len(injected) == sent["faults"],
                  f"{len(errors)} errors, {len(injected)} injected, {sent['faults']} sent"))

    def table(self):
        rows = ["| minute | RSS KiB | fds | wake p50 us | p99 us | p99.9 us | max us | overruns | cycles | "
                "LUSTBUS telegrams (servo/fan) | DFS-1 requests | control lines | check errors |",
                "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: |"]
        for x in self.samples:
            b = {d["name"]: d for d in x.get("bench", [])}
            errors = sum(d["errors"] + d["dropped"] for d in x.get("bench", []))
            w = x["wake_ns"]
            minute = f"{x['t_s'] / 60:.0f}" + (" (end)" if x.get("last") else "")
            rows.append(f"| {minute} | {x['rss_kib']} | {x['fds']} | {w['p50'] / 1000:.0f} | "
                        f"{w['p99'] / 1000:.0f} | {w['p999'] / 1000:.0f} | {w['max'] / 1000:.0f} | {x['overruns']} | "
                        f"{x['cycles']} | {b.get('servo', {}).get('telegrams')}/{b.get('fan', {}).get('telegrams')} | "
                        f"{b.get('press', {}).get('telegrams')} | {x.get('control', {}).get('lines')} | {errors} |")
        return "\n".join(rows)


def run_campaign(ibs, transactions, out):
    start = time.monotonic()
    r = subprocess.run([ibs, "campaign", "--seed", "1", "--transactions", str(transactions), "--json", "-q"],
                       capture_output=True, text=True)
    wall = time.monotonic() - start
    with open(os.path.join(out, "campaign.json"), "w") as f:
        f.write(r.stdout)
    try:
        j = json.loads(r.stdout)
    except ValueError:
        j = {}
    violations = j.get("violation_count")
    total = j.get("transactions", {}).get("total")
    simulated = j.get("simulated_s")
    ok = r.returncode == 0 and violations == 0 and total is not None and total >= transactions
    line = (f"`ibs campaign --seed 1 --transactions {transactions}`: exit {r.returncode}, {total} transactions, "
            f"{violations} violations, {simulated} s simulated in {wall:.1f} s wall time")
    return ok, line


def run_fuzz(seconds, jobs, out):
    start = time.monotonic()
    r = subprocess.run([os.path.join(ROOT, "fuzz", "run.sh"), "--jobs", str(jobs), str(seconds)],
                       capture_output=True, text=True, cwd=ROOT)
    wall = time.monotonic() - start
    with open(os.path.join(out, "fuzz.txt"), "w") as f:
        f.write(r.stdout + r.stderr)
    rows = ["| target | executions | cov | ft | corpus | findings |", "| --- | ---: | ---: | ---: | --- | --- |"]
    pattern = re.compile(r"^(\S+)\s+(\S+) execs\s+cov\s+(\S+)\s+ft\s+(\S+)\s+corpus\s+(\S+) -> (\S+)\s+(.*)$")
    targets = 0
    for line in r.stdout.splitlines():
        m = pattern.match(line)
        if m:
            targets += 1
            rows.append(f"| `{m.group(1)}` | {m.group(2)} | {m.group(3)} | {m.group(4)} | {m.group(5)} -> {m.group(6)} | "
                        f"{m.group(7).replace('no findings', 'none')} |")
    ok = r.returncode == 0 and targets > 0
    return ok, f"{targets} targets, {seconds} s each, {jobs} at a time, {wall / 60:.1f} min wall time, exit {r.returncode}", \
        "\n".join(rows)


def machine():
    cpu = platform.processor() or "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{platform.system()} {platform.release()}, {cpu}, {os.cpu_count()} cores"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--ibs", required=True)
    p.add_argument("--minutes", type=float, default=60.0)
    p.add_argument("--fuzz-seconds", type=int, default=int(os.environ.get("SOAK_FUZZ_SECONDS", "600")))
    p.add_argument("--fuzz-jobs", type=int, default=int(os.environ.get("SOAK_FUZZ_JOBS", str(os.cpu_count() or 1))))
    p.add_argument("--transactions", type=int, default=int(os.environ.get("SOAK_TRANSACTIONS", "10000000")))
    p.add_argument("--out", default=os.path.join(ROOT, "build", "soak"))
    p.add_argument("--parts", default="bench,campaign,fuzz",
                   help="the parts to run, comma-separated (default: bench,campaign,fuzz)")
    a = p.parse_args()
    parts = set(a.parts.split(","))
    if not parts <= {"bench", "campaign", "fuzz"}:
        raise SystemExit("soak: --parts takes bench, campaign and fuzz")
    if a.minutes < 1:
        raise SystemExit("soak: MINUTES must be at least 1")
    os.makedirs(a.out, exist_ok=True)
    started = datetime.datetime.now(datetime.timezone.utc)
    bench = Bench(a.ibs, a.minutes, a.out)
    if "bench" in parts:
        bench.run()
    campaign_ok, campaign_line = True, "not run"
    if "campaign" in parts:
        print(f"soak: the campaign, {a.transactions} transactions", flush=True)
        campaign_ok, campaign_line = run_campaign(a.ibs, a.transactions, a.out)
    fuzz_ok, fuzz_line, fuzz_table = True, "not run", ""
    if "fuzz" in parts:
        print(f"soak: every fuzz target for {a.fuzz_seconds} s, {a.fuzz_jobs} at a time", flush=True)
        fuzz_ok, fuzz_line, fuzz_table = run_fuzz(a.fuzz_seconds, a.fuzz_jobs, a.out)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT).stdout.strip()
    ok = all(c[1] for c in bench.checks) and campaign_ok and fuzz_ok
    report = [
        f"### Soak of {started:%Y-%m-%d} ({a.minutes:g} minutes)",
        "",
        f"`./dev.sh soak {a.minutes:g}` on {machine()}, commit {commit}, started {started:%Y-%m-%d %H:%M} UTC: "
        f"**{'passed' if ok else 'FAILED'}**.",
        "",
        "The test bench, one line a minute (`ibs-stats:` lines; RSS and descriptors from /proc):",
        "",
        bench.table(),
        "",
        "| check | held | figures |",
        "| --- | --- | --- |",
    ]
    report += [f"| {name} | {'yes' if held else '**no**'} | {figures} |" for name, held, figures in bench.checks]
    report += ["", f"Campaign: {campaign_line}{'' if campaign_ok else ' **FAILED**'}.", "",
               f"Fuzzing: {fuzz_line}{'' if fuzz_ok else ' **FAILED**'}.", "", fuzz_table, ""]
    text = "\n".join(report)
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write(text)
    print("\n" + text)
    print(f"soak: {'passed' if ok else 'FAILED'}; everything is in {a.out}", flush=True)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""A user's own host test against the ibs test bench (docs/testbench.md).

It is written the way a test engineer would test their own LUSTBUS host software: standard
library only. It starts the bench (`ibs run --realtime bench.toml --json`), waits for the line
that names the pseudo-terminal, and then talks to the emulated drives there -- byte by byte, as
the host software under test would (LUSTBUS manual: EOT ADR CODE ENQ, the answer ADR STX CODE=VALUE
ETX BCC) -- and through `ibs lustbus read`, while ibs's INTERBUS master runs the same drives. At
the end it reads the run's JSON summary.

    python3 examples/testbench/test_host.py [PATH-TO-IBS]

PATH-TO-IBS defaults to the environment's IBS, then to `ibs` on the PATH. Exit 0 when every
check holds; unittest's report otherwise.
"""
import json
import os
import select
import subprocess
import sys
import termios
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
IBS = os.environ.get("IBS", "ibs")

EOT, STX, ETX, ENQ, NAK = 0x04, 0x02, 0x03, 0x05, 0x15


def open_line(path):
    """The pty (or a real RS-485 port) raw at 9600 baud, 7E1 (LUSTBUS manual 4)."""
    fd = os.open(path, os.O_RDWR | os.O_NOCTTY)
    attrs = termios.tcgetattr(fd)
    attrs[0] = 0                                                             # iflag: raw
    attrs[1] = 0                                                             # oflag
    attrs[2] = termios.CS7 | termios.PARENB | termios.CREAD | termios.CLOCAL  # cflag: 7E1
    attrs[3] = 0                                                             # lflag: no echo
    attrs[4] = attrs[5] = termios.B9600
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    return fd


def read_for(fd, seconds):
    """What arrives within `seconds`."""
    out = b""
    deadline = time.monotonic() + seconds
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return out
        ready, _, _ = select.select([fd], [], [], left)
        if not ready:
            return out
        out += os.read(fd, 256)
        if len(out) >= 2 and out[-2] == ETX:
            return out  # a whole text answer: ... ETX BCC


def enquiry(fd, address, code):
    """Reads one parameter: the VALUE as text, or None (NAK or no answer)."""
    adr = 0x40 + address
    os.write(fd, bytes([EOT, adr]) + code.encode() + bytes([ENQ]))
    answer = read_for(fd, 0.5)
    os.write(fd, bytes([EOT]))  # the host ends every sequence with EOT
    if len(answer) < 5 or answer[0] != adr or answer[1] != STX or answer[-2] != ETX:
        return None
    bcc = 0
    for b in answer[2:-1]:  # everything after STX up to and including ETX
        bcc ^= b
    if bcc != answer[-1]:
        raise AssertionError("BCC %02X, should be %02X: %r" % (answer[-1], bcc, answer))
    text = answer[2:-2].decode()
    got_code, value = text.split("=", 1)
    assert got_code == code, (got_code, code)
    return value


def poll(fd, address, code, ok, seconds):
    """Reads until ok(value) or the time is up; the last value read."""
    deadline = time.monotonic() + seconds
    value = None
    while time.monotonic() < deadline:
        value = enquiry(fd, address, code)
        if value is not None and ok(value):
            return value
        time.sleep(0.05)
    return value


class TestMyHostAgainstTheBench(unittest.TestCase):
    def test_drives_on_both_buses(self):
        bench = subprocess.Popen(
            [IBS, "run", "--realtime", os.path.join(HERE, "bench.toml"), "--json"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            # The first line names the pty, before the run starts.
            first = bench.stdout.readline().strip()
            self.assertTrue(first.startswith("lustbus pty: "), first)
            pty = first[len("lustbus pty: "):]
            fd = open_line(pty)
            try:
                # 77-SPEED of the servo (address 1; 000 2.4.2 CODE 20077), Q16 rpm in hex: the
                # speed the INTERBUS master commanded.
                speed = poll(fd, 1, "20077", lambda v: int(v, 16) >> 16 == 1500, 3.0)
                self.assertIsNotNone(speed, "the servo never answered")
                self.assertEqual(int(speed, 16) >> 16, 1500)
                # The fan (address 2) answers once the master has written 1-MODE = 1 (INTERBUS manual,
                # 6.1) and runs at 25 Hz: 12-FOUT in 0.05 Hz (000 2.4.1 CODE 00012).
                fout = poll(fd, 2, "00012", lambda v: int(v, 16) == 500, 4.0)
                self.assertEqual(fout is not None and int(fout, 16), 500, fout)
                # The same through an unmodified client: ibs's own host command.
                read = subprocess.run(
                    [IBS, "lustbus", "read", "--port", pty, "--addr", "2", "--device", "vf1000",
                     "--json", "FOUT"], capture_output=True, text=True, timeout=10)
                self.assertEqual(read.returncode, 0, read.stderr)
                self.assertEqual(json.loads(read.stdout)["raw"], 500, read.stdout)
                # The fault injected at 4 s shows in the servo's status word (408-IBSTA, bit 3).
                status = poll(fd, 1, "20408", lambda v: int(v, 16) & 0x0008, 5.0)
                self.assertTrue(status is not None and int(status, 16) & 0x0008, status)
            finally:
                os.close(fd)
            out, err = bench.communicate(timeout=30)
        finally:
            if bench.poll() is None:
                bench.kill()
                bench.wait()
        self.assertEqual(bench.returncode, 0, err)
        summary = json.loads(out)
        servo = next(d for d in summary["devices"] if d["name"] == "servo")
        self.assertIn("FAULT", [s["what"] for s in servo["states"]])
        self.assertIn("overruns", summary["bus"]["realtime"])
        served = {d["name"]: d for d in summary["bench"]["devices"]}
        self.assertGreater(served["servo"]["answers"], 0)
        self.assertGreater(served["fan"]["answers"], 0)
        self.assertEqual(served["servo"]["errors"], 0)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        IBS = sys.argv.pop(1)
    unittest.main()

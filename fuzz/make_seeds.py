#!/usr/bin/env python3
"""Writes the seed corpora of fuzz/corpus/ (docs/robustness.md, "Fuzzing").

The seeds are the project's own data -- the manuals' tables in tests/data/*.trace, the example
scenarios -- and short hand-made inputs in each target's input format (see the comment at the top
of each fuzz/<target>.cpp; integers are big-endian, read front to back). Run it again after
changing a format or adding a trace; it replaces every seed it writes and leaves other files alone.

    python3 fuzz/make_seeds.py
"""
import pathlib
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"


def u16(*ws):
    return b"".join(struct.pack(">H", w & 0xFFFF) for w in ws)


def put(target, name, data):
    d = CORPUS / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data)


def read_trace(path):
    """Headers and rows (m2s words, s2m words) of an ibs-trace 1 file."""
    headers, rows = {}, []
    for line in path.read_text().splitlines():
        line = line.strip()
        if line.startswith("#"):
            body = line[1:].strip()
            key, sep, value = body.partition(":")
            if sep and " " not in key:
                headers.setdefault(key, value.strip())
            continue
        if not line or line.startswith("!") or line == "...":
            continue
        fields = [f.strip() for f in line.split(",")]
        rows.append(([int(w.split("/")[0].replace("?", "0"), 16) for w in fields[1].split()],
                     [int(w.split("/")[0].replace("?", "0"), 16) for w in fields[2].split()]))
    return headers, rows


def number(text):
    return int(text, 0)


def traces(pattern):
    return sorted((ROOT / "tests" / "data").glob(pattern))


# --- trace_fuzz: the manuals' tables as they are, and a few broken ones ------------------------
for p in traces("*.trace"):
    put("trace_fuzz", p.name, p.read_bytes())
put("trace_fuzz", "gap_max_gap.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# max-gap: 5\n"
    b"0, 0000, 8000\n...\n7, 0000, 8000\n")
put("trace_fuzz", "max_gap_huge.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n"
    b"# max-gap: 1000000000000\n0, 0000, 8000\n...\n7, 0000, 1234\n")
put("trace_fuzz", "short_row_pd.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: pd\n"
    b"0, 0000, 0240\n1, 0006, 0231\n")
put("trace_fuzz", "pcp_state_request.trace", b"# format: ibs-trace 1\n# device: mc6000\n# words: pcp\n# supi: 3\n"
    b"# ibcnf: 0\n# request: state enabled\n# outcome: ok\n0, 0E00 0000 0000 0000, 8F00 0000 0000 0000\n"
    b"1, 0E00 0000 0000 0000, 9700 0000 0000 0000\n2, 0100 0000 0000 0000, 8000 0000 0000 0000\n")
put("trace_fuzz", "events.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: pd\n# init: operational\n"
    b"# request: state enabled\n0, 0000 0000 0000, 0240 0000 8000\n! fault\n1, 0006 0000 0000, 0208 0000 8000\n"
    b"! fault-cleared\n2, 0086 0000 0000, 0231 0000 8000\n")
put("trace_fuzz", "no_data_watchdog.trace", b"# format: ibs-trace 1\n# device: mc6000\n# words: pd\n# supi: 11\n"
    b"# ibcnf: 2\n# watchdog_ms: 5\n# step-time: 1 ms\n# init: operational\n0, 0000 0000 0000, 0240 0000 0000\n"
    b"! no-data 3 corrupted cycles\n4, 0000 0000 0000, 0240 0000 0000\n! fault\n! no-data 4\n"
    b"9, 0000 0000 0000, 0240 0000 0000\n")
put("trace_fuzz", "step_time_vf1000.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: pd\n# watchdog_ms: 200\n"
    b"# step-time: 8.2 ms\n0, 0000 0000 0000, 0240 0000 8000\n! no-data 30\n31, 0000 0000 0000, 0240 0000 8000\n")
put("trace_fuzz", "settings_and_writes.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: pd\n"
    b"# watchdog_ms: 100\n# step-time: 8.2 ms\n# setting: watchdog_reaction 1\n# setting: keypad true\n"
    b"# setting: reset_time \"2 s\"\n# init: operational\n0, 0000 0000 0000, 0240 0000 8000\n! write 85 0\n"
    b"! write 22 1000 over LUSTBUS\n1, 0000 0000 0000, 0240 0000 8000\n! no-data 20\n"
    b"22, 0000 0000 0000, 0208 0000 8000\n")
put("trace_fuzz", "comm_step_time.trace", b"# format: ibs-trace 1\n# device: vf1000\n# words: comm\n# step-time: 726 us\n"
    b"# request: read 0x16\n0, 0000, 8000\n1, 2416, 8000\n2, 2416, A003\n")

# --- scenario_fuzz: byte 0 = format (bit 0 JSON, bit 1 also parse_time), then the file -----------
for p in sorted((ROOT / "examples").glob("*")):
    if p.suffix == ".toml":
        put("scenario_fuzz", p.name, b"\x00" + p.read_bytes())
    elif p.suffix == ".json":
        put("scenario_fuzz", p.name, b"\x01" + p.read_bytes())
put("scenario_fuzz", "minimal.toml", b"\x00duration = \"10 ms\"\n[[device]]\nname = \"a\"\ntype = \"vf1000\"\n")
put("scenario_fuzz", "minimal.json", b"\x01{\"duration\": \"10 ms\", \"device\": [{\"name\": \"m\", \"type\": \"mc6000\", "
    b"\"supi\": 3, \"ibcnf\": 0}]}\n")
put("scenario_fuzz", "timeline.toml", b"\x00name = \"t\"\nduration = \"30 ms\"\n[bus]\ncycle_time = \"1 ms\"\n"
    b"[[device]]\nname = \"m\"\ntype = \"mc6000\"\n[[timeline]]\nat = \"0 s\"\ndevice = \"m\"\nstate = \"enabled\"\n"
    b"[[timeline]]\nat = \"5 ms\"\ndevice = \"m\"\nwrite = { parameter = 428, value = 65536 }\n"
    b"[[timeline]]\nat = \"6 ms\"\nfault = \"corrupt\"\ncount = 3\n[random_faults]\nseed = 7\ncorrupt_per_s = 100\n")
for i, t in enumerate([b"250 ms", b"8.2 ms", b"726us", b"1.5 s", b"100 ns", b"0 s"]):
    put("scenario_fuzz", f"time_{i}", b"\x02" + t)

# --- pcp_pdu_fuzz: PMS messages of docs/pcp.md -------------------------------------------------
pdus = {
    "initiate_req": u16(0x008B, 0x0008, 0x0002, 0x0000, 0x0000, 0x0086, 0x0086, 0x0403, 0x0000, 0x0000),
    "initiate_conf": u16(0x808B, 0x0007, 0x0002, 0x0000, 0x0086, 0x0086, 0x0000, 0x0004, 0x0304),
    "initiate_conf_neg": u16(0x808B, 0x0008, 0x0002, 0x0800, 0x0000, 0x0086, 0x0086, 0x0000, 0x0004, 0x0304),
    "read_req": u16(0x0081, 0x0003, 0x0102, 0x5DAC, 0x0000),
    "read_conf": u16(0x8081, 0x0005, 0x0102, 0x0000, 0x0004, 0x0084, 0x2666),
    "write_req": u16(0x0082, 0x0005, 0x0202, 0x5DAC, 0x0004, 0x0084, 0x2666),
    "write_req_u8": u16(0x0082, 0x0004, 0x0202, 0x5C04, 0x0001, 0x0100),
    "write_conf": u16(0x8082, 0x0002, 0x0202, 0x0000),
    "write_conf_neg": u16(0x8082, 0x0003, 0x0202, 0x0800, 0x0020),
    "get_ov_req": u16(0x0088, 0x0002, 0x0302, 0x5DAC),
    "identify_req": u16(0x0087, 0x0001, 0x0402),
    "status_req": u16(0x0086, 0x0001, 0x0502),
    "status_conf": u16(0x8086, 0x0004, 0x0502, 0x0000, 0x0001, 0x0001),
    "abort": u16(0x088D, 0x0002, 0x0002, 0x0002),
    "info_report": u16(0x0085, 0x0004, 0x0002, 0x5D98, 0x0002, 0x0237),
    "value_usign16": bytes([2, 0x12, 0x34]),
    "value_int32q16": bytes([5, 0x00, 0x84, 0x26, 0x66]),
}
for name, b in pdus.items():
    put("pcp_pdu_fuzz", name, b)

# --- pcp_link_fuzz: byte 0 bit 0 = mode (0 one link, 1 two links) -----------------------------
WIDTH = {1: 0, 2: 1, 4: 2}  # header byte % 3
for p in traces("mc6000_pcp_*.trace"):
    h, rows = read_trace(p)
    words = len(rows[0][1])
    ready = 0x20 if h.get("init", "operational") != "power-on" else 0
    # A master-side link (direction to_server) fed the servo's frames, 1 ms per cycle.
    data = bytes([0x00, WIDTH[words] | ready, 100])
    for _, s2m in rows:
        data += bytes([0x02]) + u16(*s2m)
    put("pcp_link_fuzz", "single_" + p.stem, data)
for words in (1, 2, 4):
    # Two links: each cycle op (faults, time), where, act (send master / servo); PDUs made from input.
    data = bytes([0x01, WIDTH[words] | 0x10, 80])               # links start ready
    data += bytes([0x00, 0x00, 0x01, 0x00]) + bytes(range(6))   # a master PDU of 1 count word
    data += bytes([0x00, 0x00, 0x00]) * 40
    data += bytes([0x00, 0x00, 0x02, 0x01]) + bytes(range(8))   # a servo PDU of 2 count words
    data += bytes([0x05, 0x07, 0x00]) * 60  # lost and repeated cycles
    put("pcp_link_fuzz", f"pair_{words}words", data)

# --- pcp_server_fuzz / pcp_client_fuzz --------------------------------------------------------
IDLE = bytes([0x01])  # one cycle of 1 ms, no action
for p in traces("mc6000_pcp_*.trace"):
    h, rows = read_trace(p)
    words = len(rows[0][0])
    running = 0x04 if h.get("init", "operational") != "power-on" else 0
    # The servo fed the trace's master frames as raw words (op bit 2), 1 ms a cycle.
    data = bytes([WIDTH[words] | running, 0, 100])
    for m2s, _ in rows:
        data += bytes([0x05]) + u16(*m2s)
    put("pcp_server_fuzz", "raw_" + p.stem, data)
    # The client fed the trace's servo frames as raw words.
    data = bytes([WIDTH[words] | running, 200, 100])
    req = h.get("request", "read 428").split()
    kinds = {"read": 1, "write": 3, "describe": 4}
    data += bytes([0x01 | (1 << 3), 0, 0xE0]) + u16(0x5C00) + bytes([0])  # Initiate first
    for m2s, s2m in rows:
        data += bytes([0x05]) + u16(*s2m)
    put("pcp_client_fuzz", "raw_" + p.stem, data)

# Through the master-side link: Initiate, Write 428, Read 428, Get-OV 407, SERR read, PROG = 1.
TABLE = [4, 15, 77, 80, 81, 82, 83, 84, 85, 91, 107, 108, 300, 402, 405, 406, 407, 408, 409, 416, 417,
         418, 419, 420, 428, 439, 440, 443, 444, 445, 446]
SEND = 0x01 | (1 << 3)


def server_request(kind, *rest):
    return bytes([SEND, kind, 0x00]) + bytes(rest)


for words in (1, 2, 4):
    data = bytes([WIDTH[words] | 0x04, 0, 100])
    data += server_request(0, 0x01) + IDLE * 120                                     # Initiate, password
    data += server_request(1, TABLE.index(428), 0x00, 0x00, 0x00, 0x84, 0x26, 0x66) + IDLE * 120
    data += server_request(2, TABLE.index(428)) + IDLE * 120                         # Read 428
    data += server_request(3, TABLE.index(407)) + IDLE * 160                         # Get-OV 407
    data += server_request(1, TABLE.index(82), 0x00, 0x00, 0x00, 0x05) + IDLE * 120  # EEPROM 82 = 5
    data += server_request(1, TABLE.index(80), 0x00, 0x00, 0xFF, 0xFF) + IDLE * 120  # SLOAD -1
    data += server_request(1, TABLE.index(80), 0x00, 0x00, 0xFF, 0xFE) + IDLE * 120  # SLOAD -2
    data += bytes([0x03, 200]) * 3                                                   # 600 ms
    data += server_request(2, TABLE.index(85)) + IDLE * 120                          # Read SERR
    data += server_request(1, TABLE.index(4), 0x00, 0x00, 0x01) + IDLE * 60          # PROG = 1
    put("pcp_server_fuzz", f"services_{words}words", data)
    data = bytes([WIDTH[words] | 0x08, 0, 100])                                     # power-on, latency
    data += server_request(1, TABLE.index(428), 0x00, 0x00, 0x00, 0x00, 0x00, 0x01) + IDLE * 120
    data += server_request(0, 0x01) + IDLE * 120
    data += server_request(2, TABLE.index(85)) + IDLE * 150
    data += server_request(1, TABLE.index(428), 0x00, 0x00, 0x00, 0x00, 0x00, 0x01) + IDLE * 150
    data += bytes([0x01 | (4 << 3)]) + IDLE * 60                                     # power-on
    put("pcp_server_fuzz", f"power_on_{words}words", data)


def client_submit(kind, pb, tb, *rest):
    return bytes([0x01 | (1 << 3), kind, pb, tb]) + bytes(rest)


for words in (1, 2, 4):
    data = bytes([WIDTH[words] | 0x04, 200, 100])
    data += client_submit(0, 0, 0) + IDLE * 120                                    # Initiate
    data += client_submit(2, TABLE.index(428), 0, 5) + IDLE * 120                  # typed Read INT32Q16
    data += client_submit(3, TABLE.index(428), 0, 5, 0x00, 0x84, 0x26, 0x66) + IDLE * 120
    data += client_submit(4, TABLE.index(407), 0) + IDLE * 160                     # Get-OV
    data += client_submit(5, 0, 0) + IDLE * 120                                    # Identify
    data += client_submit(6, 0, 0) + IDLE * 120                                    # Status
    data += bytes([0x09, 1, 0xF0]) + u16(0x1234) + bytes([0x90]) + IDLE * 120      # Read of no object
    data += client_submit(1, TABLE.index(85), 0) + bytes([0x01 | (5 << 3)]) + IDLE * 30  # Read, abort
    data += client_submit(0, 0, 0) + IDLE * 5 + bytes([0x01 | (6 << 3)]) + IDLE * 200    # servo restart
    put("pcp_client_fuzz", f"services_{words}words", data)

# --- vf1000_server_fuzz / vf1000_client_fuzz: the cycle tables of 4.1.3 ----------------------
for p in traces("vf1000_comm_*.trace"):
    h, rows = read_trace(p)
    start = {"power-on": 1, "operational": 2, "fault": 2}[h.get("init", "operational")]
    # The inverter fed the master's words, one step of 16.4 ms per row (control byte 2: 33 ms).
    data = bytes([start, 0])
    for m2s, _ in rows:
        data += bytes([0x02]) + u16(m2s[0])
    put("vf1000_server_fuzz", p.stem, data)
    # The master fed the inverter's words, with the trace's request submitted at step 0.
    req = h["request"].split()
    kind = {"read": 0, "write": 1, "describe": 2}[req[0]]
    value = number(req[2]) if len(req) > 2 else 0
    data = bytes([255, 100, 4, 1])
    data += bytes([0x01 | (4 << 2), kind]) + u16(number(req[1]), value) + bytes([0]) + u16(rows[0][1][0])
    for _, s2m in rows[1:]:
        data += bytes([0x01]) + u16(s2m[0])
    put("vf1000_client_fuzz", p.stem, data)
# A transfer whose 85-SIOF becomes non-zero after the parameter number (a watchdog bit, 02H).
put("vf1000_server_fuzz", "siof_after_pnr", bytes([2, 0]) + bytes([0x02]) + u16(0x0000) + bytes([0x02]) + u16(0x2816)
    + bytes([0x0A]) + u16(0x0801) + bytes([0x02]) + bytes([0x02]) + u16(0x28F4) + bytes([0x02]) + u16(0x0000))
# Power stage on during an EEPROM transfer; CODE 0 in the middle; a power cycle.
put("vf1000_server_fuzz", "eeprom_power_stage", bytes([2, 50]) + bytes([0x02]) + u16(0x2816) + bytes([0x06]) + u16(0x0801)
    + bytes([0x06]) + u16(0x28F4) + bytes([0x02]) + u16(0x0000) + bytes([0x12]) + u16(0x2455) + bytes([0x03])
    + u16(0x2455) + bytes([60, 0x02]) + u16(0x0455))

# --- drivecom_device_fuzz: [exit/initial state] then [control word, inputs, device bits] -------
OK = 0x0D  # initialised, reaction done, stopped
put("drivecom_device_fuzz", "startup_5_3_4", bytes([0x00]) + b"".join(u16(c) + bytes([OK, 0x04])
                                                                       for c in (0x0000, 0x0006, 0x000F, 0x000F)))
put("drivecom_device_fuzz", "vf1000_stop_ramp", bytes([0x03]) + b"".join(u16(c) + bytes([f, 0x04]) for c, f in
    ((0x0006, OK), (0x007F, OK), (0x000B, 0x05), (0x000B, OK), (0x0000, OK))))
put("drivecom_device_fuzz", "fault_reset", bytes([0x08]) + b"".join(u16(c) + bytes([f, 0]) for c, f in
    ((0x000F, 0x0B), (0x000F, 0x0F), (0x0000, OK), (0x0086, OK), (0x0006, OK), (0x0086, 0x0F), (0x0006, OK), (0x0086, OK))))
put("drivecom_device_fuzz", "enable_locked", bytes([0x00]) + b"".join(u16(c) + bytes([f, 0x04]) for c, f in
    ((0x0006, OK), (0x000F, OK | 0x40), (0x000F, OK | 0x40), (0x000F, OK), (0x000F, OK | 0x40))))
put("drivecom_device_fuzz", "power_on_force", bytes([0x0E]) + u16(0x000F) + bytes([0x1D, 0]) + u16(0x000F)
    + bytes([0x2D, 0x04]) + u16(0x0002) + bytes([OK, 0x7F]))

# --- sequencer_fuzz: [mode][timeouts][pulse][app bits] then [event, status word, time step us] --
NONE, REQ_ENABLED, REQ_READY = 0xF0, 0x03, 0x01


def cycles(*items):
    return b"".join(bytes([e]) + u16(s, dt) for e, s, dt in items)


put("sequencer_fuzz", "startup", bytes([0x00]) + u16(0x0000) + cycles(
    (REQ_ENABLED, 0x0240, 1000), (NONE, 0x0231, 1000), (NONE, 0x0237, 1000), (NONE, 0x0637, 1000), (0x30, 0x0637, 1000),
    (NONE, 0x0217, 1000), (0x40, 0x0217, 1000), (NONE, 0x0240, 1000)))
put("sequencer_fuzz", "fault_covered", bytes([0x02, 20]) + u16(0x0070) + cycles(
    (REQ_ENABLED, 0x0208, 8200), (NONE, 0x0208, 8200), (NONE, 0x0208, 30000), (NONE, 0x0208, 30000),
    (NONE, 0x0240, 8200), (NONE, 0x0231, 8200), (NONE, 0x0237, 8200), (NONE, 0x0208, 8200), (NONE, 0x0208, 8200)))
put("sequencer_fuzz", "timeouts_restart", bytes([0x01]) + bytes([5] * 16) + u16(0xF870) + cycles(
    (REQ_READY, 0x0240, 1000), (NONE, 0x0240, 6000), (NONE, 0x0001, 1000), (0x50, 0x0231, 1000))
    + bytes([0x60]) + u16(0x1234, 0x0240, 0) + cycles((0x02, 0x0231, 1000), (NONE, 0x0233, 1000), (0x00, 0x0233, 1000)))

# --- cut frames (issue 23): a host that dies mid-telegram, the next host after the silence -------
# lustbus_fuzz reads its integers with libFuzzer's FuzzedDataProvider, which takes them from the
# END of the input: the values are listed in the order the target consumes them and reversed.
def fdp_from_end(*values):
    out = []
    for v, size in values:
        out += list(v.to_bytes(size, "big"))  # the first byte consumed is the most significant
    return bytes(reversed(out))


EOT, STX, ETX, ENQ = 0x04, 0x02, 0x03, 0x05


def lustbus_receiver(own, chars):
    """chars: (byte, gap) pairs; gap >= 60000 is a silence of gap - 60000 ms (fuzz/lustbus_fuzz.cpp).
    A (byte, gap, answer_bool) triple is a character that completes a telegram; its Responder
    call takes one bool (true: NAK) before the gap."""
    values = [(1, 1), (own, 1)]
    for c in chars:
        values.append((c[0], 1))
        if len(c) == 3:
            values.append((c[2], 1))
        values.append((c[1], 2))
    return fdp_from_end(*values)


ADR5 = 0x40 + 5
dead_select = [EOT, ADR5, STX] + list(b"00005=0068") + [ETX]  # without its BCC: the host died
next_enquiry = [EOT, ADR5] + list(b"00112")
put("lustbus_fuzz", "receiver_cut_select_then_enquiry", lustbus_receiver(
    5, [(b, 0) for b in dead_select[:-1]] + [(dead_select[-1], 60000 + 100)]
    + [(b, 0) for b in next_enquiry] + [(ENQ, 0, 1)]))
put("lustbus_fuzz", "receiver_cut_after_address", lustbus_receiver(
    5, [(EOT, 0), (ADR5, 60000 + 60)] + [(b, 0) for b in next_enquiry] + [(ENQ, 0, 1)]))

# dfs1_frame_fuzz: [controller UID][host UID = the byte before which the second pass is silent]
# [command] then the line: P6 := 99 cut after 8 of its 13 bytes (issue 23, defect 1), then a
# whole status request of the next host.
p6_cut = bytes([0x10, 0x02, 0x01, 0x86, 0x06, 0x00, 0x00, 0x00])
status_request = bytes([0x10, 0x02, 0x01, 0x81, 0x10, 0x03, 0x7E])
put("dfs1_frame_fuzz", "cut_write_then_status", bytes([0x01, len(p6_cut), 0x00]) + p6_cut + status_request)
# line_capture_fuzz: byte 0 the mode. Mode 0: a capture file (pcap, nanosecond magic, link type
# 148 LUSTBUS or 149 DFS-1; each packet the 8-byte header of docs/pcap.md, then the telegram).
# Mode 1: byte 1 the protocol (0 LUSTBUS, 1 DFS-1), then chunks [bit 7 side, bits 0-6 length][bytes].
def line_capture(linktype, packets):
    out = struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, linktype)
    for i, (side, flags, address, data) in enumerate(packets):
        body = bytes([1, side, flags | (0x80 if address is not None else 0), address or 0]) + struct.pack(">I", 0) + data
        out += struct.pack("<IIII", 1700000000, i * 10000000, len(body), len(body)) + body
    return out


def lb_text(head, text, tail):
    return bytes(head) + text.encode() + bytes(tail)


lb_seed = [(0, 0, 0, lb_text([EOT, 0x40], "00112", [ENQ])), (1, 0, 0, lb_text([0x40, STX], "00112=03E8", [ETX, 0x72])),
           (0, 0, None, bytes([EOT])), (0, 0, 0, lb_text([EOT, 0x40, STX], "00105=03E8", [ETX, 0x74])),
           (1, 0, 0, bytes([0x40, 0x06])), (0, 0, None, bytes([EOT]))]
put("line_capture_fuzz", "file_lustbus_seed_000", b"\x00" + line_capture(148, lb_seed))
df_seed = [(0, 0, 1, bytes([0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x10, 0x10, 0x00, 0x10, 0x03, 0x6D])),
           (1, 0, 1, bytes([0x10, 0x02, 0x01, 0x06, 0x10, 0x03, 0xF9]))]
put("line_capture_fuzz", "file_dfs1_seed_004", b"\x00" + line_capture(149, df_seed))
put("line_capture_fuzz", "file_cut_record", b"\x00" + line_capture(149, df_seed)[:-3])


def chunks(*items):
    out = b""
    for side, data in items:
        out += bytes([(0x80 if side else 0) | len(data)]) + bytes(data)
    return out


put("line_capture_fuzz", "line_lustbus_seed_000", b"\x01\x00" + chunks(*[(s, d) for s, _, _, d in lb_seed]))
put("line_capture_fuzz", "line_lustbus_bad_bcc_and_cut", b"\x01\x00" + chunks(
    (0, lb_text([EOT, 0x40], "20077", [ENQ])), (1, lb_text([0x40, STX], "20077=04FA4000", [ETX, 0x3B])),
    (0, [EOT, 0x40]), (0, list(b"00112")), (1, lb_text([0x40, STX], "001", []))))
put("line_capture_fuzz", "line_dfs1_seed_004", b"\x01\x01" + chunks(*[(s, d) for s, _, _, d in df_seed]))
put("line_capture_fuzz", "line_dfs1_noise_and_interrupted", b"\x01\x01" + chunks(
    (0, [0x55, 0x10, 0x10, 0x10, 0x02, 0x01, 0x81]), (0, [0x10, 0x02, 0x01, 0x81, 0x10, 0x03, 0x7E]),
    (1, [0x10, 0x02, 0x01, 0x06, 0x00])))
# control_fuzz, the channel (byte 0 bit 1): [clients][max_clients][max_line][read_budget]
# [lines_per_poll] then operations: (client << 2) | 0 write (a length byte, the bytes), | 2 the
# client's end of input, | 3 a poll (issue 41).
def channel(clients, max_clients, max_line, budget, lines, *ops):
    out = bytes([0x02, clients - 1, max_clients - 1, max_line - 1, budget - 1, lines - 1])
    for op in ops:
        if isinstance(op, tuple):
            client, data = op
            out += bytes([client << 2, len(data)]) + data
        else:  # "poll"
            out += bytes([3])
    return out


def end(client):
    return bytes([(client << 2) | 2])


put("control_fuzz", "channel_two_clients_interleaved", channel(
    2, 4, 48, 16, 4, (0, b'{"device": "servo", "spe'), (1, b'{"device": "fan", "load": 1}\n'), "poll",
    (0, b'ed": 5}\n# comment\n\r\n'), (1, b"not json\r\n"), "poll") + end(0) + bytes([3]))
put("control_fuzz", "channel_endless_line_and_a_refused_client", channel(
    3, 2, 8, 8, 2, (0, b"x" * 40), (1, b'{"a": 1}\n'), "poll", (0, b"x" * 40), "poll", (0, b"\nok\n"),
    (1, b"last without newline"), "poll") + end(1) + bytes([3]))
print("seeds written to", CORPUS)

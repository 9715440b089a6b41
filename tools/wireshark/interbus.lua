-- INTERBUS cycle captures of ibs (`ibs run --pcap`, `ibs replay --pcap`) for Wireshark / tshark.
-- The packet layouts are this project's own and docs/pcap.md specifies them: a configuration
-- packet first (the ring: each device's kind, ID code, slices in the process image, value format),
-- then one packet per bus cycle with the master's OUT and IN process data, both PCP areas and the
-- cycle's validity. Each device's words are decoded: DRIVECOM control and status words with the
-- command and the state, references and actual values in engineering units, the VF1000
-- communication word (toggle, ACK/NAK, CODE, byte), the MC6000's PCP frames (fragments).
--
--   tshark -X lua_script:tools/wireshark/interbus.lua -r capture.pcap -V
--
-- Captures: LINKTYPE_USER0 (147). This script registers itself for it; without the script,
-- Wireshark's "User DLTs" table (Preferences > Protocols > DLT_USER) can map DLT 147 to
-- "interbus" once the script is in the personal Lua plugins folder.

local p = Proto("interbus", "INTERBUS (ibs capture)")

local kinds = { [0] = "other", [1] = "VF1000", [2] = "MC6000" }
local types = { [1] = "configuration", [2] = "cycle" }
local sources = { [0] = "ibs run", [1] = "ibs replay --emulate device", [2] = "ibs replay --emulate master" }
local value_formats = { [0] = "none", [1] = "16-bit whole units (IBCNF 1)", [2] = "32-bit Q16 (IBCNF 2)",
                        [3] = "Q16 reference, 16-bit speed and torque (IBCNF 3)", [4] = "VF1000 0.05 Hz per bit" }
local codes = { [0] = "starting position", [1] = "value inquiry", [2] = "value transfer", [3] = "description scan" }
local frame_types = { [0] = "control", [1] = "FIRST", [2] = "NEXT", [3] = "LAST" }
local control_codes = { [0] = "IDLE", [1] = "ABORT", [2] = "ABORT-ACK", [3] = "invalid control code" }
local services = { [0x0081] = "Read", [0x0082] = "Write", [0x0085] = "Information-Report", [0x0086] = "Status",
                   [0x0087] = "Identify", [0x0088] = "Get-OV", [0x008B] = "Initiate", [0x088D] = "Abort" }

-- DRIVECOM Profile 20 (INTERBUS manual 5.1.2 and 5.1.3), in the rows' priority order.
local commands = {
  { 0x0002, 0x0000, "BLOCK POWER" },
  { 0x0006, 0x0002, "EMERGENCY STOP" },
  { 0x0007, 0x0006, "SHUTDOWN" },
  { 0x000F, 0x0007, "POWER-ON/DISABLE" },
  { 0x000F, 0x000F, "POWER-ON/ENABLE" },
}
local states = {
  { 0x004F, 0x0000, "NOT READY" },
  { 0x004F, 0x0040, "START-UP INHIBIT" },
  { 0x006F, 0x0021, "READY" },
  { 0x006F, 0x0023, "ON" },
  { 0x006F, 0x0027, "ENABLED" },
  { 0x004F, 0x0008, "FAULT" },
  { 0x004F, 0x000F, "FAULT RESPONSE ACTIVE" },
  { 0x006F, 0x0007, "EMERGENCY STOP ACTIVE" },
}

local f = p.fields
f.version = ProtoField.uint8("interbus.version", "Version", base.DEC)
f.type = ProtoField.uint8("interbus.type", "Packet", base.DEC, types)
f.devices = ProtoField.uint16("interbus.devices", "Devices", base.DEC)
f.in_words = ProtoField.uint16("interbus.in_words", "IN words", base.DEC)
f.out_words = ProtoField.uint16("interbus.out_words", "OUT words", base.DEC)
f.pcp_words = ProtoField.uint16("interbus.pcp_words", "PCP words", base.DEC)
f.cycle_time = ProtoField.uint32("interbus.cycle_time", "Cycle time (ns)", base.DEC)
f.source = ProtoField.uint8("interbus.source", "Written by", base.DEC, sources)
f.device = ProtoField.string("interbus.device", "Device")
f.kind = ProtoField.uint8("interbus.device.kind", "Kind", base.DEC, kinds)
f.first_word = ProtoField.uint8("interbus.device.first_word", "First word", base.DEC)
f.id_code = ProtoField.uint16("interbus.device.id_code", "ID code", base.HEX)
f.in_offset = ProtoField.uint16("interbus.device.in_offset", "IN offset", base.DEC)
f.in_length = ProtoField.uint16("interbus.device.in_length", "IN words", base.DEC)
f.out_offset = ProtoField.uint16("interbus.device.out_offset", "OUT offset", base.DEC)
f.out_length = ProtoField.uint16("interbus.device.out_length", "OUT words", base.DEC)
f.pcp_offset = ProtoField.uint16("interbus.device.pcp_offset", "PCP offset", base.DEC)
f.pcp_length = ProtoField.uint16("interbus.device.pcp_length", "PCP words", base.DEC)
f.values = ProtoField.uint8("interbus.device.values", "Values", base.DEC, value_formats)
f.supi = ProtoField.uint8("interbus.device.supi", "405-SUPI", base.DEC)
f.ibcnf = ProtoField.uint8("interbus.device.ibcnf", "406-IBCNF", base.DEC)
f.unit = ProtoField.string("interbus.device.unit", "Unit")

f.cycle = ProtoField.uint32("interbus.cycle", "Cycle", base.DEC)
f.valid = ProtoField.bool("interbus.valid", "Valid", 8, nil, 0x01)
f.word = ProtoField.uint16("interbus.word", "Word", base.HEX)

f.control = ProtoField.uint16("interbus.control", "Control word", base.HEX)
f.command = ProtoField.string("interbus.command", "Command")
f.reset_fault = ProtoField.bool("interbus.control.reset_fault", "RESET FAULT (bit 7)", 16, nil, 0x0080)
f.ramp_enable = ProtoField.bool("interbus.control.ramp_enable", "Ramp enable (bit 4)", 16, nil, 0x0010)
f.ramp_run = ProtoField.bool("interbus.control.ramp_run", "Ramp run (bit 5)", 16, nil, 0x0020)
f.ramp_follow = ProtoField.bool("interbus.control.ramp_follow", "Ramp follows the reference (bit 6)", 16, nil, 0x0040)
f.s2ind = ProtoField.bool("interbus.control.s2ind", "S2IND (bit 12)", 16, nil, 0x1000)
f.s1ind = ProtoField.bool("interbus.control.s1ind", "S1IND (bit 13)", 16, nil, 0x2000)
f.stl = ProtoField.bool("interbus.control.stl", "STL, start counter-clockwise (bit 14)", 16, nil, 0x4000)
f.str = ProtoField.bool("interbus.control.str", "STR, start clockwise (bit 15)", 16, nil, 0x8000)
f.os00 = ProtoField.bool("interbus.control.os00", "OS00 (bit 14)", 16, nil, 0x4000)
f.os01 = ProtoField.bool("interbus.control.os01", "OS01 (bit 15)", 16, nil, 0x8000)

f.status = ProtoField.uint16("interbus.status", "Status word", base.HEX)
f.state = ProtoField.string("interbus.state", "State")
f.alarm = ProtoField.bool("interbus.status.alarm", "Alarm (bit 7)", 16, nil, 0x0080)
f.message = ProtoField.bool("interbus.status.message", "Message (bit 8)", 16, nil, 0x0100)
f.remote = ProtoField.bool("interbus.status.remote", "Remote (bit 9)", 16, nil, 0x0200)
f.reached = ProtoField.bool("interbus.status.reference_reached", "Reference reached (bit 10)", 16, nil, 0x0400)
f.limit = ProtoField.bool("interbus.status.limit_value", "Limit value (bit 11)", 16, nil, 0x0800)
f.s2out = ProtoField.bool("interbus.status.s2out", "S2OUT (bit 14)", 16, nil, 0x4000)
f.s1out = ProtoField.bool("interbus.status.s1out", "S1OUT (bit 15)", 16, nil, 0x8000)
f.is00 = ProtoField.bool("interbus.status.is00", "IS00 (bit 14)", 16, nil, 0x4000)
f.is01 = ProtoField.bool("interbus.status.is01", "IS01 (bit 15)", 16, nil, 0x8000)

f.reference = ProtoField.double("interbus.reference", "Reference")
f.actual = ProtoField.double("interbus.actual", "Actual value")
f.torque = ProtoField.double("interbus.torque", "Torque (% of rated)")

f.comm_master = ProtoField.uint16("interbus.comm.master", "Communication word (master)", base.HEX)
f.comm_toggle = ProtoField.bool("interbus.comm.toggle", "Toggle", 16, nil, 0x2000)
f.comm_code = ProtoField.uint16("interbus.comm.code", "CODE", base.DEC, codes, 0x1C00)
f.comm_pnr_high = ProtoField.uint16("interbus.comm.pnr_high", "Parameter number bits 8-9", base.DEC, nil, 0x0300)
f.comm_byte = ProtoField.uint16("interbus.comm.byte", "Byte", base.HEX, nil, 0x00FF)
f.comm_pnr = ProtoField.uint16("interbus.comm.pnr", "As a parameter number", base.DEC)
f.comm_inverter = ProtoField.uint16("interbus.comm.inverter", "Communication word (inverter)", base.HEX)
f.comm_ready = ProtoField.bool("interbus.comm.ready", "Ready (RESET distinction)", 16, nil, 0x8000)
f.comm_itoggle = ProtoField.bool("interbus.comm.inverter_toggle", "Toggle", 16, nil, 0x2000)
f.comm_nak = ProtoField.bool("interbus.comm.nak", "NAK (last byte, error)", 16, nil, 0x1000)
f.comm_ack = ProtoField.bool("interbus.comm.ack", "ACK (last byte, no error)", 16, nil, 0x0800)
f.comm_data = ProtoField.uint16("interbus.comm.data", "Data byte", base.HEX, nil, 0x00FF)

f.pcp_frame = ProtoField.string("interbus.pcp.frame", "PCP frame")
f.pcp_admin = ProtoField.uint8("interbus.pcp.admin", "Administrative byte", base.HEX)
f.pcp_dir = ProtoField.uint8("interbus.pcp.dir", "DIR", base.DEC, { [0] = "master -> servo", [1] = "servo -> master" }, 0x80)
f.pcp_type = ProtoField.uint8("interbus.pcp.frame_type", "TYPE", base.DEC, frame_types, 0x60)
f.pcp_seq = ProtoField.uint8("interbus.pcp.seq", "SEQ", base.DEC, nil, 0x18)
f.pcp_ctl = ProtoField.uint8("interbus.pcp.control", "Control code", base.DEC, control_codes, 0x18)
f.pcp_ack = ProtoField.uint8("interbus.pcp.ack", "ACK", base.DEC, nil, 0x06)
f.pcp_parity = ProtoField.uint8("interbus.pcp.parity", "P", base.DEC, nil, 0x01)
f.pcp_parity_ok = ProtoField.bool("interbus.pcp.parity_ok", "Odd parity holds")
f.pcp_data = ProtoField.bytes("interbus.pcp.data", "Data", base.SPACE)
f.pcp_service = ProtoField.string("interbus.pcp.service", "Service")
f.msg = ProtoField.bytes("interbus.pcp.message", "PCP message", base.SPACE)
f.msg_device = ProtoField.string("interbus.pcp.message.device", "Device")
f.msg_dir = ProtoField.string("interbus.pcp.message.direction", "Direction")
f.msg_service = ProtoField.string("interbus.pcp.message.service", "Service")
f.msg_code = ProtoField.uint16("interbus.pcp.message.code", "Code", base.HEX)
f.msg_count = ProtoField.uint16("interbus.pcp.message.count", "Count (words after it)", base.DEC)
f.msg_invoke = ProtoField.uint8("interbus.pcp.message.invoke_id", "InvokeID", base.DEC)
f.msg_cr = ProtoField.uint8("interbus.pcp.message.cr", "CR", base.DEC)
f.msg_index = ProtoField.uint16("interbus.pcp.message.index", "Index", base.HEX)
f.msg_parameter = ProtoField.uint16("interbus.pcp.message.parameter", "Parameter (index - 5C00H)", base.DEC)
f.msg_result = ProtoField.uint16("interbus.pcp.message.result", "Result", base.HEX)
f.msg_params = ProtoField.bytes("interbus.pcp.message.parameters", "Parameters", base.SPACE)

-- Arithmetic instead of bit operators: the script runs on Lua 5.2 to 5.4 alike.
local function bits(v, shift, n) return math.floor(v / 2 ^ shift) % 2 ^ n end
local function bit(v, n) return bits(v, n, 1) == 1 end
local function band_eq(v, mask, value)
  local r = 0
  for i = 0, 15 do
    if bit(mask, i) and bit(v, i) then r = r + 2 ^ i end
  end
  return r == value
end
local function int16(w) if w >= 0x8000 then return w - 0x10000 end return w end
local function int32(hi, lo)
  local v = hi * 65536 + lo
  if v >= 2 ^ 31 then v = v - 2 ^ 32 end
  return v
end
local function fmt(v)
  local s = string.format("%.6f", v):gsub("0+$", ""):gsub("%.$", "")
  return s
end

local function command_of(w)
  for _, row in ipairs(commands) do
    if band_eq(w, row[1], row[2]) then return row[3] end
  end
  return "?"
end
local function state_of(w)
  for _, row in ipairs(states) do
    if band_eq(w, row[1], row[2]) then return row[3] end
  end
  return "no DRIVECOM state"
end

-- The configuration each packet is read with: the latest configuration packet before it.
local configs = {}
-- PCP reassembly, done on the first pass in frame order: per device and direction the fragments
-- of the message in transfer; the complete messages by the frame whose LAST fragment ended them.
local transfers = {}
local messages = {}

function p.init()
  configs = {}
  transfers = {}
  messages = {}
end

local function config_for(number)
  local best, best_n = nil, -1
  for n, c in pairs(configs) do
    if n <= number and n > best_n then best, best_n = c, n end
  end
  return best
end

local function dissect_configuration(tvb, pinfo, t)
  if tvb:len() < 20 then
    t:add_expert_info(PI_MALFORMED, PI_ERROR, "configuration packet shorter than 20 bytes")
    return
  end
  local c = { devices = {} }
  local n = tvb(4, 2):uint()
  t:add(f.devices, tvb(4, 2))
  t:add(f.in_words, tvb(6, 2)); c.in_words = tvb(6, 2):uint()
  t:add(f.out_words, tvb(8, 2)); c.out_words = tvb(8, 2):uint()
  t:add(f.pcp_words, tvb(10, 2)); c.pcp_words = tvb(10, 2):uint()
  t:add(f.cycle_time, tvb(12, 4))
  t:add(f.source, tvb(16, 1))
  local o = 20
  local names = {}
  for _ = 1, n do
    if o + 21 > tvb:len() then
      t:add_expert_info(PI_MALFORMED, PI_ERROR, "device record cut short")
      return
    end
    local nl = tvb(o + 19, 1):uint()
    local ul = tvb(o + 20 + nl, 1):uint()
    local len = 21 + nl + ul
    local d = {
      kind = tvb(o, 1):uint(), first = tvb(o + 1, 1):uint(), id = tvb(o + 2, 2):uint(),
      in_off = tvb(o + 4, 2):uint(), in_len = tvb(o + 6, 2):uint(),
      out_off = tvb(o + 8, 2):uint(), out_len = tvb(o + 10, 2):uint(),
      pcp_off = tvb(o + 12, 2):uint(), pcp_len = tvb(o + 14, 2):uint(),
      values = tvb(o + 16, 1):uint(), supi = tvb(o + 17, 1):uint(), ibcnf = tvb(o + 18, 1):uint(),
      name = tvb(o + 20, nl):string(), unit = tvb(o + 21 + nl, ul):string(),
    }
    local dt = t:add(f.device, tvb(o + 20, nl))
    dt:set_text(string.format("Device %s: %s, ID code %03XH", d.name, kinds[d.kind] or "?", d.id))
    dt:add(f.kind, tvb(o, 1))
    dt:add(f.first_word, tvb(o + 1, 1))
    dt:add(f.id_code, tvb(o + 2, 2))
    dt:add(f.in_offset, tvb(o + 4, 2)); dt:add(f.in_length, tvb(o + 6, 2))
    dt:add(f.out_offset, tvb(o + 8, 2)); dt:add(f.out_length, tvb(o + 10, 2))
    dt:add(f.pcp_offset, tvb(o + 12, 2)); dt:add(f.pcp_length, tvb(o + 14, 2))
    dt:add(f.values, tvb(o + 16, 1))
    if d.kind == 2 then dt:add(f.supi, tvb(o + 17, 1)); dt:add(f.ibcnf, tvb(o + 18, 1)) end
    dt:add(f.unit, tvb(o + 21 + nl, ul))
    c.devices[#c.devices + 1] = d
    names[#names + 1] = string.format("%s (%s)", d.name, kinds[d.kind] or "?")
    o = o + len
  end
  configs[pinfo.number] = c
  pinfo.cols.info = string.format("configuration: %s; cycle %s ns", table.concat(names, ", "), tvb(12, 4):uint())
end

-- One word of a device slice: index j of the slice that starts at byte `base`.
local function word(tvb, base, j) return tvb(base + 2 * j, 2) end

local function add_control(t, d, r)
  local w = r:uint()
  local ct = t:add(f.control, r)
  local cmd = command_of(w)
  local extra = ""
  if bit(w, 7) then extra = extra .. ", RESET FAULT bit" end
  if d.kind == 1 then
    if bit(w, 14) then extra = extra .. ", STL" end
    if bit(w, 15) then extra = extra .. ", STR" end
  end
  ct:append_text(" " .. cmd .. extra)
  ct:add(f.command, r, cmd):set_generated()
  ct:add(f.reset_fault, r)
  if d.kind == 1 then
    ct:add(f.ramp_enable, r); ct:add(f.ramp_run, r); ct:add(f.ramp_follow, r)
    ct:add(f.s2ind, r); ct:add(f.s1ind, r); ct:add(f.stl, r); ct:add(f.str, r)
  elseif d.kind == 2 then
    ct:add(f.os00, r); ct:add(f.os01, r)
  end
  return cmd, w
end

local function add_status(t, d, r)
  local w = r:uint()
  local st = t:add(f.status, r)
  local name = state_of(w)
  local extra = ""
  if bit(w, 7) then extra = extra .. ", alarm" end
  if bit(w, 9) then extra = extra .. ", remote" end
  if bit(w, 10) then extra = extra .. ", reference reached" end
  if bit(w, 11) then extra = extra .. ", limit value" end
  st:append_text(" " .. name .. extra)
  st:add(f.state, r, name):set_generated()
  st:add(f.alarm, r); st:add(f.message, r); st:add(f.remote, r); st:add(f.reached, r); st:add(f.limit, r)
  if d.kind == 1 then
    st:add(f.s2out, r); st:add(f.s1out, r)
  elseif d.kind == 2 then
    st:add(f.is00, r); st:add(f.is01, r)
  end
  return name
end

local function add_value(t, field, range, value, unit, extra)
  local it = t:add(field, range, value)
  it:set_text(string.format("%s: %s %s%s", field == f.reference and "Reference" or "Actual value", fmt(value), unit,
                            extra or ""))
  return it
end

-- The reference (master's words) or the actual value (device's words) of a device: words 2.. of
-- its process data, as the value format says.
local function add_values(t, tvb, d, base, count, is_reference, control)
  local function w(n)  -- device word n (1-based) or nil outside the slice
    local j = n - d.first
    if j < 0 or j >= count then return nil end
    return word(tvb, base, j)
  end
  local field = is_reference and f.reference or f.actual
  if d.values == 4 then
    local r = w(2)
    if not r then return nil end
    if is_reference then
      local hz = r:uint() * 0.05
      local ccw = control and bit(control, 14) and not bit(control, 15)
      if ccw then hz = -hz end
      add_value(t, field, r, hz, d.unit, ccw and " (counter-clockwise, STL)" or "")
      return hz
    end
    local hz = int16(r:uint()) * 0.05
    add_value(t, field, r, hz, d.unit)
    return hz
  elseif d.values == 1 then
    local r = w(2)
    if not r then return nil end
    local v = int16(r:uint())
    add_value(t, field, r, v, d.unit)
    return v
  elseif d.values == 2 or (d.values == 3 and is_reference) then
    local hi, lo = w(2), w(3)
    if not hi or not lo then return nil end
    local v = int32(hi:uint(), lo:uint()) / 65536
    add_value(t, field, tvb(hi:offset(), 4), v, d.unit, " (Q16)")
    return v
  elseif d.values == 3 then
    local sp, tq = w(2), w(3)
    if not sp then return nil end
    local v = int16(sp:uint())
    add_value(t, field, sp, v, d.unit)
    if tq then t:add(f.torque, tq, int16(tq:uint())) end
    return v
  end
  return nil
end

local function add_comm(t, r, master)
  local v = r:uint()
  if master then
    local ct = t:add(f.comm_master, r)
    local code = bits(v, 10, 3)
    ct:append_text(string.format(" (toggle %d, CODE %d %s, byte %02XH)", bits(v, 13, 1), code,
                                 codes[code] or "(undefined)", v % 256))
    ct:add(f.comm_toggle, r); ct:add(f.comm_code, r); ct:add(f.comm_pnr_high, r); ct:add(f.comm_byte, r)
    if code >= 1 and code <= 3 then ct:add(f.comm_pnr, r, bits(v, 8, 2) * 256 + v % 256):set_generated() end
  else
    local ct = t:add(f.comm_inverter, r)
    local flags = ""
    if bit(v, 11) then flags = ", ACK" end
    if bit(v, 12) then flags = flags .. ", NAK" end
    if bit(v, 15) then
      ct:append_text(string.format(" (ready, toggle %d%s, data %02XH)", bits(v, 13, 1), flags, v % 256))
    else
      ct:append_text(" (initialising)")
    end
    ct:add(f.comm_ready, r); ct:add(f.comm_itoggle, r); ct:add(f.comm_nak, r); ct:add(f.comm_ack, r)
    ct:add(f.comm_data, r)
  end
end

-- One PCP frame (docs/pcp.md, "Link"): the administrative byte and 2 x words - 1 data bytes.
local function add_pcp(t, tvb, base, words, label)
  if words == 0 then return end
  local r = tvb(base, 2 * words)
  local admin = tvb(base, 1):uint()
  local ones = 0
  for i = 0, 7 do if bit(admin, i) then ones = ones + 1 end end
  local parity_ok = ones % 2 == 1
  local ftype = bits(admin, 5, 2)
  local text
  if not parity_ok then
    text = string.format("invalid administrative byte %02XH (parity)", admin)
  elseif ftype == 0 then
    local code = bits(admin, 3, 2)
    text = control_codes[code]
    if code == 0 then text = text .. string.format(" a%d", bits(admin, 1, 2)) end
  else
    text = string.format("%s s%d a%d:", frame_types[ftype], bits(admin, 3, 2), bits(admin, 1, 2))
    for i = 1, 2 * words - 1 do text = text .. string.format(" %02X", tvb(base + i, 1):uint()) end
  end
  local service
  if parity_ok and ftype == 1 and words >= 2 then
    local code = tvb(base + 1, 2):uint()
    local conf = code >= 0x8000 and code ~= 0x088D
    local b = conf and code - 0x8000 or code
    if services[b] then
      local unconfirmed = b == 0x088D or b == 0x0085
      service = services[b] .. (conf and ".conf" or (unconfirmed and "" or ".req"))
      text = text .. " (" .. service .. ")"
    end
  end
  local pt = t:add(f.pcp_frame, r, text)
  pt:set_text(label .. ": " .. text)
  pt:add(f.pcp_admin, tvb(base, 1))
  pt:add(f.pcp_dir, tvb(base, 1))
  pt:add(f.pcp_type, tvb(base, 1))
  if ftype == 0 then pt:add(f.pcp_ctl, tvb(base, 1)) else pt:add(f.pcp_seq, tvb(base, 1)) end
  pt:add(f.pcp_ack, tvb(base, 1))
  pt:add(f.pcp_parity, tvb(base, 1))
  pt:add(f.pcp_parity_ok, tvb(base, 1), parity_ok):set_generated()
  if words > 0 and 2 * words - 1 > 0 then pt:add(f.pcp_data, tvb(base + 1, 2 * words - 1)) end
  if service then pt:add(f.pcp_service, tvb(base + 1, 2), service):set_generated() end
  return text
end

-- Whether device word n (1-based) carries the reference / actual value.
local function value_word(d, n)
  if d.kind == 0 or d.values == 0 then return false end
  if d.values == 1 or d.values == 4 then return n == 2 end
  return n == 2 or n == 3
end

local function service_name(code)
  local conf = code >= 0x8000 and code ~= 0x088D
  local b = conf and code - 0x8000 or code
  if not services[b] then return string.format("unknown service %04XH", code) end
  local unconfirmed = b == 0x088D or b == 0x0085
  return services[b] .. (conf and ".conf" or (unconfirmed and "" or ".req"))
end

-- Follows one frame of a device's channel (first pass only), as the receiver does (docs/pcp.md,
-- "Go-back-N, window two"): a data frame is a new fragment only with the SEQ after the last one
-- taken (the sender shows a fragment again while it waits, and goes back); ABORT and ABORT-ACK
-- drop the message in transfer and restart the counter. Over 4 words a LAST frame alone is a
-- message of its own.
local function follow_fragment(pinfo, tvb, base, words, key)
  local admin = tvb(base, 1):uint()
  local ones = 0
  for i = 0, 7 do if bit(admin, i) then ones = ones + 1 end end
  if ones % 2 == 0 then return end
  local tr = transfers[key]
  if not tr then
    tr = { bytes = nil, seq = nil }
    transfers[key] = tr
  end
  local ftype, seq = bits(admin, 5, 2), bits(admin, 3, 2)
  if ftype == 0 then
    if seq == 1 or seq == 2 then tr.bytes, tr.seq = nil, 3 end
    return
  end
  if tr.seq ~= nil and seq ~= (tr.seq + 1) % 4 then return end
  if tr.seq == nil and ftype == 2 then return end  -- the capture began in the middle of a message
  tr.seq = seq
  if ftype == 1 or (ftype == 3 and not tr.bytes and words == 4) then
    tr.bytes = {}
  elseif not tr.bytes then
    return
  end
  for i = 1, 2 * words - 1 do tr.bytes[#tr.bytes + 1] = tvb(base + i, 1):uint() end
  if ftype == 3 then
    local list = messages[pinfo.number] or {}
    list[#list + 1] = { key = key, bytes = tr.bytes }
    messages[pinfo.number] = list
    tr.bytes = nil
  end
end

-- A reassembled message: PDU and zero padding, no link CRC (docs/pcp.md, "Messages on the channel").
-- `device`: the name of the device whose channel carried it. The message is an item of that
-- device's subtree, but `interbus.device` occurs once per device of the packet, so `-T fields`
-- could not tell which one a message belongs to; `interbus.pcp.message.device` occurs once per
-- message, beside its service.
local function add_message(t, bytes, direction, device)
  local ba = ByteArray.new()
  ba:set_size(#bytes)
  for i = 1, #bytes do ba:set_index(i - 1, bytes[i]) end
  local mt = ba:tvb("PCP message")
  local n = #bytes
  if n < 6 then
    local it = t:add(f.msg, mt())
    it:append_text(" (shorter than a PDU)")
    it:add(f.msg_device, mt(0, 0), device):set_generated()
    return nil
  end
  local code, count = mt(0, 2):uint(), mt(2, 2):uint()
  local size = 4 + 2 * count
  local service = service_name(code)
  local it = t:add(f.msg, mt(0, math.min(size, n)))
  it:set_text(string.format("PCP message %s (%s): %s, %d bytes", direction, device, service, size))
  it:add(f.msg_device, mt(0, 0), device):set_generated()
  it:add(f.msg_dir, mt(0, 0), direction):set_generated()
  it:add(f.msg_service, mt(0, 2), service):set_generated()
  it:add(f.msg_code, mt(0, 2))
  it:add(f.msg_count, mt(2, 2))
  it:add(f.msg_invoke, mt(4, 1))
  it:add(f.msg_cr, mt(5, 1))
  if size > n then
    it:append_text(" (the count word announces more bytes than arrived)")
    return service
  end
  local conf = code >= 0x8000 and code ~= 0x088D
  if conf and size >= 8 then
    local result = mt(6, 2):uint()
    local rt = it:add(f.msg_result, mt(6, 2))
    if result == 0 then
      rt:append_text(" (positive)")
    else
      rt:append_text(string.format(" (negative: error class %d, code %d)", bits(result, 8, 8), result % 256))
    end
  elseif (code == 0x0081 or code == 0x0082 or code == 0x0088) and size >= 8 then
    local index = mt(6, 2):uint()
    it:add(f.msg_index, mt(6, 2))
    if index >= 0x5C00 then it:add(f.msg_parameter, mt(6, 2), index - 0x5C00):set_generated() end
    it:set_text(string.format("PCP message %s (%s): %s, %d bytes, index %04XH", direction, device, service, size,
                              index))
  end
  if size > 6 then it:add(f.msg_params, mt(6, size - 6)) end
  return service
end

-- A device's words one way, in word order. Master side: returns the control word; device side:
-- the state's name and the actual value.
local function add_words(t, tvb, d, base, count, master, control)
  local first_value, state, value = true, nil, nil
  for j = 0, count - 1 do
    local n = d.first + j
    local r = word(tvb, base, j)
    if n == 1 and d.kind ~= 0 then
      if master then
        local _, w = add_control(t, d, r)
        control = w
      else
        state = add_status(t, d, r)
      end
    elseif value_word(d, n) then
      if first_value then
        value = add_values(t, tvb, d, base, count, master, control)
        first_value = false
      end
    elseif n == 3 and d.kind == 1 then
      add_comm(t, r, master)
    else
      t:add(f.word, r):prepend_text(string.format("Word %d: ", n))
    end
  end
  if master then return control end
  return state, value
end

local function dissect_cycle(tvb, pinfo, t)
  if tvb:len() < 16 then
    t:add_expert_info(PI_MALFORMED, PI_ERROR, "cycle packet shorter than 16 bytes")
    return
  end
  local number = tvb(4, 4):uint()
  t:add(f.cycle, tvb(4, 4))
  local valid = tvb(8, 1):uint() % 2 == 1
  t:add(f.valid, tvb(8, 1))
  local nout, nin, npcp = tvb(10, 2):uint(), tvb(12, 2):uint(), tvb(14, 2):uint()
  t:add(f.out_words, tvb(10, 2)); t:add(f.in_words, tvb(12, 2)); t:add(f.pcp_words, tvb(14, 2))
  local out_base = 16
  local in_base = out_base + 2 * nout
  local pcp_out_base = in_base + 2 * nin
  local pcp_in_base = pcp_out_base + 2 * npcp
  if pcp_in_base + 2 * npcp > tvb:len() then
    t:add_expert_info(PI_MALFORMED, PI_ERROR, "the words announced do not fit the packet")
    return
  end
  local info = {}
  local c = config_for(pinfo.number)
  if not c then
    t:add_expert_info(PI_UNDECODED, PI_WARN, "no configuration packet before this cycle: words not assigned to devices")
  else
    for index, d in ipairs(c.devices) do
      local dt = t:add(f.device, tvb(0, 0), d.name)
      dt:set_text(string.format("%s (%s)", d.name, kinds[d.kind] or "?"))
      local summary = d.name
      local control
      if d.out_len > 0 and d.out_off + d.out_len <= nout then
        local ob = out_base + 2 * d.out_off
        local ot = dt:add(p, tvb(ob, 2 * d.out_len), "Master -> device (OUT)")
        control = add_words(ot, tvb, d, ob, d.out_len, true, nil)
      end
      if d.in_len > 0 and d.in_off + d.in_len <= nin then
        local ib = in_base + 2 * d.in_off
        local it = dt:add(p, tvb(ib, 2 * d.in_len), "Device -> master (IN)")
        local state, actual = add_words(it, tvb, d, ib, d.in_len, false, control)
        if state then summary = summary .. " " .. state end
        if actual then summary = summary .. " " .. fmt(actual) .. " " .. d.unit end
        if d.first == 3 and d.kind == 1 and d.out_len > 0 then
          summary = summary .. string.format(" comm %04X/%04X", word(tvb, out_base + 2 * d.out_off, 0):uint(),
                                             word(tvb, ib, 0):uint())
        end
      end
      if d.pcp_len > 0 and d.pcp_off + d.pcp_len <= npcp then
        local ob, ib = pcp_out_base + 2 * d.pcp_off, pcp_in_base + 2 * d.pcp_off
        local out_text = add_pcp(dt, tvb, ob, d.pcp_len, "PCP master -> servo")
        local in_text = add_pcp(dt, tvb, ib, d.pcp_len, "PCP servo -> master")
        if d.in_len == 0 then summary = summary .. " PCP " .. out_text .. " / " .. in_text end
        if not pinfo.visited then
          follow_fragment(pinfo, tvb, ob, d.pcp_len, index .. ">")
          follow_fragment(pinfo, tvb, ib, d.pcp_len, index .. "<")
        end
        for _, m in ipairs(messages[pinfo.number] or {}) do
          local dir = (m.key == index .. ">") and "master -> servo" or ((m.key == index .. "<") and "servo -> master")
          if dir then
            local service = add_message(dt, m.bytes, dir, d.name)
            if service then summary = summary .. " " .. service end
          end
        end
      end
      info[#info + 1] = summary
    end
  end
  pinfo.cols.info = string.format("cycle %d%s: %s", number, valid and "" or " INVALID", table.concat(info, " | "))
end

function p.dissector(tvb, pinfo, tree)
  if tvb:len() < 4 or tvb(0, 1):uint() ~= 0x49 or tvb(1, 1):uint() ~= 0x42 then return 0 end
  pinfo.cols.protocol = "INTERBUS"
  local t = tree:add(p, tvb(), "INTERBUS (ibs capture)")
  t:add(f.version, tvb(2, 1))
  t:add(f.type, tvb(3, 1))
  local kind = tvb(3, 1):uint()
  if kind == 1 then
    t:append_text(", configuration")
    dissect_configuration(tvb, pinfo, t)
  elseif kind == 2 then
    t:append_text(string.format(", cycle %d", tvb:len() >= 8 and tvb(4, 4):uint() or 0))
    dissect_cycle(tvb, pinfo, t)
  end
  return tvb:len()
end

DissectorTable.get("wtap_encap"):add(wtap_encaps.USER0, p)

-- LUSTBUS (LUSTBUS manual) captures of ibs (`ibs lustbus ... --pcap`, `ibs run --lustbus-pcap`) for
-- Wireshark / tshark. Each packet is one telegram of the line after an 8-byte header of ibs's own
-- (docs/pcap.md, "Serial lines"): version, direction (0 host, 1 device), flags (bit 0 check
-- character wrong, bit 1 cut, bit 2 noise, bit 7 address present), address, the telegram's
-- duration in microseconds. The telegram is decoded by ISO 1745 as the LUSTBUS manual uses it (2.2, 6.1,
-- 6.2, 11.6): every control character named, ADR with the address (0 '@' every device, 31 '_'
-- broadcast), CODE by the coding of 2.4.1 (VF1000) / 2.4.2 (MC6000) / 5.2 (both) / 11.3 / 11.6
-- (PosMOD1), VALUE as text and as the hex number it is, and the BCC checked (XOR of the bytes
-- after STX through ETX; a wrong one is an expert error). An answer links to its request.
--
--   tshark -X lua_script:tools/wireshark/lustbus.lua -r capture.pcap -V
--
-- Captures: LINKTYPE_USER1 (148). This script registers itself for it (the INTERBUS dissector
-- takes USER0, the DFS-1 one USER2).

local p = Proto("lustbus", "LUSTBUS (ibs capture)")

local STX, ETX, EOT, ENQ, ACK, NAK, EQ = 0x02, 0x03, 0x04, 0x05, 0x06, 0x15, 0x3D
local chars = { [STX] = "STX", [ETX] = "ETX", [EOT] = "EOT", [ENQ] = "ENQ", [ACK] = "ACK", [NAK] = "NAK" }
local directions = { [0] = "host to device", [1] = "device to host" }
local shared = { [81] = "SIOC/SBAUD", [82] = "SIOA/SADDR", [83] = "SIOW/SDMMY", [84] = "SIOT/SWDGT",
                 [85] = "SIOF/SERR", [91] = "TYPE" }

local f = p.fields
-- The header ibs writes (docs/pcap.md).
f.version = ProtoField.uint8("lustbus.version", "Capture header version", base.DEC)
f.direction = ProtoField.uint8("lustbus.direction", "Direction", base.DEC, directions)
f.flags = ProtoField.uint8("lustbus.flags", "Recorder's flags", base.HEX)
f.flag_check = ProtoField.bool("lustbus.flags.check_bad", "BCC wrong (as recorded)", 8, nil, 0x01)
f.flag_cut = ProtoField.bool("lustbus.flags.cut", "Cut (ended before it was complete)", 8, nil, 0x02)
f.flag_noise = ProtoField.bool("lustbus.flags.noise", "Noise (no telegram)", 8, nil, 0x04)
f.flag_address = ProtoField.bool("lustbus.flags.address", "Address present", 8, nil, 0x80)
f.header_address = ProtoField.uint8("lustbus.header_address", "Address (as recorded)", base.DEC)
f.duration = ProtoField.uint32("lustbus.duration", "Duration, first byte to last (us)", base.DEC)
-- The telegram.
f.kind = ProtoField.string("lustbus.kind", "Telegram")
f.char = ProtoField.uint8("lustbus.char", "Control character", base.HEX, chars)
f.adr = ProtoField.char("lustbus.adr", "ADR")
f.address = ProtoField.uint8("lustbus.address", "Address", base.DEC)
f.broadcast = ProtoField.bool("lustbus.broadcast", "Broadcast (31: every device, no answer, 4.2)")
f.code = ProtoField.string("lustbus.code", "CODE")
f.family = ProtoField.string("lustbus.code.family", "Coded for")
f.specifier = ProtoField.string("lustbus.code.specifier", "Specifier")
f.dataset = ProtoField.uint8("lustbus.code.dataset", "Data set", base.DEC)
f.device = ProtoField.uint8("lustbus.code.device", "Device digit", base.DEC)
f.parameter = ProtoField.uint16("lustbus.code.parameter", "Parameter", base.DEC)
f.value = ProtoField.string("lustbus.value", "VALUE")
f.value_raw = ProtoField.uint32("lustbus.value.raw", "VALUE as a hex number", base.HEX_DEC)
f.posmod_status = ProtoField.uint8("lustbus.posmod.status", "PosMOD1 status byte (11.6.3)", base.HEX)
f.posmod_request = ProtoField.bool("lustbus.posmod.request", "Request telegram", 8, nil, 0x01)
f.posmod_multiblock = ProtoField.bool("lustbus.posmod.multiblock", "Multiblock telegram", 8, nil, 0x04)
f.bcc = ProtoField.uint8("lustbus.bcc", "BCC", base.HEX)
f.bcc_computed = ProtoField.uint8("lustbus.bcc.computed", "BCC computed (2.2)", base.HEX)
f.bcc_ok = ProtoField.bool("lustbus.bcc.ok", "BCC correct")
f.request_in = ProtoField.framenum("lustbus.request_in", "Request in frame")
f.response_in = ProtoField.framenum("lustbus.response_in", "Answer in frame")

local e_bcc = ProtoExpert.new("lustbus.bcc.bad", "BCC wrong", expert.group.CHECKSUM, expert.severity.ERROR)
local e_cut = ProtoExpert.new("lustbus.cut", "Telegram cut", expert.group.MALFORMED, expert.severity.WARN)
local e_noise = ProtoExpert.new("lustbus.noise", "No telegram of the LUSTBUS manual", expert.group.MALFORMED,
                                expert.severity.WARN)
local e_code = ProtoExpert.new("lustbus.code.bad", "No CODE of 2.4", expert.group.MALFORMED, expert.severity.WARN)
p.experts = { e_bcc, e_cut, e_noise, e_code }

local last_request = nil -- on the first pass: the host's last ENQUIRY or SELECT
local request_of = {}    -- answer frame -> request frame
local response_of = {}   -- request frame -> answer frame

function p.init()
  last_request = nil
  request_of = {}
  response_of = {}
end

local function hex2(b) return string.format("%02XH", b) end

-- ADR at `off`: 40H + address (2.2, 4.2).
local function add_adr(t, tvb, off)
  local b = tvb(off, 1):uint()
  local a = b - 0x40
  local item = t:add(f.adr, tvb(off, 1))
  item:append_text(string.format(" (%s): address %d", hex2(b), a))
  t:add(f.address, tvb(off, 1), a):set_generated()
  if a == 31 then t:add(f.broadcast, tvb(off, 1), true):set_generated() end
  return a
end

local function add_char(t, tvb, off)
  t:add(f.char, tvb(off, 1))
end

-- CODE: five decimal digits, coded by family (2.4.1, 2.4.2, 5.2, 11.3, 11.6). Returns its text.
local function add_code(t, tvb, off)
  local range = tvb(off, 5)
  local code = range:string()
  local item = t:add(f.code, range)
  if not code:match("^%d%d%d%d%d$") then
    item:add_proto_expert_info(e_code, "CODE is not five decimal digits (2.4)")
    return code
  end
  local d = {}
  for i = 1, 5 do d[i] = tonumber(code:sub(i, i)) end
  local what
  if code == "49999" then
    what = "MC6000 PosMOD1 channel (11.6)"
    item:add(f.family, range, "PosMOD1 (MC6000, 11.6)"):set_generated()
  elseif d[1] == 0 and d[2] == 0 and d[3] == 0 and shared[d[4] * 10 + d[5]] then
    local n = d[4] * 10 + d[5]
    what = string.format("parameter %d-%s of either family (5.2)", n, shared[n])
    item:add(f.family, range, "VF1000 and MC6000 (5.2)"):set_generated()
    item:add(f.specifier, range(0, 1), "value"):set_generated()
    item:add(f.parameter, range(3, 2), n):set_generated()
  elseif (d[1] == 0 or d[1] == 1) and d[2] == 0 and (d[3] == 0 or d[3] == 1) then
    local n = d[4] * 10 + d[5]
    local spec = d[1] == 0 and "value" or "description (11.1)"
    what = string.format("VF1000 parameter %d, %s", n, spec)
    item:add(f.family, range, "VF1000 (2.4.1)"):set_generated()
    item:add(f.specifier, range(0, 1), spec):set_generated()
    item:add(f.dataset, range(1, 1), d[2]):set_generated()
    item:add(f.device, range(2, 1), d[3]):set_generated()
    item:add(f.parameter, range(3, 2), n):set_generated()
  elseif (d[1] == 2 or d[1] == 3 or d[1] == 6) and d[2] == 0 then
    local n = d[3] * 100 + d[4] * 10 + d[5]
    local spec = ({ [2] = "value", [3] = "description (11.2)", [6] = "special function" })[d[1]]
    what = string.format("MC6000 parameter %d, %s", n, spec)
    item:add(f.family, range, "MC6000 (2.4.2)"):set_generated()
    item:add(f.specifier, range(0, 1), spec):set_generated()
    item:add(f.dataset, range(1, 1), d[2]):set_generated()
    item:add(f.parameter, range(2, 3), n):set_generated()
  elseif d[1] == 6 and d[2] == 1 then
    local n = d[3] * 100 + d[4] * 10 + d[5]
    what = string.format("MC6000 parameter %d, substitution text (11.3)", n)
    item:add(f.family, range, "MC6000 (11.3)"):set_generated()
    item:add(f.specifier, range(0, 2), "substitution text"):set_generated()
    item:add(f.parameter, range(2, 3), n):set_generated()
  else
    item:add_proto_expert_info(e_code, "no CODE of either family (2.4.1, 2.4.2)")
    return code
  end
  item:append_text(" (" .. what .. ")")
  return code
end

-- VALUE at [off, off + len): its characters and, for 1..8 hex digits, the number (2.3).
local function add_value(t, tvb, off, len, code)
  if len <= 0 then
    t:add(f.value, tvb(off, 0), "")
    return ""
  end
  local range = tvb(off, len)
  local text = range:string()
  local shown = text:gsub("[%c\128-\255]", function(c) return string.format("<%02X>", c:byte()) end)
  local item = t:add(f.value, range, shown)
  if text:match("^%x+$") and len <= 8 then
    item:add(f.value_raw, range, tonumber(text, 16)):set_generated()
  end
  if code == "49999" then
    local st = item:add(f.posmod_status, range(0, 1))
    st:add(f.posmod_request, range(0, 1))
    st:add(f.posmod_multiblock, range(0, 1))
  end
  return shown
end

-- STX CODE = VALUE ETX BCC from `stx` to the end; returns "CODE=VALUE" and whether the BCC is right.
local function add_text(t, tvb, stx)
  local n = tvb:len()
  add_char(t, tvb, stx)
  if n < stx + 6 then return "", nil end
  local code = add_code(t, tvb, stx + 1)
  if n < stx + 7 then return code, nil end
  t:add(tvb(stx + 6, 1), "= (3DH): between CODE and VALUE")
  local has_end = n >= stx + 9 and tvb(n - 2, 1):uint() == ETX
  local value_end = has_end and n - 2 or n
  local value = add_value(t, tvb, stx + 7, value_end - (stx + 7), code)
  if not has_end then return code .. "=" .. value, nil end
  add_char(t, tvb, n - 2)
  local x = 0
  for i = stx + 1, n - 2 do x = bit32.bxor(x, tvb(i, 1):uint()) end
  local bcc = tvb(n - 1, 1):uint()
  local item = t:add(f.bcc, tvb(n - 1, 1))
  t:add(f.bcc_computed, tvb(n - 1, 1), x):set_generated()
  t:add(f.bcc_ok, tvb(n - 1, 1), x == bcc):set_generated()
  if x == bcc then
    item:append_text(" [correct]")
  else
    item:append_text(string.format(" [wrong: should be %s]", hex2(x)))
    item:add_proto_expert_info(e_bcc, string.format("BCC %s wrong: should be %s (2.2)", hex2(bcc), hex2(x)))
  end
  return code .. "=" .. value, x == bcc, bcc, x
end

local function bcc_note(ok, bcc, x)
  if ok == nil then return "" end
  if ok then return " BCC ok" end
  return string.format(" BCC WRONG (%s, should be %s)", hex2(bcc), hex2(x))
end

local function host_telegram(tvb, pinfo, t)
  local n = tvb:len()
  if n == 1 and tvb(0, 1):uint() == EOT then
    add_char(t, tvb, 0)
    t:add(f.kind, "EOT"):set_generated()
    return "EOT", nil
  end
  if n < 2 or tvb(0, 1):uint() ~= EOT or tvb(1, 1):uint() < 0x40 or tvb(1, 1):uint() > 0x5F then
    return nil, nil
  end
  add_char(t, tvb, 0)
  local a = add_adr(t, tvb, 1)
  local adr = string.char(tvb(1, 1):uint())
  if n >= 3 and tvb(2, 1):uint() == STX then
    t:add(f.kind, "SELECT"):set_generated()
    local text, ok, bcc, x = add_text(t, tvb, 2)
    return string.format("SELECT %s %s%s", adr, text, bcc_note(ok, bcc, x)), { kind = "SELECT", address = a }
  end
  t:add(f.kind, "ENQUIRY"):set_generated()
  local code = ""
  if n >= 7 then code = add_code(t, tvb, 2) end
  if n >= 3 and tvb(n - 1, 1):uint() == ENQ then add_char(t, tvb, n - 1) end
  return string.format("ENQUIRY %s %s", adr, code), { kind = "ENQUIRY", address = a }
end

local function device_telegram(tvb, t)
  local n = tvb:len()
  if n < 1 or tvb(0, 1):uint() < 0x40 or tvb(0, 1):uint() > 0x5F then return nil end
  add_adr(t, tvb, 0)
  local adr = string.char(tvb(0, 1):uint())
  if n < 2 then
    t:add(f.kind, "answer"):set_generated()
    return "answer " .. adr
  end
  local c = tvb(1, 1):uint()
  if c == ACK or c == NAK then
    add_char(t, tvb, 1)
    t:add(f.kind, chars[c]):set_generated()
    return chars[c] .. " " .. adr
  end
  if c ~= STX then return nil end
  t:add(f.kind, "answer"):set_generated()
  local text, ok, bcc, x = add_text(t, tvb, 1)
  return string.format("answer %s %s%s", adr, text, bcc_note(ok, bcc, x))
end

function p.dissector(tvb, pinfo, tree)
  if tvb:len() < 8 then return 0 end
  pinfo.cols.protocol = "LUSTBUS"
  local dir = tvb(1, 1):uint()
  local flags = tvb(2, 1):uint()
  local t = tree:add(p, tvb(), "LUSTBUS (LUSTBUS manual), " .. (directions[dir] or "direction ?"))
  local h = t:add(tvb(0, 8), "ibs capture header")
  h:add(f.version, tvb(0, 1))
  h:add(f.direction, tvb(1, 1))
  local fl = h:add(f.flags, tvb(2, 1))
  fl:add(f.flag_check, tvb(2, 1))
  fl:add(f.flag_cut, tvb(2, 1))
  fl:add(f.flag_noise, tvb(2, 1))
  fl:add(f.flag_address, tvb(2, 1))
  if bit32.band(flags, 0x80) ~= 0 then h:add(f.header_address, tvb(3, 1)) end
  h:add(f.duration, tvb(4, 4))
  local body = tvb(8):tvb()
  local info, request
  if body:len() > 0 then
    if dir == 0 then
      info, request = host_telegram(body, pinfo, t)
    else
      info = device_telegram(body, t)
    end
  end
  if info == nil then
    t:add(f.kind, "noise"):set_generated()
    t:add_proto_expert_info(e_noise, "bytes that begin no telegram of the LUSTBUS manual (6.1, 6.2)")
    info = string.format("noise, %d byte(s)", body:len())
  end
  if bit32.band(flags, 0x02) ~= 0 then
    t:add_proto_expert_info(e_cut, "the telegram ended before it was complete")
    info = info .. " [cut]"
  end
  -- An answer belongs to the host's last ENQUIRY or SELECT (3); the host's EOT ends the exchange.
  if not pinfo.visited then
    if dir == 0 then
      last_request = request and { frame = pinfo.number } or nil
    elseif last_request then
      request_of[pinfo.number] = last_request.frame
      if not response_of[last_request.frame] then response_of[last_request.frame] = pinfo.number end
    end
  end
  if request_of[pinfo.number] then t:add(f.request_in, request_of[pinfo.number]):set_generated() end
  if response_of[pinfo.number] then t:add(f.response_in, response_of[pinfo.number]):set_generated() end
  pinfo.cols.info = (dir == 0 and "host   " or "device ") .. info
  return tvb:len()
end

DissectorTable.get("wtap_encap"):add(wtap_encaps.USER1, p)

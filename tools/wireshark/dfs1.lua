-- PowerTec DFS-1 (DFS-1 manual) captures of ibs (`ibs dfs1 ... --pcap`, `ibs run --dfs1-pcap`) for
-- Wireshark / tshark. Each packet is one frame of the line after an 8-byte header of ibs's own
-- (docs/pcap.md, "Serial lines"): version, direction (0 host, 1 controller), flags (bit 0 check
-- character wrong, bit 1 cut, bit 2 noise, bit 7 address present), address (the UID), the
-- frame's duration in microseconds. The frame DLE STX UID CMD [data] DLE ETX CSM is unstuffed
-- (a doubled 10H is one datum; the unstuffed bytes are a data source of their own), its checksum
-- checked (the 2's complement of the sum of UID, CMD and data, DFS1-E1; a wrong one is an expert
-- error), the command or the ACK/NAK named with the NAK's error, and the data read by command
-- (docs/dfs1.md, "Commands and responses"): speeds, parameter and channel numbers, values, and a
-- status response's speeds, load and the ST2 / ST1 bits by name. A response links to its request.
--
--   tshark -X lua_script:tools/wireshark/dfs1.lua -r capture.pcap -V
--
-- Captures: LINKTYPE_USER2 (149). This script registers itself for it.

local p = Proto("dfs1", "DFS-1 (ibs capture)")

local DLE, STX, ETX, ACK, NAK = 0x10, 0x02, 0x03, 0x06, 0x15
local directions = { [0] = "host to controller", [1] = "controller to host" }
local commands = { [0x81] = "status", [0x82] = "set speed", [0x83] = "execute speed",
                   [0x84] = "set and execute speed", [0x85] = "read parameter", [0x86] = "write parameter",
                   [0x87] = "read analog input", [0x88] = "read analog output", [0x89] = "write analog output",
                   [0x8A] = "read digital input", [0x8B] = "read digital output", [0x8C] = "write digital output",
                   [0x8D] = "set operational mode", [0x8E] = "read operational mode", [0x8F] = "application mode",
                   [ACK] = "ACK", [NAK] = "NAK" }
local errors = { [0x80] = "not in remote", [0x81] = "illegal speed", [0x82] = "illegal parameter number",
                 [0x83] = "illegal parameter value", [0x84] = "illegal channel", [0x85] = "illegal channel value",
                 [0x86] = "illegal command" }
-- The data bytes of each request (docs/dfs1.md, "Commands and responses"; dfs1/protocol.hpp's table).
local request_sizes = { [0x81] = 0, [0x82] = 4, [0x83] = 0, [0x84] = 4, [0x85] = 1, [0x86] = 5, [0x87] = 1,
                        [0x88] = 1, [0x89] = 5, [0x8A] = 1, [0x8B] = 1, [0x8C] = 5, [0x8D] = 4, [0x8E] = 0,
                        [0x8F] = 5 }
-- ST2 and ST1, bit 7 down (docs/dfs1.md, "Status"; devices/dfs1/status.cpp has the same names,
-- and the test WiresharkDissector.Dfs1StatusBitsAreTheControllers keeps the two equal).
local st2_names = { { 0x80, "remote" }, { 0x40, "slave" }, { 0x20, "at-speed" }, { 0x10, "forward" },
                    { 0x08, "fault" }, { 0x04, "enabled" }, { 0x02, "uP-fault" }, { 0x01, "zero-speed" } }
local st1_names = { { 0x80, "bus-not-charged" }, { 0x40, "IOC" }, { 0x20, "stall" }, { 0x10, "I2t" },
                    { 0x08, "heatsink-overtemp" }, { 0x04, "commutation" }, { 0x02, "overvolt" },
                    { 0x01, "undervolt" } }

local f = p.fields
f.version = ProtoField.uint8("dfs1.version", "Capture header version", base.DEC)
f.direction = ProtoField.uint8("dfs1.direction", "Direction", base.DEC, directions)
f.flags = ProtoField.uint8("dfs1.flags", "Recorder's flags", base.HEX)
f.flag_check = ProtoField.bool("dfs1.flags.check_bad", "Checksum wrong (as recorded)", 8, nil, 0x01)
f.flag_cut = ProtoField.bool("dfs1.flags.cut", "Cut (ended before it was complete)", 8, nil, 0x02)
f.flag_noise = ProtoField.bool("dfs1.flags.noise", "Noise (no frame)", 8, nil, 0x04)
f.flag_address = ProtoField.bool("dfs1.flags.address", "Address present", 8, nil, 0x80)
f.header_address = ProtoField.uint8("dfs1.header_address", "UID (as recorded)", base.DEC)
f.duration = ProtoField.uint32("dfs1.duration", "Duration, first byte to last (us)", base.DEC)
f.kind = ProtoField.string("dfs1.kind", "Frame")
f.start = ProtoField.uint16("dfs1.start", "DLE STX", base.HEX)
f.stop = ProtoField.uint16("dfs1.end", "DLE ETX", base.HEX)
f.uid = ProtoField.uint8("dfs1.uid", "UID", base.DEC)
f.global = ProtoField.bool("dfs1.global", "Global (UID 0: command 83 to every controller, no response)")
f.command = ProtoField.uint8("dfs1.command", "Command", base.HEX, commands)
f.response = ProtoField.uint8("dfs1.response", "Response", base.HEX, commands)
f.error = ProtoField.uint8("dfs1.error", "Error", base.HEX, errors)
f.speed = ProtoField.int32("dfs1.speed", "Speed (rpm)", base.DEC)
f.parameter = ProtoField.uint8("dfs1.parameter", "Parameter", base.DEC)
f.channel = ProtoField.uint8("dfs1.channel", "Channel", base.DEC)
f.mode = ProtoField.uint8("dfs1.application_mode", "Application mode", base.DEC, { [0] = "master", [1] = "slave" })
f.value = ProtoField.uint32("dfs1.value", "Value", base.DEC_HEX)
f.mask = ProtoField.uint16("dfs1.input_mask", "Digital inputs switched remote (SMH SML)", base.HEX)
f.commanded = ProtoField.int32("dfs1.status.commanded", "Commanded speed (rpm)", base.DEC)
f.actual = ProtoField.int32("dfs1.status.actual", "Actual speed (rpm)", base.DEC)
f.load = ProtoField.uint32("dfs1.status.load", "Load (%)", base.DEC)
f.st2 = ProtoField.uint8("dfs1.st2", "ST2", base.HEX)
f.st1 = ProtoField.uint8("dfs1.st1", "ST1", base.HEX)
f.st2_flags = ProtoField.string("dfs1.st2.flags", "ST2 bits set")
f.st1_flags = ProtoField.string("dfs1.st1.flags", "ST1 bits set")
for _, b in ipairs(st2_names) do
  f["st2_" .. b[2]] = ProtoField.bool("dfs1.st2." .. b[2]:gsub("-", "_"), b[2], 8, nil, b[1])
end
for _, b in ipairs(st1_names) do
  f["st1_" .. b[2]] = ProtoField.bool("dfs1.st1." .. b[2]:gsub("-", "_"), b[2], 8, nil, b[1])
end
f.data = ProtoField.bytes("dfs1.data", "Data (unstuffed)")
f.checksum = ProtoField.uint8("dfs1.checksum", "CSM", base.HEX)
f.checksum_computed = ProtoField.uint8("dfs1.checksum.computed", "CSM computed", base.HEX)
f.checksum_ok = ProtoField.bool("dfs1.checksum.ok", "CSM correct")
f.request_in = ProtoField.framenum("dfs1.request_in", "Request in frame")
f.response_in = ProtoField.framenum("dfs1.response_in", "Response in frame")

local e_csm = ProtoExpert.new("dfs1.checksum.bad", "CSM wrong", expert.group.CHECKSUM, expert.severity.ERROR)
local e_cut = ProtoExpert.new("dfs1.cut", "Frame cut", expert.group.MALFORMED, expert.severity.WARN)
local e_noise = ProtoExpert.new("dfs1.noise", "No frame of the DFS-1 manual", expert.group.MALFORMED, expert.severity.WARN)
local e_nak = ProtoExpert.new("dfs1.nak", "NAK", expert.group.RESPONSE_CODE, expert.severity.NOTE)
local e_length = ProtoExpert.new("dfs1.length", "Data length not that of the command", expert.group.MALFORMED,
                                 expert.severity.WARN)
p.experts = { e_csm, e_cut, e_noise, e_nak, e_length }

local last_request = {} -- UID -> { frame, command }, on the first pass
local request_of = {}   -- response frame -> { frame, command }
local response_of = {}  -- request frame -> response frame

function p.init()
  last_request = {}
  request_of = {}
  response_of = {}
end

-- DLE STX ... DLE ETX CSM: the unstuffed body (UID, CMD, data) with each byte's offset in the
-- frame, where DLE ETX begins, the CSM's offset and value (nil when the frame is cut before them).
local function unstuff(tvb)
  local n = tvb:len()
  local body, at = {}, {}
  local i = 2
  while i < n do
    local b = tvb(i, 1):uint()
    if b == DLE then
      if i + 1 >= n then return body, at, nil end
      local c = tvb(i + 1, 1):uint()
      if c == ETX then
        if i + 2 >= n then return body, at, i end
        return body, at, i, i + 2, tvb(i + 2, 1):uint()
      end
      if c ~= DLE then return body, at, nil end -- a lone DLE: a broken frame
      body[#body + 1] = DLE
      at[#at + 1] = i
      i = i + 2
    else
      body[#body + 1] = b
      at[#at + 1] = i
      i = i + 1
    end
  end
  return body, at, nil
end

local function s32(range) return range:int() end

-- The data of a request of `cmd` (docs/dfs1.md, "Commands and responses").
local function request_data(t, d, cmd)
  local n = d and d:len() or 0
  local info = ""
  if cmd == 0x82 or cmd == 0x84 then
    if n >= 4 then
      t:add(f.speed, d(0, 4), s32(d(0, 4)))
      info = string.format(" %d rpm", s32(d(0, 4)))
    end
  elseif cmd == 0x85 or cmd == 0x86 then
    if n >= 1 then
      t:add(f.parameter, d(0, 1))
      info = string.format(" %d", d(0, 1):uint())
    end
    if cmd == 0x86 and n >= 5 then
      t:add(f.value, d(1, 4))
      info = info .. string.format(" = %d", d(1, 4):uint())
    end
  elseif cmd >= 0x87 and cmd <= 0x8C then
    if n >= 1 then
      t:add(f.channel, d(0, 1))
      info = string.format(" channel %d", d(0, 1):uint())
    end
    if (cmd == 0x89 or cmd == 0x8C) and n >= 5 then
      t:add(f.value, d(1, 4))
      info = info .. string.format(" = %d", d(1, 4):uint())
    end
  elseif cmd == 0x8D then
    if n >= 4 then
      t:add(f.mask, d(2, 2))
      info = string.format(" mask %04X", d(2, 2):uint())
    end
  elseif cmd == 0x8F then
    if n >= 1 then
      t:add(f.mode, d(0, 1))
      info = " " .. (d(0, 1):uint() == 1 and "slave" or "master")
    end
    if n >= 5 then t:add(f.value, d(1, 4)) end
  end
  return info
end

local function bits(t, field, flag_fields, names, range, prefix)
  local v = range:uint()
  local item = t:add(field, range)
  local set = {}
  for _, b in ipairs(names) do
    item:add(flag_fields[prefix .. b[2]], range)
    if bit32.band(v, b[1]) ~= 0 then set[#set + 1] = b[2] end
  end
  local text = #set > 0 and table.concat(set, " ") or "none"
  item:append_text(" (" .. text .. ")")
  t:add(prefix == "st2_" and f.st2_flags or f.st1_flags, range, text):set_generated()
  return text
end

-- The data of an ACK answering `cmd` (`arg`: the request's parameter or channel number).
local function response_data(t, d, cmd, arg)
  local n = d and d:len() or 0
  if cmd == 0x81 and n >= 16 then
    t:add(f.commanded, d(0, 4), s32(d(0, 4)))
    t:add(f.actual, d(4, 4), s32(d(4, 4)))
    t:add(f.load, d(8, 4))
    local st2 = bits(t, f.st2, f, st2_names, d(14, 1), "st2_")
    local st1 = bits(t, f.st1, f, st1_names, d(15, 1), "st1_")
    return string.format(" status: commanded %d rpm, actual %d rpm, load %d %%, ST2 %s, ST1 %s", s32(d(0, 4)),
                         s32(d(4, 4)), d(8, 4):uint(), st2, st1)
  end
  if cmd == 0x8E and n >= 4 then
    t:add(f.mask, d(2, 2))
    return string.format(" mask %04X", d(2, 2):uint())
  end
  if (cmd == 0x85 or (cmd >= 0x87 and cmd <= 0x8B)) and n >= 4 then
    t:add(f.value, d(0, 4))
    return string.format(" %s%s = %d", cmd == 0x85 and "parameter" or commands[cmd], arg and " " .. arg or "",
                         d(0, 4):uint())
  end
  return ""
end

function p.dissector(tvb, pinfo, tree)
  if tvb:len() < 8 then return 0 end
  pinfo.cols.protocol = "DFS-1"
  local dir = tvb(1, 1):uint()
  local flags = tvb(2, 1):uint()
  local t = tree:add(p, tvb(), "DFS-1 (DFS-1 manual), " .. (directions[dir] or "direction ?"))
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
  local fr = tvb(8):tvb()
  local prefix = dir == 0 and "host       " or "controller "
  local cut = bit32.band(flags, 0x02) ~= 0
  if fr:len() < 2 or fr(0, 1):uint() ~= DLE or fr(1, 1):uint() ~= STX then
    t:add(f.kind, "noise"):set_generated()
    t:add_proto_expert_info(e_noise, "bytes outside DLE STX ... CSM (DFS-1 manual 6.0)")
    pinfo.cols.info = prefix .. string.format("noise, %d byte(s)", fr:len())
    return tvb:len()
  end
  t:add(f.start, fr(0, 2))
  local body, at, etx, csm_at, csm = unstuff(fr)
  local unstuffed = ByteArray.new()
  unstuffed:set_size(#body)
  for i, b in ipairs(body) do unstuffed:set_index(i - 1, b) end
  local info
  local uid, code
  if #body >= 1 then
    uid = body[1]
    t:add(f.uid, fr(at[1], 1), uid)
    if uid == 0 then t:add(f.global, fr(at[1], 1), true):set_generated() end
  end
  local d = nil
  if #body >= 2 then
    code = body[2]
    local is_response = code == ACK or code == NAK
    t:add(is_response and f.response or f.command, fr(at[2], 1), code)
    t:add(f.kind, is_response and (code == ACK and "ACK" or "NAK") or "request"):set_generated()
    if #body > 2 then
      local dtvb = unstuffed:tvb("Unstuffed DFS-1 frame")
      d = dtvb(2, #body - 2)
      t:add(f.data, d)
    end
    info = string.format("UID %d %s", uid, commands[code] or string.format("command %02X", code))
    if code == NAK then
      if d then
        t:add(f.error, d(0, 1))
        info = info .. string.format(" %02X %s", d(0, 1):uint(), errors[d(0, 1):uint()] or "unknown error")
      end
      t:add_proto_expert_info(e_nak, info)
    elseif not is_response then
      info = info .. request_data(t, d, code)
      local want = request_sizes[code]
      if want and want ~= #body - 2 and csm_at then
        t:add_proto_expert_info(e_length, string.format("%d data byte(s); %s takes %d", #body - 2, commands[code], want))
      end
    end
    -- A response belongs to the last request to its UID.
    if not pinfo.visited then
      if not is_response then
        last_request[uid] = { frame = pinfo.number, command = code, arg = d and d(0, 1):uint() or nil }
      elseif last_request[uid] then
        request_of[pinfo.number] = last_request[uid]
        response_of[last_request[uid].frame] = pinfo.number
        last_request[uid] = nil
      end
    end
    local rq = request_of[pinfo.number]
    if rq then
      t:add(f.request_in, rq.frame):set_generated()
      if code == ACK then info = info .. response_data(t, d, rq.command, rq.arg) end
    end
    if response_of[pinfo.number] then t:add(f.response_in, response_of[pinfo.number]):set_generated() end
  else
    t:add(f.kind, "frame"):set_generated()
    info = "frame"
  end
  if etx then t:add(f.stop, fr(etx, 2)) end
  if csm_at then
    local sum = 0
    for _, b in ipairs(body) do sum = sum + b end
    local computed = bit32.band(0x100 - bit32.band(sum, 0xFF), 0xFF)
    local item = t:add(f.checksum, fr(csm_at, 1))
    t:add(f.checksum_computed, fr(csm_at, 1), computed):set_generated()
    t:add(f.checksum_ok, fr(csm_at, 1), computed == csm):set_generated()
    if computed == csm then
      item:append_text(" [correct]")
    else
      item:append_text(string.format(" [wrong: should be %02XH]", computed))
      item:add_proto_expert_info(e_csm, string.format("CSM %02XH wrong: should be %02XH (the 2's complement of the sum)",
                                                      csm, computed))
      info = info .. string.format(" CSM WRONG (%02XH, should be %02XH)", csm, computed)
    end
  end
  if cut or not csm_at then
    t:add_proto_expert_info(e_cut, "the frame ended before its DLE ETX CSM")
    info = info .. " [cut]"
  end
  pinfo.cols.info = prefix .. info
  return tvb:len()
end

DissectorTable.get("wtap_encap"):add(wtap_encaps.USER2, p)

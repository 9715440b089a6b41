-- CANLust (LUST CM-CAN1, CANLust manual) dissector for Wireshark / tshark, on top of the CAN dissector.
-- It registers on the `can.id` table for every CANLust identifier: base + step x address for
-- error 441, logon 1543, control 661, status 881, parameter request 1101, reply 1321, and the
-- broadcast 221 (docs/canlust.md). The step (2, decision D1 / erratum CAN-E1) is a preference.
--
--   tshark -X lua_script:tools/wireshark/canlust.lua -r capture.pcap -V
--
-- Captures: LINKTYPE_CAN_SOCKETCAN (227), e.g. written by ibs::can::PcapWriter or candump -l.

local p = Proto("canlust", "CANLust (LUST CM-CAN1)")

local kinds = { [0] = "error", [1] = "logon", [2] = "control", [3] = "status",
                [4] = "parameter request", [5] = "parameter reply", [6] = "system start/stop" }
local bases = { {441, 0}, {1543, 1}, {661, 2}, {881, 3}, {1101, 4}, {1321, 5} }
local modes = { [2] = "SEL (write)", [4] = "ENQUIRY_List (describe)", [5] = "ENQ (read)",
                [8] = "SELECT_String", [11] = "ENQUIRY_String", [16] = "List_End" }

local f = p.fields
f.kind = ProtoField.uint8("canlust.kind", "Telegram", base.DEC, kinds)
f.address = ProtoField.uint8("canlust.address", "Address", base.DEC)
f.system = ProtoField.uint8("canlust.system", "System command", base.HEX,
                            { [0] = "System Stop", [1] = "System Start" })
f.control = ProtoField.uint16("canlust.control", "Control word", base.HEX)
f.status_word = ProtoField.uint16("canlust.status_word", "Status word", base.HEX)
f.value16 = ProtoField.int16("canlust.value16", "Value (Int16Q0)", base.DEC)
f.value32 = ProtoField.int32("canlust.value32", "Value (raw Q16)", base.DEC)
f.q16 = ProtoField.double("canlust.q16", "Value (Q16)")
f.param = ProtoField.uint16("canlust.parameter", "Parameter number", base.DEC)
f.mode = ProtoField.uint8("canlust.mode", "Mode", base.DEC, modes)
f.pstatus = ProtoField.uint8("canlust.status", "Reply status", base.HEX)
f.st_watchdog = ProtoField.bool("canlust.status.watchdog", "Watchdog", 8, nil, 0x02)
f.st_mode = ProtoField.bool("canlust.status.unknown_mode", "Unknown mode", 8, nil, 0x04)
f.st_read = ProtoField.bool("canlust.status.read_not_permitted", "Read not permitted", 8, nil, 0x08)
f.st_repeat = ProtoField.bool("canlust.status.repeat", "Repeat / List_End", 8, nil, 0x10)
f.st_param = ProtoField.bool("canlust.status.unknown_parameter", "Unknown parameter", 8, nil, 0x20)
f.st_change = ProtoField.bool("canlust.status.change_not_permitted", "Change not permitted", 8, nil, 0x40)
f.st_value = ProtoField.bool("canlust.status.impermissible_value", "Impermissible value", 8, nil, 0x80)
f.data = ProtoField.uint32("canlust.data", "Data (bytes 3-6)", base.HEX)
f.text = ProtoField.string("canlust.text", "Characters")
f.block = ProtoField.uint8("canlust.block", "Block counter / index", base.DEC)
f.err_number = ProtoField.uint8("canlust.error.number", "Error number", base.DEC,
  { [8] = "E-OTI", [9] = "E-PLS", [10] = "E-PAR", [11] = "E-FLT", [12] = "E-PWR", [16] = "E-OP2" })
f.err_location = ProtoField.uint8("canlust.error.location", "Error location", base.DEC)
f.err_reaction = ProtoField.uint8("canlust.error.reaction", "Error reaction", base.DEC,
  { [0] = "WRN", [1] = "STOP", [2] = "quick stop", [3] = "disable power" })

f.state = ProtoField.string("canlust.drivecom_state", "DRIVECOM state")
f.command = ProtoField.string("canlust.drivecom_command", "DRIVECOM command")
f.pname = ProtoField.string("canlust.parameter_name", "CDA3000 parameter")
f.ptype = ProtoField.string("canlust.data_type", "Data type")
f.value = ProtoField.double("canlust.value", "Value")
f.unit = ProtoField.string("canlust.unit", "Unit")
f.err_hours = ProtoField.uint16("canlust.error.hours", "Operating hours", base.DEC)
f.desc_type = ProtoField.string("canlust.description.data_type", "Description: data type")
f.item = ProtoField.uint8("canlust.description_item", "Description item", base.DEC)
f.checksum = ProtoField.uint32("canlust.checksum", "String checksum (XOR of the blocks)", base.HEX)
f.request_in = ProtoField.framenum("canlust.request_in", "Request in frame")

-- DRIVECOM (the CDA3000 with 492-CACNF 1..3): the state table of the status word and the command
-- table of the control word (INTERBUS manual 5.1.2 / 5.1.3; drivecom/), rows as mask, value, name.
local states = { {0x4F, 0x00, "NOT READY"}, {0x4F, 0x40, "START-UP INHIBIT"}, {0x6F, 0x21, "READY"},
                 {0x6F, 0x23, "ON"}, {0x6F, 0x27, "ENABLED"}, {0x4F, 0x08, "FAULT"},
                 {0x4F, 0x0F, "FAULT RESPONSE ACTIVE"}, {0x6F, 0x07, "EMERGENCY STOP ACTIVE"} }
local commands = { {0x02, 0x00, "BLOCK POWER"}, {0x06, 0x02, "EMERGENCY STOP"}, {0x07, 0x06, "SHUTDOWN"},
                   {0x0F, 0x07, "POWER-ON/DISABLE"}, {0x0F, 0x0F, "POWER-ON/ENABLE"} }
local function lookup(rows, word)
  for _, r in ipairs(rows) do
    if bit32.band(word, r[1]) == r[2] then return r[3] end
  end
  return "no DRIVECOM state"
end

-- The CDA3000's parameters: display name, data type (CANLust manual 4.1.1) and unit, as the wing's
-- table has them (devices/cda3000/parameters.hpp; the test CanlustDissector.ParameterTableIsTheWings
-- keeps the two equal). The type says how data bytes 3-6 of a value read, written or echoed are
-- shown: INT32Q16 406-REFF as "-12.25 Hz".
local cda3000 = {
  [4] = { "04-PROG", "USIGN8", "" }, [80] = { "80-SLOAD", "INT16", "" }, [90] = { "90-NAME", "STRING", "" },
  [95] = { "95-ERR1", "ERR_STRUC", "" }, [150] = { "150-SAVE", "USIGN8", "" }, [151] = { "151-ASTPR", "USIGN8", "" },
  [152] = { "152-ASTER", "USIGN8", "" }, [180] = { "180-FISA0", "USIGN8", "" }, [260] = { "260-CLSEL", "USIGN8", "" },
  [280] = { "280-RSSL1", "USIGN8", "" }, [360] = { "360-DISP", "USIGN16", "" }, [406] = { "406-REFF", "INT32Q16", "Hz" },
  [489] = { "489-CLBDR", "USIGN16", "kBaud" }, [492] = { "492-CACNF", "USIGN8", "" }, [520] = { "520-ROTI", "USIGN8", "" },
  [521] = { "521-RPLS", "USIGN8", "" }, [522] = { "522-RPAR", "USIGN8", "" }, [523] = { "523-RFLT", "USIGN8", "" },
  [524] = { "524-RPWR", "USIGN8", "" }, [525] = { "525-ROP2", "USIGN8", "" }, [570] = { "570-CAMOD", "USIGN8", "" },
  [571] = { "571-CLADR", "USIGN8", "" }, [574] = { "574-CAWDG", "USIGN8", "ms" }, [575] = { "575-CASCY", "USIGN16", "ms" },
  [576] = { "576-CAWMK", "USIGN16", "" }, [577] = { "577-CAWRN", "USIGN16", "" }, [578] = { "578-OPTN2", "STRING", "" },
  [651] = { "651-CDSSL", "USIGN8", "" },
}
-- canlust::DataType's codes (data_types.hpp), item 0 of a description.
local type_codes = { [0] = "USIGN8", [1] = "INT8", [2] = "USIGN16", [3] = "INT16", [4] = "USIGN32", [5] = "INT32",
                     [6] = "INT32Q16", [7] = "FIXPOINT16", [8] = "ERR_STRUC", [9] = "STRING" }
-- The CDA3000's description items (mode 04; devices/cda3000/description.hpp, decision D29).
local describe_items = { [0] = "data type", [1] = "minimum", [2] = "maximum", [3] = "factory setting",
                         [4] = "attributes", [5] = "name, characters 1-4", [6] = "name, characters 5-8",
                         [7] = "unit" }

p.prefs.step = Pref.uint("Identifier step", 2, "identifier = base + step x address (1: the text, 2: the examples)")
p.prefs.max_address = Pref.uint("Highest address", 99, "addresses 0..N")
p.prefs.value32 = Pref.bool("32-bit values", true, "control/status carry a Q16 32-bit value (492-CACNF 2..4)")
p.prefs.drivecom = Pref.bool("DRIVECOM words", true, "control/status words are DRIVECOM (492-CACNF 1..3), not EasyDrive")

local table_ids = {}

local function classify(id)
  if id == 221 then return 6, 0 end
  local step = p.prefs.step
  for _, b in ipairs(bases) do
    local off = id - b[1]
    if off >= 0 and off % step == 0 and off / step <= p.prefs.max_address then
      return b[2], off / step
    end
  end
  return nil, nil
end

-- The request a reply answers: the last request to the same address before it, taken on the
-- first pass in frame order (every request gets exactly one reply, CAL; CANLust manual 4.5). A
-- reply's data bytes mean what the request asked for: a value, a description item, characters of
-- a string or its checksum.
local last_request = {}  -- address -> { frame, parameter, mode }
local request_of = {}    -- reply frame -> that request

function p.init()
  last_request = {}
  request_of = {}
end

-- A number as written: integers whole, others without trailing zeros.
local function fmt(v)
  if v == math.floor(v) and math.abs(v) < 2 ^ 53 then return string.format("%d", v) end
  local s = string.format("%.6f", v):gsub("0+$", ""):gsub("%.$", "")
  return s
end

-- Bytes 3-6 as a value of `ptype` (4.1.1; data_types.hpp): nil for STRING and ERR_STRUC.
local function number_of(range, ptype)
  if ptype == "INT8" or ptype == "INT16" or ptype == "INT32" then return range:le_int() end
  if ptype == "INT32Q16" then return range:le_int() / 65536 end
  if ptype == "FIXPOINT16" then return range:le_uint() / 20 end
  if ptype == "USIGN8" or ptype == "USIGN16" or ptype == "USIGN32" then return range:le_uint() end
  return nil
end

-- The characters of bytes 3-6 up to the first NUL (a string block, a text item of a description).
local function chars(range)
  local out = {}
  for i = 0, range:len() - 1 do
    local c = range(i, 1):uint()
    if c == 0 then break end
    out[#out + 1] = string.char(c)
  end
  return table.concat(out)
end

-- A value of parameter row `row` (nil: not a CDA3000 parameter, shown as data only). Returns the
-- text for the Info column.
local function add_value(t, range, row, label)
  if not row then return "" end
  local ptype, unit = row[2], row[3]
  if ptype == "ERR_STRUC" then
    -- 4.1.1: error number, location, operating hours low, high (E-OP2 at 172 after 85 h = 10 AC 55 00).
    local number, location, hours = range(0, 1):uint(), range(1, 1):uint(), range(2, 2):le_uint()
    t:add(f.err_number, range(0, 1))
    t:add(f.err_location, range(1, 1))
    t:add_le(f.err_hours, range(2, 2))
    return string.format(" = error %d at %d after %d h", number, location, hours)
  end
  local v = number_of(range, ptype)
  if v == nil then return "" end
  local text = fmt(v) .. (unit ~= "" and " " .. unit or "")
  t:add(f.value, range, v):set_text(string.format("%s: %s (%s)", label, text, ptype))
  if unit ~= "" then t:add(f.unit, unit):set_generated() end
  return " = " .. text
end

-- Data bytes 3-6 of a parameter request (kind 4) or reply (kind 5) by what was asked for.
local function add_data(tvb, pinfo, t, kind, address)
  local number, code, block = tvb(0, 2):le_uint(), tvb(2, 1):uint(), tvb(7, 1):uint()
  local data = tvb(3, 4)
  local row = cda3000[number]
  if row then t:add(f.ptype, row[2]):set_generated() end
  local mode, status = code, nil
  if kind == 4 then
    if not pinfo.visited then last_request[address] = { frame = pinfo.number, parameter = number, mode = code } end
  else
    if not pinfo.visited then
      local rq = last_request[address]
      if rq and rq.parameter == number then request_of[pinfo.number] = rq end
      last_request[address] = nil
    end
    local rq = request_of[pinfo.number]
    if not rq then return "" end  -- the capture began after the request: the data stay raw
    t:add(f.request_in, rq.frame):set_generated()
    mode, status = rq.mode, code
  end
  -- String transfer (4.5.x): the List_End telegram carries the checksum, the others 4 characters.
  if (kind == 4 and mode == 16) or (kind == 5 and mode == 11 and status == 16) then
    t:add_le(f.checksum, data)
    return string.format(" checksum %08X", data:le_uint())
  end
  if status ~= nil and status ~= 0 then return "" end
  if mode == 2 then
    return add_value(t, data, row, kind == 4 and "Value written" or "Value written (echo)")
  elseif mode == 5 and kind == 5 then
    return add_value(t, data, row, "Value read")
  elseif mode == 4 then
    t:add(f.item, tvb(7, 1)):append_text(" (" .. (describe_items[block] or "none: List_End") .. ")")
    if kind == 4 then return "" end
    if block == 0 then
      local name = type_codes[data:le_uint()] or "?"
      t:add(f.desc_type, data, name)
      return " = " .. name
    elseif block >= 1 and block <= 3 then
      return add_value(t, data, row, "Description: " .. describe_items[block])
    elseif block >= 5 and block <= 7 then
      local text = chars(data)
      t:add(f.text, data, text)
      return string.format(" = \"%s\"", text)
    end
  elseif (mode == 11 and kind == 5) or (mode == 8 and block >= 1) then
    local text = chars(data)
    t:add(f.text, data, text)
    return string.format(" \"%s\"", text)
  end
  return ""
end

function p.dissector(tvb, pinfo, tree)
  local can_id = pinfo.match_uint
  local kind, address = classify(can_id)
  if kind == nil then return 0 end
  pinfo.cols.protocol = "CANLust"
  local t = tree:add(p, tvb(), "CANLust (LUST CM-CAN1), " .. kinds[kind])
  t:add(f.kind, kind):set_generated()
  if kind ~= 6 then t:add(f.address, address):set_generated() end
  local n = tvb:len()
  local info = kinds[kind]
  if kind == 6 and n >= 1 then
    t:add(f.system, tvb(0, 1))
    info = (tvb(0, 1):uint() == 1) and "System Start" or "System Stop"
  elseif (kind == 2 or kind == 3) and n >= 2 then
    t:add_le(kind == 2 and f.control or f.status_word, tvb(0, 2))
    local word = tvb(0, 2):le_uint()
    local meaning = ""
    if p.prefs.drivecom then
      meaning = (kind == 2) and lookup(commands, word) or lookup(states, word)
      t:add(kind == 2 and f.command or f.state, meaning):set_generated()
      meaning = " " .. meaning
    end
    if p.prefs.value32 and n >= 6 then
      t:add_le(f.value32, tvb(2, 4))
      t:add(f.q16, tvb(2, 4):le_int() / 65536.0):set_generated()
    elseif n >= 4 then
      t:add_le(f.value16, tvb(2, 2))
    end
    info = string.format("%s %d: word %04X%s", kinds[kind], address, word, meaning)
  elseif (kind == 4 or kind == 5) and n >= 8 then
    t:add_le(f.param, tvb(0, 2))
    local row = cda3000[tvb(0, 2):le_uint()]
    if row then t:add(f.pname, row[1]):set_generated() end
    if kind == 4 then
      t:add(f.mode, tvb(2, 1))
    else
      local st = t:add(f.pstatus, tvb(2, 1))
      st:add(f.st_watchdog, tvb(2, 1)); st:add(f.st_mode, tvb(2, 1)); st:add(f.st_read, tvb(2, 1))
      st:add(f.st_repeat, tvb(2, 1)); st:add(f.st_param, tvb(2, 1)); st:add(f.st_change, tvb(2, 1))
      st:add(f.st_value, tvb(2, 1))
    end
    t:add_le(f.data, tvb(3, 4))
    t:add(f.block, tvb(7, 1))
    info = string.format("%s %d: parameter %d %s %02X data %08X block %d", kinds[kind], address,
                         tvb(0, 2):le_uint(), kind == 4 and "mode" or "status", tvb(2, 1):uint(),
                         tvb(3, 4):le_uint(), tvb(7, 1):uint())
    info = info .. add_data(tvb, pinfo, t, kind, address)
  elseif kind == 0 and n >= 3 then
    t:add(f.err_number, tvb(0, 1))
    t:add(f.err_location, tvb(1, 1))
    t:add(f.err_reaction, tvb(2, 1))
    info = string.format("error %d: number %d location %d", address, tvb(0, 1):uint(), tvb(1, 1):uint())
  elseif kind == 1 then
    info = string.format("logon %d", address)
  end
  pinfo.cols.info = info
  return n
end

local function register()
  local dt = DissectorTable.get("can.id")
  for id, _ in pairs(table_ids) do dt:remove(id, p) end
  table_ids = {}
  local ids = { 221 }
  for _, b in ipairs(bases) do
    for a = 0, p.prefs.max_address do
      local id = b[1] + p.prefs.step * a
      if id <= 0x7FF then ids[#ids + 1] = id end
    end
  end
  for _, id in ipairs(ids) do
    dt:add(id, p)
    table_ids[id] = true
  end
end

function p.prefs_changed() register() end
register()

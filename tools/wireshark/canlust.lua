-- CANLust (LUST CM-CAN1, seed 003) dissector for Wireshark / tshark, on top of the CAN dissector.
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

-- DRIVECOM (the CDA3000 with 492-CACNF 1..3): the state table of the status word and the command
-- table of the control word (seed 001, 5.1.2 / 5.1.3; drivecom/), rows as mask, value, name.
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

-- The CDA3000's parameter names (devices/cda3000/parameters.hpp; the test
-- CanlustDissector.ParameterNamesAreTheWings keeps the two equal).
local cda3000 = {
  [4] = "04-PROG", [80] = "80-SLOAD", [90] = "90-NAME", [95] = "95-ERR1", [150] = "150-SAVE", [151] = "151-ASTPR", [152] = "152-ASTER",
  [180] = "180-FISA0", [260] = "260-CLSEL", [280] = "280-RSSL1", [360] = "360-DISP", [406] = "406-REFF",
  [489] = "489-CLBDR", [492] = "492-CACNF", [520] = "520-ROTI", [521] = "521-RPLS", [522] = "522-RPAR",
  [523] = "523-RFLT", [524] = "524-RPWR", [525] = "525-ROP2", [570] = "570-CAMOD", [571] = "571-CLADR",
  [574] = "574-CAWDG", [575] = "575-CASCY", [576] = "576-CAWMK", [577] = "577-CAWRN", [578] = "578-OPTN2",
  [651] = "651-CDSSL",
}

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
    local name = cda3000[tvb(0, 2):le_uint()]
    if name then t:add(f.pname, name):set_generated() end
    if kind == 4 then
      t:add(f.mode, tvb(2, 1))
    else
      local st = t:add(f.pstatus, tvb(2, 1))
      st:add(f.st_watchdog, tvb(2, 1)); st:add(f.st_mode, tvb(2, 1)); st:add(f.st_read, tvb(2, 1))
      st:add(f.st_repeat, tvb(2, 1)); st:add(f.st_param, tvb(2, 1)); st:add(f.st_change, tvb(2, 1))
      st:add(f.st_value, tvb(2, 1))
    end
    t:add_le(f.data, tvb(3, 4))
    t:add(f.text, tvb(3, 4))
    t:add(f.block, tvb(7, 1))
    info = string.format("%s %d: parameter %d %s %02X data %08X block %d", kinds[kind], address,
                         tvb(0, 2):le_uint(), kind == 4 and "mode" or "status", tvb(2, 1):uint(),
                         tvb(3, 4):le_uint(), tvb(7, 1):uint())
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

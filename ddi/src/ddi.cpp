// The DDI's calls (ibs/ddi.h) over the virtual board. The board is the process's one piece of
// hardware: it starts with the first node opened and stops when the last one closes, so a
// program (or a test) that closes everything and opens again gets a new board that reads the
// environment anew. All state lives in one Driver object behind one lock.
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <string_view>
#include <vector>

#include "board.hpp"
#include "ibs/ddi.h"
#include "ibs_util.h"  // the legacy diagnostic calls (ddi/include/ibs/phoenix)

namespace {

using ibs::ddi::Board;

struct Node {
  int kind = DDI_NODE_DATA;
  int perm = DDI_RW;
};

struct Driver {
  std::mutex mutex;  // the node table and the board's lifetime; the board's own lock for the rest
  std::map<IBDDIHND, Node> nodes;
  IBDDIHND next = 1;
  std::unique_ptr<Board> board;
};

Driver& driver() {
  static Driver d;
  return d;
}

// A board or node number: one or two digits whose value is 1 ("1", "01"), the forms of the ISA /
// PCI boards' names (IBB1N1_D) and of the Ethernet controllers' (IBETH01N1_D).
bool is_one(std::string_view digits) { return digits == "1" || digits == "01"; }

bool all_digits(std::string_view s) {
  return !s.empty() && s.size() <= 2 && s.find_first_not_of("0123456789") == std::string_view::npos;
}

// "IBB<board>N<node>_<D|M>" or "IBETH<board>N<node>_<D|M>" (docs/ddi.md, "Calls").
IBDDIRET parse_name(std::string_view name, int& kind) {
  std::size_t prefix = 0;
  if (name.substr(0, 5) == "IBETH") {
    prefix = 5;
  } else if (name.substr(0, 3) == "IBB") {
    prefix = 3;
  } else {
    return ERR_INVLD_PARAM;
  }
  const std::size_t n = name.find('N', prefix);
  const std::size_t u = name.find('_', prefix);
  if (n == std::string_view::npos || u == std::string_view::npos || u < n || u + 2 != name.size()) {
    return ERR_INVLD_PARAM;
  }
  const std::string_view board = name.substr(prefix, n - prefix);
  const std::string_view node = name.substr(n + 1, u - n - 1);
  if (!all_digits(board) || !all_digits(node)) return ERR_INVLD_PARAM;
  if (!is_one(board)) return ERR_INVLD_BOARD_NUM;
  if (!is_one(node)) return ERR_INVLD_NODE_NUM;
  if (name[u + 1] == 'D') {
    kind = DDI_NODE_DATA;
  } else if (name[u + 1] == 'M') {
    kind = DDI_NODE_MAILBOX;
  } else {
    return ERR_INVLD_NODE_NUM;
  }
  return ERR_OK;
}

// The node of `h` if it is open and of `kind`, with the permission `need` (0: any).
IBDDIRET find(Driver& d, IBDDIHND h, int kind, int need) {
  const auto it = d.nodes.find(h);
  if (it == d.nodes.end() || it->second.kind != kind || !d.board) return ERR_INVLD_NODE_HD;
  if ((it->second.perm & need) != need) return ERR_INVLD_PERM;
  return ERR_OK;
}

IBDDIRET check_access(const T_DDI_DTI_ACCESS* a) {
  if (a == nullptr || a->data == nullptr || a->length == 0) return ERR_INVLD_PARAM;
  static constexpr std::uint16_t kUnit[] = {2, 4, 1, 8};  // DDI_WORD, DDI_LWORD, DDI_BYTE, DDI_64BIT
  if (a->dataCons > DDI_64BIT) return ERR_INVLD_DATA_CONS;
  const std::uint16_t unit = kUnit[a->dataCons];
  if (a->address % unit != 0 || a->length % unit != 0) return ERR_INVLD_DATA_CONS;
  if (static_cast<unsigned>(a->address) + a->length > DDI_IMAGE_BYTES) return ERR_AREA_EXCDED;
  return ERR_OK;
}

IBDDIRET read_locked(Board& b, T_DDI_DTI_ACCESS* a) {
  if (b.mode() == ibs::ddi::Mode::stepped) {
    b.step();
    b.note_read_cycle();
  }
  if (b.firmware().sysfail()) return ERR_IBS_SYSFAIL;
  if (!b.firmware().running()) return ERR_IB_STOPPED;
  b.firmware().read_inputs(a->address, {a->data, a->length});
  return ERR_OK;
}

IBDDIRET write_locked(Board& b, const T_DDI_DTI_ACCESS* a) {
  if (b.firmware().sysfail()) return ERR_IBS_SYSFAIL;
  b.firmware().write_outputs(a->address, {a->data, a->length});
  return ERR_OK;
}

// A DTI call: the node and its permission, the access(es) checked, then `f` with the board held.
template <typename F>
IBDDIRET data_call(IBDDIHND handle, int need, std::initializer_list<const T_DDI_DTI_ACCESS*> accesses, F&& f) {
  Driver& d = driver();
  const std::lock_guard<std::mutex> lock(d.mutex);
  if (const IBDDIRET r = find(d, handle, DDI_NODE_DATA, need); r != ERR_OK) return r;
  for (const T_DDI_DTI_ACCESS* a : accesses) {
    if (const IBDDIRET r = check_access(a); r != ERR_OK) return r;
  }
  const std::lock_guard<std::mutex> board(d.board->mutex());
  return f(*d.board);
}

}  // namespace

extern "C" {

IBDDIRET DDI_DevOpenNode(const char* name, int16_t perm, IBDDIHND* handle) {
  if (name == nullptr || handle == nullptr || perm < DDI_READ || perm > DDI_RW) return ERR_INVLD_PARAM;
  int kind = 0;
  if (const IBDDIRET r = parse_name(name, kind); r != ERR_OK) return r;
  Driver& d = driver();
  const std::lock_guard<std::mutex> lock(d.mutex);
  if (!d.board) {
    try {
      d.board = std::make_unique<Board>(ibs::ddi::options_from_environment());
    } catch (const std::exception& e) {
      // The application cannot be told more through the DDI: the reason goes to stderr.
      std::fprintf(stderr, "ibs-ddi: the board cannot start: %s\n", e.what());
      return ERR_NODE_NOT_READY;
    }
  }
  *handle = d.next++;
  d.nodes[*handle] = Node{kind, perm};
  return ERR_OK;
}

IBDDIRET DDI_DevCloseNode(IBDDIHND handle) {
  Driver& d = driver();
  std::unique_ptr<Board> gone;
  {
    const std::lock_guard<std::mutex> lock(d.mutex);
    if (d.nodes.erase(handle) == 0) return ERR_INVLD_NODE_HD;
    if (d.nodes.empty()) gone = std::move(d.board);
  }
  return ERR_OK;  // `gone` stops the board's thread outside the lock
}

IBDDIRET DDI_DTI_ReadData(IBDDIHND handle, T_DDI_DTI_ACCESS* access) {
  return data_call(handle, DDI_READ, {access}, [&](Board& b) { return read_locked(b, access); });
}

IBDDIRET DDI_DTI_WriteData(IBDDIHND handle, T_DDI_DTI_ACCESS* access) {
  return data_call(handle, DDI_WRITE, {access}, [&](Board& b) { return write_locked(b, access); });
}

IBDDIRET DDI_DTI_ReadWriteData(IBDDIHND handle, T_DDI_DTI_ACCESS* write, T_DDI_DTI_ACCESS* read) {
  // Both in one hold of the board: the outputs and the inputs of the same cycle.
  return data_call(handle, DDI_RW, {write, read}, [&](Board& b) {
    const IBDDIRET r = write_locked(b, write);
    return r != ERR_OK ? r : read_locked(b, read);
  });
}

IBDDIRET DDI_MXI_SndMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access) {
  Driver& d = driver();
  const std::lock_guard<std::mutex> lock(d.mutex);
  if (const IBDDIRET r = find(d, handle, DDI_NODE_MAILBOX, DDI_WRITE); r != ERR_OK) return r;
  if (access == nullptr || access->msgBlk == nullptr) return ERR_INVLD_PARAM;
  if (access->msgLength > DDI_MAX_MESSAGE) return ERR_MSG_TO_LONG;
  if (access->msgLength < 4 || access->msgLength % 2 != 0) return ERR_INVLD_PARAM;
  std::vector<std::uint16_t> words(access->msgLength / 2U);
  for (std::size_t k = 0; k < words.size(); ++k) {
    words[k] = static_cast<std::uint16_t>((access->msgBlk[2 * k] << 8U) | access->msgBlk[2 * k + 1]);
  }
  if (words[1] != words.size() - 2) return ERR_INVLD_PARAM;  // the parameter count says otherwise
  const std::lock_guard<std::mutex> board(d.board->mutex());
  if (d.board->firmware().sysfail()) return ERR_IBS_SYSFAIL;
  if (d.board->firmware().request(words, access->DDIUserID, d.board->now()) == ibs::ddi::Accept::mailbox_full) {
    return ERR_NO_MORE_MBX;
  }
  return ERR_OK;
}

IBDDIRET DDI_MXI_RcvMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access) {
  Driver& d = driver();
  const std::lock_guard<std::mutex> lock(d.mutex);
  if (const IBDDIRET r = find(d, handle, DDI_NODE_MAILBOX, DDI_READ); r != ERR_OK) return r;
  if (access == nullptr || access->msgBlk == nullptr) return ERR_INVLD_PARAM;
  const std::lock_guard<std::mutex> board(d.board->mutex());
  Board& b = *d.board;
  // Stepped: an empty mailbox runs a bus cycle, unless a DTI read has run one since the last
  // empty receive (one cycle a pass of a loop that reads the data, then empties the mailbox).
  if (b.firmware().front() == nullptr && b.mode() == ibs::ddi::Mode::stepped && !b.take_read_cycle()) b.step();
  const ibs::ddi::Message* m = b.firmware().front();
  if (m == nullptr) return b.firmware().sysfail() ? ERR_IBS_SYSFAIL : ERR_NO_MSG;
  if (m->bytes.size() > access->msgLength) return ERR_MSG_TO_LONG;  // kept for a larger buffer
  std::memcpy(access->msgBlk, m->bytes.data(), m->bytes.size());
  access->msgLength = static_cast<std::uint16_t>(m->bytes.size());
  access->msgType = m->type;
  access->DDIUserID = m->user_id;
  b.firmware().pop();
  return ERR_OK;
}

IBDDIRET DDI_GetInfo(IBDDIHND handle, T_DDI_INFO* info) {
  Driver& d = driver();
  const std::lock_guard<std::mutex> lock(d.mutex);
  const auto it = d.nodes.find(handle);
  if (it == d.nodes.end() || !d.board) return ERR_INVLD_NODE_HD;
  if (info == nullptr) return ERR_INVLD_PARAM;
  const std::lock_guard<std::mutex> board(d.board->mutex());
  const Board& b = *d.board;
  *info = T_DDI_INFO{};
  std::snprintf(info->driverName, sizeof info->driverName, "%s", "ibs virtual INTERBUS board");
  info->driverVersion = 0x0100;
  info->boardNumber = 1;
  info->nodeType = static_cast<std::uint16_t>(it->second.kind);
  info->permission = static_cast<std::uint16_t>(it->second.perm);
  info->deviceCount = static_cast<std::uint16_t>(b.config().devices.size());
  info->inputBytes = static_cast<std::uint16_t>(b.config().in_words * 2);
  info->outputBytes = static_cast<std::uint16_t>(b.config().out_words * 2);
  info->mode = b.mode() == ibs::ddi::Mode::stepped ? DDI_MODE_STEPPED : DDI_MODE_REALTIME;
  info->cycleTimeUs =
      static_cast<std::uint32_t>(std::chrono::duration_cast<std::chrono::microseconds>(b.cycle_time()).count());
  info->cycles = static_cast<std::uint32_t>(d.board->firmware().cycles());
  return ERR_OK;
}

// The legacy headers' register reading (ibs_util.h): a register, not a service -- no message and
// no bus cycle, whatever the mode.
IBDDIRET GetIBSDiagnosticEx(IBDDIHND handle, T_IBS_DIAG_EX* info) {
  Driver& d = driver();
  const std::lock_guard<std::mutex> lock(d.mutex);
  if (d.nodes.find(handle) == d.nodes.end() || !d.board) return ERR_INVLD_NODE_HD;
  if (info == nullptr) return ERR_INVLD_PARAM;
  const std::lock_guard<std::mutex> board(d.board->mutex());
  info->state = d.board->firmware().diag_status();
  info->diagPara = d.board->firmware().diag_parameter();
  info->addInfo = 0;
  return ERR_OK;
}

IBDDIRET GetIBSDiagnostic(IBDDIHND handle, T_IBS_DIAG* info) {
  if (info == nullptr) {
    // The handle is checked first, as by the Ex form.
    T_IBS_DIAG_EX probe{};
    const IBDDIRET r = GetIBSDiagnosticEx(handle, &probe);
    return r == ERR_OK ? ERR_INVLD_PARAM : r;
  }
  T_IBS_DIAG_EX ex{};
  const IBDDIRET r = GetIBSDiagnosticEx(handle, &ex);
  if (r == ERR_OK) {
    info->state = ex.state;
    info->diagPara = ex.diagPara;
  }
  return r;
}

}  // extern "C"

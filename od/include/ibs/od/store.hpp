// The one store of a drive's parameter values, behind its dictionary: per entry a RAM value (what
// every bus reads), a kept copy (EEPROM or flash: what power-on brings back), the factory default
// (the entry's, or an overlay's) and a spare (the data set a download brings back or takes in,
// LUSTBUS manual 11.4); per text entry the same for its text. It models what drive::ParameterStore,
// pcp::ParameterStore, the CDA3000's current_/saved_/pending_/name_ and the DFS-1's values_ do:
// a write by storage kind, power-on, a save, the factory defaults, the download's old data set.
//
// Construction allocates (and checks the overlay); nothing else does, nothing throws. ram() and
// set() are inline: one indexed load or store, on every request and every sample of every drive.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "ibs/base/error.hpp"
#include "ibs/od/dictionary.hpp"

namespace ibs::od {

class Store {
 public:
  // The overlay's numbers must be entries of the dictionary, each once, not text, each value a
  // number of the entry's type within its min..max (ErrorCode::table_*; the message names it).
  [[nodiscard]] static Error validate(const Dictionary& d,
                                      std::span<const DefaultOverride> defaults = {});
  // Every value and text at its factory default, RAM and kept copy (a factory-fresh drive). An
  // overlay validate() refuses throws std::invalid_argument, or, in the embedded build, aborts.
  // `d` must outlive the store.
  explicit Store(const Dictionary& d, std::span<const DefaultOverride> defaults = {});

  [[nodiscard]] const Dictionary& dictionary() const { return *dict_; }
  [[nodiscard]] std::size_t size() const { return cells_.size(); }

  // ---- values by slot (a slot of the dictionary: kNoSlot is the caller's to refuse) -----------
  [[nodiscard]] Raw ram(Slot s) const { return cells_[s].ram; }
  [[nodiscard]] Raw kept(Slot s) const { return cells_[s].kept; }
  [[nodiscard]] Raw default_raw(Slot s) const { return factory_[s]; }
  // The drive's own value (a reading, a command that reverts): RAM only, no check.
  void set(Slot s, Raw r) { cells_[s].ram = r; }
  // The kept copy alone: a background EEPROM save that has ended (the MC6000's 15 ms a byte).
  void keep(Slot s, Raw r) { cells_[s].kept = r; }
  // Whether the entry is a text (Type::string): its value is text(), not ram().
  [[nodiscard]] bool is_text(Slot s) const { return !texts_.empty() && texts_[s].text; }
  // RAM and the kept copy: a configured drive, a keypad, a tool's preset.
  void preset(Slot s, Raw r) { cells_[s] = {r, r}; }
  // A value transfer that passed the checks (`r` canonical, fit() ok), by the entry's storage:
  // RAM always; the kept copy too for eeprom, and for eeprom_ram while the power stage is disabled
  // (INTERBUS manual 4.1.3.3); flash waits for save(). Returns whether the kept copy changed.
  bool write(Slot s, Raw r, bool power_stage_enabled) {
    return write(s, r, (*dict_)[s].storage, power_stage_enabled);
  }
  // The same, with the entry's storage the caller has at hand.
  bool write(Slot s, Raw r, Storage storage, bool power_stage_enabled) {
    Cell& c = cells_[s];
    c.ram = r;
    if (storage == Storage::eeprom || (storage == Storage::eeprom_ram && !power_stage_enabled)) {
      const bool changed = c.kept != r;
      c.kept = r;
      return changed;
    }
    return false;
  }

  // By number, for configuration and reports: nullopt / false for a number the dictionary lacks.
  [[nodiscard]] std::optional<Raw> ram_of(std::uint16_t number) const;
  [[nodiscard]] std::optional<Raw> kept_of(std::uint16_t number) const;
  bool set_of(std::uint16_t number, Raw r);

  // ---- the drive's moments ----------------------------------------------------------------
  // Power-on: every kept kind (eeprom, eeprom_ram, flash) from its kept copy; RAM control values
  // to their defaults but those with attr::kNoInit (LUSTBUS manual 11.2.1), which keep their RAM; RAM
  // actual values to their defaults. Texts alike.
  void power_on();
  // A save (150-SAVE, CANLust manual 3.5.1): the kept copy of every entry of storage `kind` from RAM.
  void save(Storage kind);
  // The factory defaults (PROG = 1, LUSTBUS manual 10 exception 1; CANLust manual p. 13): every RAM value and
  // text, and the kept copy of all but flash entries, which a save keeps (the CDA3000's PROG
  // leaves its flash alone until 150-SAVE).
  void factory_defaults();

  // ---- texts (Type::string entries) -------------------------------------------------------
  // The RAM text / the kept text; empty for an entry that is no text.
  [[nodiscard]] std::string_view text(Slot s) const;
  [[nodiscard]] std::string_view kept_text(Slot s) const;
  // false, and nothing changed, for an entry that is no text, a length outside its min..max or a
  // NUL byte. set_text: RAM only; write_text: by storage kind, as write().
  bool set_text(Slot s, std::string_view t);
  bool write_text(Slot s, std::string_view t, bool power_stage_enabled);

  // ---- the data set of a download (LUSTBUS manual 11.4; the CDA3000's D39) -------------------------
  // The spare takes every RAM value: the old data set (restored if the new one is refused), or
  // the new one being received (taken if it is valid).
  void snapshot();
  [[nodiscard]] Raw spare(Slot s) const { return spare_[s]; }
  void set_spare(Slot s, Raw r) { spare_[s] = r; }
  // RAM from the spare, for every entry in the data set (Entry::in_data_set).
  void restore_data_set();
  // The kept copy from RAM, for every kept entry in the data set: "put in EEPROM" (11.4).
  void keep_data_set();

 private:
  struct Cell {
    Raw ram = 0;
    Raw kept = 0;
  };
  struct TextCell {
    std::uint32_t offset =
        0;  // of the RAM text in chars_; the kept text follows at offset + capacity
    std::uint16_t capacity = 0;
    std::uint16_t ram_size = 0;
    std::uint16_t kept_size = 0;
    std::uint16_t factory_size = 0;  // the factory text follows the kept text
    bool text = false;
  };
  void put_text(TextCell& c, std::size_t which, std::string_view t);
  [[nodiscard]] bool text_ok(Slot s, std::string_view t) const;

  const Dictionary* dict_;
  std::vector<Cell> cells_;
  std::vector<Raw> factory_;
  std::vector<Raw> spare_;
  std::vector<TextCell> texts_;  // by slot; empty when the dictionary has no text
  std::vector<char> chars_;
};

}  // namespace ibs::od

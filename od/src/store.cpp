#include "ibs/od/store.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ibs::od {

namespace {

std::string label(const Entry& e) {
  return std::to_string(e.number) + "-" + std::string(e.name);
}

const Dictionary& checked(const Dictionary& d, std::span<const DefaultOverride> defaults) {
  ibs::detail::require<std::invalid_argument>(Store::validate(d, defaults));
  return d;
}

}  // namespace

Error Store::validate(const Dictionary& d, std::span<const DefaultOverride> defaults) {
  for (std::size_t i = 0; i < defaults.size(); ++i) {
    const DefaultOverride& o = defaults[i];
    const std::string who =
        "default override " + std::to_string(i) + " (parameter " + std::to_string(o.number) + ")";
    const Entry* e = d.find(o.number);
    if (e == nullptr)
      return {ErrorCode::table_number_out_of_range, who + ": the dictionary has no such entry"};
    for (std::size_t j = 0; j < i; ++j) {
      if (defaults[j].number == o.number)
        return {ErrorCode::table_number_repeated, who + ": number given twice"};
    }
    if (e->is_text())
      return {ErrorCode::table_limits_outside_type, who + ": " + label(*e) + " is a text"};
    if (!fits(e->type, o.value) || fit(*e, raw(e->type, o.value)) != Fit::ok) {
      return {ErrorCode::table_default_outside_limits, who + ": " + std::to_string(o.value) +
                                                           " is no value of " + label(*e) +
                                                           " (min..max, type, choices)"};
    }
  }
  return {};
}

Store::Store(const Dictionary& d, std::span<const DefaultOverride> defaults)
    : dict_(&checked(d, defaults)), cells_(d.size()), factory_(d.size()), spare_(d.size()) {
  const auto entries = d.entries();
  std::size_t chars = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    factory_[i] = entries[i].default_raw();
    if (entries[i].is_text()) chars += 3 * static_cast<std::size_t>(entries[i].max);
  }
  for (const DefaultOverride& o : defaults)
    factory_[d.slot(o.number)] = raw(d.find(o.number)->type, o.value);
  if (chars > 0 ||
      std::any_of(entries.begin(), entries.end(), [](const Entry& e) { return e.is_text(); })) {
    texts_.resize(entries.size());
    chars_.resize(chars);
    std::uint32_t offset = 0;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (!entries[i].is_text()) continue;
      TextCell& c = texts_[i];
      c.text = true;
      c.offset = offset;
      c.capacity = static_cast<std::uint16_t>(entries[i].max);
      offset += 3U * c.capacity;
      put_text(c, 2, entries[i].default_text);
    }
  }
  for (std::size_t i = 0; i < entries.size(); ++i) cells_[i] = {factory_[i], factory_[i]};
  for (std::size_t i = 0; i < texts_.size(); ++i) {
    if (!entries[i].is_text()) continue;
    const std::string_view f(chars_.data() + texts_[i].offset + 2U * texts_[i].capacity,
                             texts_[i].factory_size);
    put_text(texts_[i], 0, f);
    put_text(texts_[i], 1, f);
  }
  spare_ = factory_;
}

void Store::put_text(TextCell& c, std::size_t which, std::string_view t) {
  std::copy(t.begin(), t.end(),
            chars_.begin() + static_cast<std::ptrdiff_t>(c.offset + which * c.capacity));
  const auto n = static_cast<std::uint16_t>(t.size());
  (which == 0 ? c.ram_size : which == 1 ? c.kept_size : c.factory_size) = n;
}

std::optional<Raw> Store::ram_of(std::uint16_t number) const {
  const Slot s = dict_->slot(number);
  if (s == kNoSlot) return std::nullopt;
  return cells_[s].ram;
}

std::optional<Raw> Store::kept_of(std::uint16_t number) const {
  const Slot s = dict_->slot(number);
  if (s == kNoSlot) return std::nullopt;
  return cells_[s].kept;
}

bool Store::set_of(std::uint16_t number, Raw r) {
  const Slot s = dict_->slot(number);
  if (s == kNoSlot) return false;
  cells_[s].ram = r;
  return true;
}

void Store::power_on() {
  const auto entries = dict_->entries();
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const Entry& e = entries[i];
    if (e.kept()) {
      cells_[i].ram = cells_[i].kept;
    } else if (!(e.storage == Storage::ram_control && e.has(attr::kNoInit))) {
      cells_[i].ram = factory_[i];
    }
    if (!texts_.empty() && e.is_text()) {
      TextCell& c = texts_[i];
      const std::size_t from = e.kept() ? 1 : 2;
      const std::uint16_t n = from == 1 ? c.kept_size : c.factory_size;
      if (e.kept() || !(e.storage == Storage::ram_control && e.has(attr::kNoInit))) {
        std::copy_n(chars_.begin() + static_cast<std::ptrdiff_t>(c.offset + from * c.capacity), n,
                    chars_.begin() + static_cast<std::ptrdiff_t>(c.offset));
        c.ram_size = n;
      }
    }
  }
}

void Store::save(Storage kind) {
  const auto entries = dict_->entries();
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (entries[i].storage != kind) continue;
    cells_[i].kept = cells_[i].ram;
    if (!texts_.empty() && entries[i].is_text()) {
      TextCell& c = texts_[i];
      std::copy_n(chars_.begin() + static_cast<std::ptrdiff_t>(c.offset), c.ram_size,
                  chars_.begin() + static_cast<std::ptrdiff_t>(c.offset + c.capacity));
      c.kept_size = c.ram_size;
    }
  }
}

void Store::factory_defaults() {
  const auto entries = dict_->entries();
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const bool keep_kept = entries[i].storage == Storage::flash;
    cells_[i].ram = factory_[i];
    if (!keep_kept) cells_[i].kept = factory_[i];
    if (!texts_.empty() && entries[i].is_text()) {
      TextCell& c = texts_[i];
      const auto factory = chars_.begin() + static_cast<std::ptrdiff_t>(c.offset + 2U * c.capacity);
      std::copy_n(factory, c.factory_size, chars_.begin() + static_cast<std::ptrdiff_t>(c.offset));
      c.ram_size = c.factory_size;
      if (!keep_kept) {
        std::copy_n(factory, c.factory_size,
                    chars_.begin() + static_cast<std::ptrdiff_t>(c.offset + c.capacity));
        c.kept_size = c.factory_size;
      }
    }
  }
}

std::string_view Store::text(Slot s) const {
  if (!is_text(s)) return {};
  return {chars_.data() + texts_[s].offset, texts_[s].ram_size};
}

std::string_view Store::kept_text(Slot s) const {
  if (!is_text(s)) return {};
  return {chars_.data() + texts_[s].offset + texts_[s].capacity, texts_[s].kept_size};
}

bool Store::text_ok(Slot s, std::string_view t) const {
  const Entry& e = (*dict_)[s];
  const auto n = static_cast<std::int64_t>(t.size());
  return e.is_text() && n >= e.min && n <= e.max && t.find('\0') == std::string_view::npos;
}

bool Store::set_text(Slot s, std::string_view t) {
  if (!text_ok(s, t)) return false;
  put_text(texts_[s], 0, t);
  return true;
}

bool Store::write_text(Slot s, std::string_view t, bool power_stage_enabled) {
  if (!text_ok(s, t)) return false;
  put_text(texts_[s], 0, t);
  const Storage k = (*dict_)[s].storage;
  if (k == Storage::eeprom || (k == Storage::eeprom_ram && !power_stage_enabled))
    put_text(texts_[s], 1, t);
  return true;
}

void Store::snapshot() {
  for (std::size_t i = 0; i < cells_.size(); ++i) spare_[i] = cells_[i].ram;
}

void Store::restore_data_set() {
  const auto entries = dict_->entries();
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (entries[i].in_data_set) cells_[i].ram = spare_[i];
  }
}

void Store::keep_data_set() {
  const auto entries = dict_->entries();
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (entries[i].in_data_set && entries[i].kept()) cells_[i].kept = cells_[i].ram;
  }
}

}  // namespace ibs::od
